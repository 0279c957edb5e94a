// Which material fields the fit may change, their bounds, and the map between a material and the
// optimiser's unit box (body albedo as a share of the energy max(kR, kTT) leaves).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "knit/error.hpp"
#include "knit/fit.hpp"

namespace knit {
namespace {

// A fittable field: its name, the valid range (validateMaterial's) and its default bounds.
struct FieldInfo {
    const char* name;
    double validLo, validHi, lower, upper;
};

const FieldInfo kFields[] = {
    {"kR", 0, 1, 0, 0.95},
    {"kTT", 0, 1, 0, 0.95},
    {"body-albedo", 0, 1, 0, 1},
    {"reflect-fraction", 0, 1, 0, 1},
    {"alpha-along", 0.01, 1, 0.05, 1},
    {"alpha-across", 0.01, 1, 0.05, 1},
    {"alpha-tt", 0.01, 1, 0.05, 1},
    {"fiber-shadow-floor", 0, 1, 0, 1},
    {"ply-shadow-floor", 0, 1, 0, 1},
    {"fiber-twist", -50, 50, -5, 5},
};

const FieldInfo* findField(const std::string& name) {
    for (const FieldInfo& f : kFields)
        if (name == f.name) return &f;
    return nullptr;
}

std::string knownNames() {
    std::string s;
    for (const FieldInfo& f : kFields) s += (s.empty() ? "" : ", ") + std::string(f.name);
    return s;
}

std::string fmt(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

// Scalar access to the fields (body albedo is handled per channel by FitSpace).
template <class Material>  // PlyMaterial or const PlyMaterial
auto* scalarField(Material& m, const std::string& name) {
    using Field = decltype(&m.reflectFraction);
    if (name == "reflect-fraction") return &m.reflectFraction;
    if (name == "alpha-along") return &m.alphaAlong;
    if (name == "alpha-across") return &m.alphaAcross;
    if (name == "alpha-tt") return &m.alphaTT;
    if (name == "fiber-shadow-floor") return &m.fiberShadowFloor;
    if (name == "ply-shadow-floor") return &m.plyShadowFloor;
    if (name == "fiber-twist") return &m.fiberTwist;
    return Field{nullptr};
}

double lerp(const FitParameter& p, double x) { return p.lower + std::clamp(x, 0.0, 1.0) * (p.upper - p.lower); }
double unlerp(const FitParameter& p, double v) {
    return p.upper > p.lower ? std::clamp((v - p.lower) / (p.upper - p.lower), 0.0, 1.0) : 0.0;
}

const FitParameter* findParam(const std::vector<FitParameter>& params, const char* name) {
    for (const FitParameter& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

}  // namespace

FitParameter fitParameter(const std::string& name, const std::string& option) {
    const FieldInfo* f = findField(name);
    if (!f) throw Error(option + ": unknown material field '" + name + "' (fittable: " + knownNames() + ")");
    return {f->name, f->lower, f->upper};
}

std::vector<FitParameter> parseFitList(const std::string& list, const std::string& option) {
    std::vector<FitParameter> params;
    std::stringstream in(list);
    std::string name;
    while (std::getline(in, name, ',')) {
        if (name.empty()) throw Error(option + ": empty field name in '" + list + "'");
        if (findParam(params, name.c_str())) throw Error(option + ": field '" + name + "' is listed twice");
        params.push_back(fitParameter(name, option));
    }
    if (params.empty()) throw Error(option + ": no field to fit");
    return params;
}

void applyFitBound(std::vector<FitParameter>& params, const std::string& bound, const std::string& option) {
    const size_t eq = bound.find('='), colon = bound.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
        throw Error(option + " '" + bound + "': expected NAME=LO:HI (e.g. kR=0.1:0.6)");
    const std::string name = bound.substr(0, eq);
    const FieldInfo* f = findField(name);
    if (!f) throw Error(option + " '" + bound + "': unknown material field '" + name + "'");
    auto it = std::find_if(params.begin(), params.end(), [&](const FitParameter& p) { return p.name == name; });
    if (it == params.end())
        throw Error(option + " '" + bound + "': '" + name + "' is not fitted (add it to the fitted parameters)");
    double lo = 0, hi = 0;
    try {
        size_t used = 0;
        lo = std::stod(bound.substr(eq + 1, colon - eq - 1), &used);
        hi = std::stod(bound.substr(colon + 1), &used);
    } catch (const std::exception&) {
        throw Error(option + " '" + bound + "': LO and HI must be numbers");
    }
    if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi))
        throw Error(option + " '" + bound + "': LO must not exceed HI");
    if (lo < f->validLo || hi > f->validHi)
        throw Error(option + " '" + bound + "': '" + name + "' must stay in [" + fmt(f->validLo) + ", " +
                    fmt(f->validHi) + "]");
    it->lower = lo, it->upper = hi;
}

FitSpace::FitSpace(std::vector<FitParameter> params, const PlyMaterial& base, const std::string& option)
    : params_(std::move(params)), base_(base) {
    for (const FitParameter& p : params_) dims_ += p.name == "body-albedo" ? 3 : 1;
    // The largest specular weight the box allows (fixed fields: the base's largest channel) and the
    // smallest body albedo: together they must keep max(kR, kTT) + body albedo <= 1.
    const FitParameter* kr = findParam(params_, "kR");
    const FitParameter* ktt = findParam(params_, "kTT");
    const FitParameter* body = findParam(params_, "body-albedo");
    const auto maxChannel = [](const Rgb& c) { return std::max({c.r, c.g, c.b}); };
    const double spec = std::max(kr ? kr->upper : maxChannel(base.kR), ktt ? ktt->upper : maxChannel(base.kTT));
    if (body) {
        if (spec + body->lower > 1)
            throw Error(option + ": kR/kTT up to " + fmt(spec) + " with body-albedo from " + fmt(body->lower) +
                        " break the energy bound max(kR, kTT) + body albedo <= 1 (lower the bounds)");
    } else {
        for (int c = 0; c < 3; ++c)
            if (spec + base.bodyAlbedo[c] > 1)
                throw Error(option + ": kR/kTT up to " + fmt(spec) + " with the fixed body albedo " +
                            fmt(base.bodyAlbedo[c]) + " break the energy bound max(kR, kTT) + body albedo <= 1");
    }
}

PlyMaterial FitSpace::material(const std::vector<double>& x) const {
    PlyMaterial m = base_;
    size_t i = 0;
    const FitParameter* body = nullptr;
    size_t bodyAt = 0;
    for (const FitParameter& p : params_) {
        if (p.name == "kR") m.kR = Rgb(lerp(p, x[i]));
        else if (p.name == "kTT") m.kTT = Rgb(lerp(p, x[i]));
        else if (p.name == "body-albedo") body = &p, bodyAt = i, i += 2;
        else *scalarField(m, p.name) = lerp(p, x[i]);
        ++i;
    }
    // Body albedo last: a share of what the specular weights leave, inside its own bounds.
    if (body)
        for (int c = 0; c < 3; ++c) {
            const double room = std::min(body->upper, 1 - std::max(m.kR[c], m.kTT[c]));
            m.bodyAlbedo[c] = body->lower + std::clamp(x[bodyAt + c], 0.0, 1.0) * std::max(room - body->lower, 0.0);
        }
    return m;
}

std::vector<double> FitSpace::vector(const PlyMaterial& m) const {
    std::vector<double> x;
    for (const FitParameter& p : params_) {
        if (p.name == "kR") x.push_back(unlerp(p, m.kR.g));
        else if (p.name == "kTT") x.push_back(unlerp(p, m.kTT.g));
        else if (p.name == "body-albedo")
            for (int c = 0; c < 3; ++c) {
                const double room = std::min(p.upper, 1 - std::max(m.kR[c], m.kTT[c]));
                x.push_back(room > p.lower ? std::clamp((m.bodyAlbedo[c] - p.lower) / (room - p.lower), 0.0, 1.0)
                                           : 0.0);
            }
        else x.push_back(unlerp(p, *scalarField(m, p.name)));
    }
    return x;
}

std::vector<double> FitSpace::values(const PlyMaterial& m) const {
    std::vector<double> v;
    for (const FitParameter& p : params_) {
        if (p.name == "kR") v.push_back(m.kR.g);
        else if (p.name == "kTT") v.push_back(m.kTT.g);
        else if (p.name == "body-albedo") v.insert(v.end(), {m.bodyAlbedo.r, m.bodyAlbedo.g, m.bodyAlbedo.b});
        else v.push_back(*scalarField(m, p.name));
    }
    return v;
}

std::vector<std::string> FitSpace::labels() const {
    std::vector<std::string> l;
    for (const FitParameter& p : params_) {
        if (p.name == "body-albedo") l.insert(l.end(), {"body-albedo.r", "body-albedo.g", "body-albedo.b"});
        else l.push_back(p.name);
    }
    return l;
}

}  // namespace knit
