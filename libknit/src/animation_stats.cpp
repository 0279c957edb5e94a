// animation_stats.cpp — per-frame statistics: the largest yarn stretch and the closest approach
// of different yarns (a spatial hash over the resampled centrelines).
//
// "Different yarns": points of two distinct yarns, or two points of one yarn farther apart
// along its rest centreline than AnimatorOptions::sameYarnSeparation yarn diameters (measured
// the short way round on closed yarns), so a loop pressed onto its own yarn counts while
// neighbouring points of one yarn do not. Distances are between resampled centreline points
// (spacing pitch / samplesPerTurn, half a yarn radius by default), so they overestimate the
// distance between the continuous centrelines by at most half that spacing.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "knit/animation.hpp"

namespace knit {
namespace {

using glm::dvec3;

struct Cell {
    int64_t x, y, z;
};

// Bucket of an integer cell (hash of its three coordinates, masked to the table size).
uint32_t bucketOf(int64_t x, int64_t y, int64_t z, uint32_t mask) {
    const uint64_t h = static_cast<uint64_t>(x) * 73856093ull ^ static_cast<uint64_t>(y) * 19349663ull ^
                       static_cast<uint64_t>(z) * 83492791ull;
    return static_cast<uint32_t>((h ^ (h >> 29)) & mask);
}

// Whether points i and j (of the same or different yarns) count as different yarns.
bool different(uint32_t i, uint32_t j, const std::vector<uint32_t>& yarnOf, const std::vector<double>& arc,
               const std::vector<double>& length, bool closed, double separation) {
    if (yarnOf[i] != yarnOf[j]) return true;
    double along = std::abs(arc[i] - arc[j]);
    if (closed) along = std::min(along, length[yarnOf[i]] - along);
    return along > separation;
}

}  // namespace

double maxYarnStretch(const Polylines& yarns, const std::vector<double>& restSegment) {
    tbb::combinable<double> best([] { return 0.0; });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarns.curveCount(), 256), [&](const tbb::blocked_range<size_t>& r) {
        double& b = best.local();
        for (size_t y = r.begin(); y < r.end(); ++y) {
            const uint32_t first = yarns.begin(y), e = yarns.end(y);
            for (uint32_t i = first; i < e; ++i) {
                if (!(restSegment[i] > 0.0)) continue;
                const uint32_t j = i + 1 < e ? i + 1 : first;
                b = std::max(b, glm::length(yarns.points[j] - yarns.points[i]) / restSegment[i]);
            }
        }
    });
    return best.combine([](double a, double b) { return std::max(a, b); });
}

double minYarnDistance(const Polylines& centres, const std::vector<uint32_t>& yarnOf, const std::vector<double>& arc,
                       const std::vector<double>& length, double yarnRadius, const AnimatorOptions& options,
                       DistanceScratch& scratch) {
    const double diameter = 2.0 * yarnRadius;
    const double cell = options.distanceCutoff * diameter;
    const double separation = options.sameYarnSeparation * diameter;
    const size_t n = centres.pointCount();
    if (n == 0 || !(cell > 0.0)) return std::numeric_limits<double>::infinity();
    const dvec3* p = centres.points.data();
    const double inv = 1.0 / cell;
    auto cellOf = [&](const dvec3& q) {
        return Cell{static_cast<int64_t>(std::floor(q.x * inv)), static_cast<int64_t>(std::floor(q.y * inv)),
                    static_cast<int64_t>(std::floor(q.z * inv))};
    };

    // Step 1: a hash table of at least 2n buckets, filled by counting sort (CSR).
    uint32_t buckets = 1;
    while (buckets < 2 * n) buckets <<= 1;
    const uint32_t mask = buckets - 1;
    scratch.keys.resize(n);
    scratch.bucketStart.assign(size_t(buckets) + 1, 0);
    scratch.items.resize(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const Cell c = cellOf(p[i]);
            scratch.keys[i] = bucketOf(c.x, c.y, c.z, mask);
        }
    });
    for (size_t i = 0; i < n; ++i) ++scratch.bucketStart[scratch.keys[i] + 1];
    for (size_t b = 0; b < buckets; ++b) scratch.bucketStart[b + 1] += scratch.bucketStart[b];
    // Filling advances each bucket's start to its end (the next bucket's start): shift back.
    for (size_t i = 0; i < n; ++i) scratch.items[scratch.bucketStart[scratch.keys[i]]++] = static_cast<uint32_t>(i);
    for (size_t b = buckets; b > 0; --b) scratch.bucketStart[b] = scratch.bucketStart[b - 1];
    scratch.bucketStart[0] = 0;

    // Step 2: per point, the nearest qualifying point in the 27 neighbouring cells.
    tbb::combinable<double> best([] { return std::numeric_limits<double>::infinity(); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, centres.curveCount(), 64), [&](const tbb::blocked_range<size_t>& r) {
        double& b2 = best.local();
        for (size_t y = r.begin(); y < r.end(); ++y) {
            const bool closed = centres.isClosed(y);
            for (uint32_t i = centres.begin(y); i < centres.end(y); ++i) {
                const Cell c = cellOf(p[i]);
                for (int dz = -1; dz <= 1; ++dz)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const uint32_t b = bucketOf(c.x + dx, c.y + dy, c.z + dz, mask);
                            for (uint32_t k = scratch.bucketStart[b]; k < scratch.bucketStart[b + 1]; ++k) {
                                const uint32_t j = scratch.items[k];
                                if (j <= i) continue;  // each pair once
                                const dvec3 d = p[j] - p[i];
                                const double d2 = glm::dot(d, d);
                                if (d2 < b2 && different(i, j, yarnOf, arc, length, closed, separation)) b2 = d2;
                            }
                        }
            }
        }
    });
    const double d = std::sqrt(best.combine([](double a, double b) { return std::min(a, b); }));
    return d <= cell ? d / diameter : std::numeric_limits<double>::infinity();
}

}  // namespace knit
