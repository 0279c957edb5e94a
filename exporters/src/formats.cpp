// formats.cpp — the table of written formats (see formats.hpp).
#include "formats.hpp"

#include "util/platform.hpp"

namespace knit::impl {
namespace {

void writeGltf(const FormatJob& job) { exportGltf(job, false); }
void writeGlb(const FormatJob& job) { exportGltf(job, true); }

// extension, pointCache, tubes, gltf, float32, write
constexpr Format kFormats[] = {
    {"obj", false, true, false, false, exportObj}, {"ply", false, true, false, false, exportPly},
    {"bcc", false, false, false, true, exportBcc}, {"pbrt", false, true, false, true, exportPbrt},
    {"gltf", false, true, true, true, writeGltf},  {"glb", false, true, true, true, writeGlb},
    {"pc2", true, false, false, true, nullptr},    {"mdd", true, false, false, true, nullptr},
};

}  // namespace

const Format* formatOf(const std::string& path) {
    const std::string ext = util::lowerExtension(path);
    for (const Format& f : kFormats)
        if (ext == f.extension) return &f;
    return nullptr;
}

std::string sceneFormatList(const char* separator, bool tubesOnly) {
    std::string list;
    for (const Format& f : kFormats) {
        if (f.pointCache || (tubesOnly && !f.tubes)) continue;
        if (!list.empty()) list += separator;
        list += std::string(".") + f.extension;
    }
    return list;
}

}  // namespace knit::impl
