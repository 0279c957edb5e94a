// fileKind(): knit's file formats by extension (see knit/file_kind.hpp).
#include "knit/file_kind.hpp"

#include <filesystem>
#include <utility>

#include "util/platform.hpp"

namespace knit {

std::string fileKind(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    const std::string lower = "." + util::lowerExtension(path);  // ".obj" for "a.OBJ"
    static const std::pair<const char*, const char*> kinds[] = {
        {".obj", "a mesh"},          {".ply", "a mesh"},
        {".off", "a mesh"},          {".gltf", "a mesh"},
        {".glb", "a mesh"},          {".pc2", "a point cache"},
        {".mdd", "a point cache"},   {".knitbind", "a bound scene"},
        {".npy", "a strain table"},  {".png", "an image"},
        {".exr", "an image"},        {".bcc", "a curve export"},
        {".pbrt", "a curve export"}, {".pyp", "a pattern"},
        {".chart", "a chart"},       {".json", "a JSON file"},
        {".blend", "a Blender file"}};
    for (const auto& [e, kind] : kinds)
        if (lower == e) return std::string(kind) + " (" + ext + ")";
    return "";
}

}  // namespace knit
