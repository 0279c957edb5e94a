// Curves-only pattern form: open curves in one cell plus the period, as JSON.
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "knit/error.hpp"
#include "knit/pattern.hpp"
#include "io/special_file.hpp"

namespace knit {
namespace {

double finiteNumber(const nlohmann::json& j, const std::string& where, const std::string& source) {
    if (!j.is_number()) throw Error(source + ": " + where + " must be a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) throw Error(source + ": " + where + " is not finite");
    return v;
}

}  // namespace

CurveCell parseCurvesJson(const std::string& text, const std::string& source) {
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        // parse_error, but also out_of_range for numbers beyond double (1e400).
        throw Error(source + ": invalid JSON: " + e.what());
    }
    if (!doc.is_object()) throw Error(source + ": expected a JSON object with \"period\", \"radius\" and \"curves\"");
    for (const char* key : {"period", "radius", "curves"})
        if (!doc.contains(key)) throw Error(source + ": missing field \"" + std::string(key) + "\"");

    CurveCell cell;
    cell.name = source;
    const auto& period = doc["period"];
    if (!period.is_array() || period.size() != 2) throw Error(source + ": \"period\" must be [px, py]");
    cell.px = finiteNumber(period[0], "period[0]", source);
    cell.py = finiteNumber(period[1], "period[1]", source);
    cell.radius = finiteNumber(doc["radius"], "radius", source);
    if (!(cell.px > 0 && cell.py > 0)) throw Error(source + ": period must be positive");
    if (!(cell.radius > 0)) throw Error(source + ": radius must be positive");

    const auto& curves = doc["curves"];
    if (!curves.is_array() || curves.empty()) throw Error(source + ": \"curves\" must be a non-empty array of curves");
    for (size_t c = 0; c < curves.size(); ++c) {
        const std::string where = "curves[" + std::to_string(c) + "]";
        if (!curves[c].is_array() || curves[c].empty())
            throw Error(source + ": " + where + " must be a non-empty array of points");
        std::vector<glm::dvec3> pts;
        for (size_t i = 0; i < curves[c].size(); ++i) {
            const auto& pt = curves[c][i];
            const std::string w = where + "[" + std::to_string(i) + "]";
            if (!pt.is_array() || pt.size() != 3) throw Error(source + ": " + w + " must be [x, y, z]");
            pts.emplace_back(finiteNumber(pt[0], w + "[0]", source), finiteNumber(pt[1], w + "[1]", source),
                             finiteNumber(pt[2], w + "[2]", source));
        }
        cell.curves.push_back(std::move(pts));
    }
    return cell;
}

CurveCell loadCurvesJson(const std::string& path) {
    impl::requireInputFile(path, "curves file", "JSON curves file");
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open curves file");
    std::stringstream ss;
    ss << in.rdbuf();
    return parseCurvesJson(ss.str(), path);
}

std::string curvesToJson(const CurveCell& cell) {
    nlohmann::json doc;
    doc["period"] = {cell.px, cell.py};
    doc["radius"] = cell.radius;
    doc["curves"] = nlohmann::json::array();
    for (const auto& curve : cell.curves) {
        nlohmann::json c = nlohmann::json::array();
        for (const glm::dvec3& p : curve) c.push_back({p.x, p.y, p.z});
        doc["curves"].push_back(std::move(c));
    }
    return doc.dump(1);
}

}  // namespace knit
