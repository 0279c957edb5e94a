// Ply material: range checks, the energy bound, JSON (text / file) loading with field-naming
// errors, and the per-field overrides of the render options.
#include "knit/ply_material.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "knit/error.hpp"
#include "material_overrides.hpp"

namespace knit {
namespace {

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

void checkRange(const std::string& where, const char* field, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi)
        throw Error(where + ": '" + field + "' = " + fmt(v) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
}

void checkColor(const std::string& where, const char* field, const Rgb& c, double lo, double hi) {
    static const char* names[3] = {"r", "g", "b"};
    for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(c[k]) || c[k] < lo || c[k] > hi)
            throw Error(where + ": '" + field + "' channel " + names[k] + " = " + fmt(c[k]) + " is out of range [" +
                        fmt(lo) + ", " + fmt(hi) + "]");
    }
}

double readNumber(const nlohmann::json& v, const std::string& where, const std::string& key) {
    if (!v.is_number()) throw Error(where + ": field '" + key + "' must be a number");
    return v.get<double>();
}

Rgb readColor(const nlohmann::json& v, const std::string& where, const std::string& key) {
    if (v.is_number()) return Rgb(v.get<double>());
    if (v.is_array() && v.size() == 3 && v[0].is_number() && v[1].is_number() && v[2].is_number())
        return Rgb(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    throw Error(where + ": field '" + key + "' must be a number or an array [r, g, b] of numbers");
}

int readInt(const nlohmann::json& v, const std::string& where, const std::string& key) {
    if (!v.is_number_integer()) throw Error(where + ": field '" + key + "' must be an integer");
    const long long x = v.get<long long>();
    if (x < -1000000000LL || x > 1000000000LL)
        throw Error(where + ": field '" + key + "' = " + std::to_string(x) + " is out of range");
    return static_cast<int>(x);
}

}  // namespace

void validateMaterial(const PlyMaterial& m, const std::string& where) {
    // Step 1: each parameter inside its physical / practical range.
    checkRange(where, "eta", m.eta, 1.0, 3.0);
    checkRange(where, "alphaAlong", m.alphaAlong, 0.01, 1.0);
    checkRange(where, "alphaAcross", m.alphaAcross, 0.01, 1.0);
    checkRange(where, "alphaTT", m.alphaTT, 0.01, 1.0);
    checkColor(where, "kR", m.kR, 0.0, 1.0);
    checkColor(where, "kTT", m.kTT, 0.0, 1.0);
    checkColor(where, "bodyAlbedo", m.bodyAlbedo, 0.0, 1.0);
    checkRange(where, "reflectFraction", m.reflectFraction, 0.0, 1.0);
    checkRange(where, "fiberCount", m.fiberCount, 3, 1000);
    checkRange(where, "fiberTwist", m.fiberTwist, -50.0, 50.0);
    checkRange(where, "fiberShadowFloor", m.fiberShadowFloor, 0.0, 1.0);
    checkRange(where, "plyShadowFloor", m.plyShadowFloor, 0.0, 1.0);
    checkRange(where, "tableSize", m.tableSize, 16, 65536);
    checkRange(where, "aoRays", m.aoRays, 16, 100000);
    // Step 2: energy bound per channel, max(kR, kTT) + rho_B <= 1 (so the albedo is <= 1).
    static const char* names[3] = {"r", "g", "b"};
    for (int k = 0; k < 3; ++k) {
        const double spec = std::max(m.kR[k], m.kTT[k]);
        if (spec + m.bodyAlbedo[k] > 1.0 + 1e-12)
            throw Error(where + ": energy bound violated in channel " + names[k] + ": max(kR, kTT) = " + fmt(spec) +
                        " plus bodyAlbedo = " + fmt(m.bodyAlbedo[k]) + " is " + fmt(spec + m.bodyAlbedo[k]) +
                        " > 1 (the BSDF would create energy)");
    }
}

