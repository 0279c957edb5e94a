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

namespace {

// The smallest distance between different-yarn points closer than `cell` (+infinity when
// there is none): a hash of cells of that size, each point checked against its 27 cells.
double closestWithin(const Polylines& centres, const std::vector<uint32_t>& yarnOf, const std::vector<double>& arc,
                     const std::vector<double>& length, double separation, double cell, DistanceScratch& scratch) {
    const size_t n = centres.pointCount();
    const dvec3* p = centres.points.data();
    const double inv = 1.0 / cell;
    auto cellOf = [&](const dvec3& q) {
        return Cell{static_cast<int64_t>(std::floor(q.x * inv)), static_cast<int64_t>(std::floor(q.y * inv)),
                    static_cast<int64_t>(std::floor(q.z * inv))};
    };

    // Step 1: a hash table of at least n buckets, filled by counting sort (CSR), with the
    // points copied in bucket order (neighbours are then read from contiguous memory).
    uint32_t buckets = 1;
    while (buckets < n) buckets <<= 1;
    const uint32_t mask = buckets - 1;
    scratch.keys.resize(n);
    scratch.bucketStart.assign(size_t(buckets) + 1, 0);
    scratch.items.resize(n);
    scratch.sorted.resize(n);
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
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) scratch.sorted[k] = p[scratch.items[k]];
    });

    // Step 2: per point (in bucket order, so consecutive points share their neighbouring
    // cells), the nearest qualifying point closer than `cell`: each pair once, by a half
    // stencil (the later points of the own bucket and every point of the 13 cells after it).
    const uint32_t* start = scratch.bucketStart.data();
    const uint32_t* items = scratch.items.data();
    const dvec3* q = scratch.sorted.data();
    tbb::combinable<double> best([&] { return cell * cell; });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        double& b2 = best.local();
        Cell last{INT64_MIN, 0, 0};
        uint32_t own = 0, forward[13];
        const auto visit = [&](size_t k, uint32_t from, uint32_t to) {
            const uint32_t i = items[k];
            for (uint32_t kk = from; kk < to; ++kk) {
                const dvec3 d = q[kk] - q[k];
                const double d2 = glm::dot(d, d);
                if (d2 < b2 && different(i, items[kk], yarnOf, arc, length, centres.isClosed(yarnOf[i]), separation))
                    b2 = d2;
            }
        };
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const Cell c = cellOf(q[k]);
            if (c.x != last.x || c.y != last.y || c.z != last.z) {
                own = bucketOf(c.x, c.y, c.z, mask);
                for (int m = 14; m < 27; ++m)  // (dx, dy, dz) after (0, 0, 0) in z-major order
                    forward[m - 14] = bucketOf(c.x + m % 3 - 1, c.y + m / 3 % 3 - 1, c.z + m / 9 - 1, mask);
                last = c;
            }
            visit(k, static_cast<uint32_t>(k + 1), start[own + 1]);
            for (const uint32_t b : forward) visit(k, start[b], start[b + 1]);
        }
    });
    const double d = std::sqrt(best.combine([](double a, double b) { return std::min(a, b); }));
    return d < cell ? d : std::numeric_limits<double>::infinity();
}

}  // namespace

double minYarnDistance(const Polylines& centres, const std::vector<uint32_t>& yarnOf, const std::vector<double>& arc,
                       const std::vector<double>& length, double yarnRadius, const AnimatorOptions& options,
                       DistanceScratch& scratch) {
    const double diameter = 2.0 * yarnRadius;
    const double cutoff = options.distanceCutoff * diameter;
    if (centres.pointCount() == 0 || !(cutoff > 0.0)) return std::numeric_limits<double>::infinity();
    // The search cost grows with the cube of the cell size, so start just above the previous
    // frame's answer (frames change little) and widen up to the cutoff until a pair is found:
    // any pair closer than the cell size is found, so the first hit is the exact minimum.
    double cell = scratch.lastDistance > 0.0 ? std::min(cutoff, 1.25 * scratch.lastDistance) : cutoff;
    for (;;) {
        const double d =
            closestWithin(centres, yarnOf, arc, length, options.sameYarnSeparation * diameter, cell, scratch);
        if (std::isfinite(d) || cell >= cutoff) {
            scratch.lastDistance = d;
            return std::isfinite(d) ? d / diameter : d;
        }
        cell = std::min(cutoff, 2.0 * cell);
    }
}

}  // namespace knit
