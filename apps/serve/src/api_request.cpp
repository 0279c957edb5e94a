// Parsing and checking the API's JSON bodies (api_request.hpp).
#include "api_request.hpp"

#include <cctype>
#include <cmath>

#include <nlohmann/json.hpp>

#include "knit/error.hpp"

namespace knit::serve {
namespace {

using nlohmann::json;

json parseObject(const std::string& body) {
    json j = json::parse(body, nullptr, false);
    if (j.is_discarded()) throw RequestError(400, "the request body is not valid JSON");
    if (!j.is_object()) throw RequestError(400, "the request body must be a JSON object");
    return j;
}

// Refuses keys the endpoint does not know (a typo would otherwise be silently ignored).
void requireKnownKeys(const json& j, std::initializer_list<const char*> known) {
    for (const auto& item : j.items()) {
        bool ok = false;
        for (const char* k : known) ok = ok || item.key() == k;
        if (!ok) throw RequestError(400, "unknown field \"" + item.key() + "\"");
    }
}

std::string requireSession(const json& j) {
    if (!j.contains("session") || !j["session"].is_string())
        throw RequestError(400, "\"session\" must be a string (the page's id)");
    std::string s = j["session"].get<std::string>();
    if (s.empty() || s.size() > 64) throw RequestError(400, "\"session\" must be 1 to 64 characters long");
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
            throw RequestError(400, "\"session\" may hold only letters, digits, '-' and '_'");
    return s;
}

std::string requireChart(const json& j, const RequestLimits& limits) {
    if (!j.contains("chart") || !j["chart"].is_string())
        throw RequestError(400, "\"chart\" must be a string (the chart text)");
    std::string text = j["chart"].get<std::string>();
    if (text.size() > limits.maxChartBytes)
        throw RequestError(413, "\"chart\" is " + std::to_string(text.size()) + " bytes, over the limit of " +
                                    std::to_string(limits.maxChartBytes));
    return text;
}

double finiteNumber(const json& v, const std::string& what) {
    if (!v.is_number()) throw RequestError(400, what + " must be a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) throw RequestError(400, what + " must be finite");
    return x;
}

std::array<double, 2> repeatsOf(const json& j, double maxRepeats) {
    std::array<double, 2> r{0, 0};
    if (!j.contains("repeats")) return r;
    const json& v = j["repeats"];
    const std::string message =
        "\"repeats\" must be two numbers from 1 to " + std::to_string(int(maxRepeats)) + " (or [0, 0] for the default)";
    if (!v.is_array() || v.size() != 2) throw RequestError(400, message);
    for (size_t k = 0; k < 2; ++k) r[k] = finiteNumber(v[k], "\"repeats\"");
    const bool none = r[0] == 0 && r[1] == 0;
    if (!none && (r[0] < 1 || r[1] < 1 || r[0] > maxRepeats || r[1] > maxRepeats)) throw RequestError(400, message);
    return r;
}

glm::dvec3 vec3Of(const json& v, const std::string& what) {
    if (!v.is_array() || v.size() != 3) throw RequestError(400, what + " must be three numbers");
    return {finiteNumber(v[0], what), finiteNumber(v[1], what), finiteNumber(v[2], what)};
}

View viewOf(const json& v, const RequestLimits& limits) {
    if (!v.is_object()) throw RequestError(400, "\"view\" must be an object with eye, target, up, fov, width, height");
    requireKnownKeys(v, {"eye", "target", "up", "fov", "width", "height"});
    View view;
    if (!v.contains("eye") || !v.contains("target")) throw RequestError(400, "\"view\" needs \"eye\" and \"target\"");
    view.eye = vec3Of(v["eye"], "\"view.eye\"");
    view.target = vec3Of(v["target"], "\"view.target\"");
    if (v.contains("up")) view.up = vec3Of(v["up"], "\"view.up\"");
    if (v.contains("fov")) view.fovDegrees = finiteNumber(v["fov"], "\"view.fov\"");
    for (const char* side : {"width", "height"}) {
        if (!v.contains(side)) continue;
        const double px = finiteNumber(v[side], std::string("\"view.") + side + "\"");
        if (px < 1 || px > limits.maxImageSide || px != std::floor(px))
            throw RequestError(400, std::string("\"view.") + side + "\" must be a whole number of pixels from 1 to " +
                                        std::to_string(limits.maxImageSide));
        (std::string(side) == "width" ? view.width : view.height) = int(px);
    }
    try {
        validateView(view);
    } catch (const Error& e) {
        throw RequestError(400, std::string("\"view\": ") + e.what());
    }
    return view;
}

}  // namespace

SwatchRequest parseSwatchRequest(const std::string& body, const RequestLimits& limits) {
    const json j = parseObject(body);
    requireKnownKeys(j, {"session", "chart", "repeats"});
    SwatchRequest r;
    r.session = requireSession(j);
    r.chart = requireChart(j, limits);
    r.repeats = repeatsOf(j, limits.maxRepeats);
    return r;
}

GarmentRequest parseGarmentRequest(const std::string& body, const RequestLimits& limits, bool download) {
    const json j = parseObject(body);
    if (download) requireKnownKeys(j, {"session", "chart", "mesh", "repeats", "gauge", "view", "format"});
    else requireKnownKeys(j, {"session", "chart", "mesh", "repeats", "gauge", "view"});
    GarmentRequest r;
    r.session = requireSession(j);
    r.chart = requireChart(j, limits);
    if (j.contains("mesh")) {
        if (!j["mesh"].is_string())
            throw RequestError(400, "\"mesh\" must be a string (a built-in name or an upload id)");
        r.mesh = j["mesh"].get<std::string>();
    }
    r.repeats = repeatsOf(j, 4096);
    if (j.contains("gauge") && !j["gauge"].is_null()) {
        if (!j["gauge"].is_string()) throw RequestError(400, "\"gauge\" must be a string like \"22x30/10cm\"");
        if (r.repeats[0] != 0) throw RequestError(400, "give \"repeats\" or \"gauge\", not both");
        try {
            r.gauge = parseGauge(j["gauge"].get<std::string>());
        } catch (const Error& e) {
            throw RequestError(400, std::string("\"gauge\": ") + e.what());
        }
    }
    if (j.contains("view") && !j["view"].is_null()) r.view = viewOf(j["view"], limits);
    if (download) {
        const std::string f = j.contains("format") && j["format"].is_string() ? j["format"].get<std::string>() : "";
        if (f == "pyp") r.format = DownloadFormat::Pyp;
        else if (f == "glb") r.format = DownloadFormat::Glb;
        else if (f == "pc2") r.format = DownloadFormat::Pc2;
        else throw RequestError(400, "\"format\" must be \"pyp\", \"glb\" or \"pc2\"");
    }
    return r;
}

std::string parseCancelRequest(const std::string& body) {
    const json j = parseObject(body);
    requireKnownKeys(j, {"session"});
    return requireSession(j);
}

}  // namespace knit::serve
