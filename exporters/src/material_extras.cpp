// material_extras.cpp — the glTF material extras given as JSON text (see material_extras.hpp).
#include "material_extras.hpp"

#include "knit/error.hpp"

namespace knit::impl {

nlohmann::json parseMaterialExtras(const std::string& text) {
    if (text.empty()) return nlohmann::json::object();
    nlohmann::json extras;
    try {
        extras = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(std::string("cannot export: the glTF material extras are not valid JSON: ") + e.what());
    }
    if (!extras.is_object()) throw Error("cannot export: the glTF material extras must be a JSON object");
    return extras;
}

}  // namespace knit::impl
