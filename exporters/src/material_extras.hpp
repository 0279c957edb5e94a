// material_extras.hpp (internal) — ExportInput::materialExtrasJson, the glTF material's extras.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace knit::impl {

// The extras text as a JSON object (an empty text: an empty object). Throws knit::Error unless
// the text is one JSON object: "cannot export: the glTF material extras are not valid JSON: ..." or
// "cannot export: the glTF material extras must be a JSON object".
nlohmann::json parseMaterialExtras(const std::string& text);

}  // namespace knit::impl
