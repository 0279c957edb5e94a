// mdd_writer.cpp — MDD point cache bytes (big-endian; layout in knit/cache.hpp).
#include "point_cache.hpp"

namespace knit::impl {

void mddHeader(const CacheInfo& info, std::vector<char>& out) {
    putU32(out, static_cast<uint32_t>(info.frames), true);
    putU32(out, static_cast<uint32_t>(info.points), true);
    for (size_t k = 0; k < info.frames; ++k) putF32(out, static_cast<float>(static_cast<double>(k) / info.fps), true);
}

void mddFrame(const std::vector<glm::dvec3>& points, std::vector<char>& out) { putPoints(out, points, true); }

}  // namespace knit::impl
