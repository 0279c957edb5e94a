// point_cache.hpp (internal) — the byte layouts of the point cache formats (knit/cache.hpp):
// one header and one frame encoder per format (pc2_writer.cpp, mdd_writer.cpp).
#pragma once
#include <cstdint>
#include <cstring>
#include <ostream>
#include <vector>

#include <glm/vec3.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/cache.hpp"

namespace knit::impl {

// float32 / int32 bytes in little- or big-endian order, independent of the host.
inline void putU32(std::vector<char>& out, uint32_t v, bool bigEndian) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(v >> (bigEndian ? 24 - 8 * i : 8 * i)));
}
inline void putF32(std::vector<char>& out, float f, bool bigEndian) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    putU32(out, v, bigEndian);
}
// The points of one frame as float32 x, y, z, appended to `out` (in parallel: a garment frame
// is tens of millions of points).
inline void putPoints(std::vector<char>& out, const std::vector<glm::dvec3>& points, bool bigEndian) {
    const size_t base = out.size();
    out.resize(base + 12 * points.size());
    char* dst = out.data() + base;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            for (int k = 0; k < 3; ++k) {
                const float f = static_cast<float>(points[i][k]);
                uint32_t v;
                std::memcpy(&v, &f, 4);
                char* b = dst + 12 * i + 4 * k;
                for (int j = 0; j < 4; ++j) b[j] = static_cast<char>(v >> (bigEndian ? 24 - 8 * j : 8 * j));
            }
    });
}

void pc2Header(const CacheInfo& info, std::vector<char>& out);
void pc2Frame(const std::vector<glm::dvec3>& points, std::vector<char>& out);
void mddHeader(const CacheInfo& info, std::vector<char>& out);
void mddFrame(const std::vector<glm::dvec3>& points, std::vector<char>& out);

}  // namespace knit::impl
