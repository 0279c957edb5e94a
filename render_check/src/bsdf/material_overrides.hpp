// material_overrides.hpp (internal) — RenderOptions::materialOverrides applied to a material.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "knit/ply_material.hpp"

namespace knit {

// Fields of `overrides` (field -> 1 or 3 numbers; fiberDetail: non-zero = true; fiberCount,
// tableSize, aoRays rounded to integers) override `base` with the rules of parseMaterialJson;
// errors name `where` and the field. The result is validated.
PlyMaterial applyMaterialOverrides(const std::map<std::string, std::vector<double>>& overrides, const PlyMaterial& base,
                                   const std::string& where);

}  // namespace knit