namespace {

// Fields of `j` override `base`; unknown fields and wrong types are errors naming the field.
PlyMaterial materialFromJson(const nlohmann::json& j, const PlyMaterial& base, const std::string& where) {
    if (!j.is_object()) throw Error(where + ": a material must be a JSON object");
    PlyMaterial m = base;
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string& key = it.key();
        const nlohmann::json& v = it.value();
        if (key == "eta") m.eta = readNumber(v, where, key);
        else if (key == "alphaAlong") m.alphaAlong = readNumber(v, where, key);
        else if (key == "alphaAcross") m.alphaAcross = readNumber(v, where, key);
        else if (key == "alphaTT") m.alphaTT = readNumber(v, where, key);
        else if (key == "kR") m.kR = readColor(v, where, key);
        else if (key == "kTT") m.kTT = readColor(v, where, key);
        else if (key == "bodyAlbedo") m.bodyAlbedo = readColor(v, where, key);
        else if (key == "reflectFraction") m.reflectFraction = readNumber(v, where, key);
        else if (key == "fiberDetail") {
            if (!v.is_boolean()) throw Error(where + ": field 'fiberDetail' must be true or false");
            m.fiberDetail = v.get<bool>();
        } else if (key == "fiberCount") m.fiberCount = readInt(v, where, key);
        else if (key == "fiberTwist") m.fiberTwist = readNumber(v, where, key);
        else if (key == "fiberShadowFloor") m.fiberShadowFloor = readNumber(v, where, key);
        else if (key == "plyShadowFloor") m.plyShadowFloor = readNumber(v, where, key);
        else if (key == "tableSize") m.tableSize = readInt(v, where, key);
        else if (key == "aoRays") m.aoRays = readInt(v, where, key);
        else throw Error(where + ": unknown field '" + key + "'");
    }
    validateMaterial(m, where);
    return m;
}

// The first JSON value of `in` (what follows it is not read) as a material; read errors surface
// as exceptions of the stream or the parser.
PlyMaterial parseMaterialStream(std::istream& in, const std::string& where, const PlyMaterial& base) {
    nlohmann::json j;
    try {
        in >> j;
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + ": invalid JSON: " + e.what());
    } catch (const std::exception& e) {
        throw Error(where + ": cannot be read: " + e.what());
    }
    return materialFromJson(j, base, where);
}

}  // namespace

PlyMaterial parseMaterialJson(const std::string& text, const std::string& source, const PlyMaterial& base) {
    std::istringstream in(text);
    return parseMaterialStream(in, source, base);
}

PlyMaterial loadMaterialFile(const std::string& path, const PlyMaterial& base) {
    // Step 1: a readable regular file (a folder opens as a stream on Linux, then fails to read).
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error("material file '" + path + "': is a directory, not a file");
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
        throw Error("material file '" + path + "': is not a regular file (a device, FIFO or socket)");
    std::ifstream in(path);
    if (!in) throw Error("material file '" + path + "': cannot be opened");
    // Step 2: parse.
    return parseMaterialStream(in, "material file '" + path + "'", base);
}

PlyMaterial applyMaterialOverrides(const std::map<std::string, std::vector<double>>& overrides, const PlyMaterial& base,
                                   const std::string& where) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [key, values] : overrides) {
        if (key == "fiberDetail") j[key] = !values.empty() && values[0] != 0;
        else if (key == "fiberCount" || key == "tableSize" || key == "aoRays")
            j[key] = static_cast<long long>(std::lround(values.at(0)));
        else if (values.size() == 1) j[key] = values[0];
        else j[key] = values;
    }
    return materialFromJson(j, base, where);
}

std::string materialJsonText(const PlyMaterial& m) {
    auto rgb = [](const Rgb& c) { return nlohmann::json::array({c.x, c.y, c.z}); };
    const nlohmann::json j = {{"eta", m.eta},
                              {"alphaAlong", m.alphaAlong},
                              {"alphaAcross", m.alphaAcross},
                              {"kR", rgb(m.kR)},
                              {"alphaTT", m.alphaTT},
                              {"kTT", rgb(m.kTT)},
                              {"bodyAlbedo", rgb(m.bodyAlbedo)},
                              {"reflectFraction", m.reflectFraction},
                              {"fiberDetail", m.fiberDetail},
                              {"fiberCount", m.fiberCount},
                              {"fiberTwist", m.fiberTwist},
                              {"fiberShadowFloor", m.fiberShadowFloor},
                              {"plyShadowFloor", m.plyShadowFloor},
                              {"tableSize", m.tableSize},
                              {"aoRays", m.aoRays}};
    return j.dump();
}

Rgb yarnBodyAlbedo(const PlyMaterial& material, const glm::vec3& colour) {
    const double brightest = std::max({material.bodyAlbedo.x, material.bodyAlbedo.y, material.bodyAlbedo.z});
    return Rgb(colour) * brightest;
}

}  // namespace knit
