// pc2_writer.cpp — PC2 point cache bytes (little-endian; layout in knit/cache.hpp).
#include "point_cache.hpp"

namespace knit::impl {

void pc2Header(const CacheInfo& info, std::vector<char>& out) {
    static const char kMagic[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
    out.insert(out.end(), kMagic, kMagic + 12);
    putU32(out, 1, false);  // file version
    putU32(out, static_cast<uint32_t>(info.points), false);
    putF32(out, static_cast<float>(info.startFrame), false);
    putF32(out, static_cast<float>(info.step), false);  // sample rate: frames between samples
    putU32(out, static_cast<uint32_t>(info.frames), false);
}

void pc2Frame(const std::vector<glm::dvec3>& points, std::vector<char>& out) { putPoints(out, points, false); }

}  // namespace knit::impl
