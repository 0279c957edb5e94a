// animation_stats.cpp — per-frame statistics: the largest yarn stretch and the closest approach
// of different yarns (a spatial hash over the resampled centrelines).
//
// "Different yarns": points of two distinct yarns, or two points of one yarn farther apart
// along its rest centreline than AnimatorOptions::sameYarnSeparation yarn diameters (measured
// the short way round on closed yarns), so a loop pressed onto its own yarn counts while
// neighbouring points of one yarn do not. Distances are between resampled centreline points
// (spacing pitch / samplesPerTurn, half a yarn radius by default), so they overestimate the
// distance between the continuous centrelines by at most half that spacing.
//
// The search (minYarnDistance): the previous frame's closest pair, measured on this frame, bounds
// the answer, so a grid of cells that size finds every closer pair (frames change little, and
// the cost grows with the cube of the cell size). Points are packed in float relative to the
// frame's first point (distance rounding ~1e-7 of the garment's extent; the pair found is
// measured again in double) with their yarn (walked along the centres' offsets) and rest arc
// length, so the inner loop reads only contiguous memory; cells are hashed in blocks of 8 x 8 x 8
// so most neighbours of a cell are next to it in the table.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "knit/animation.hpp"
#include "util/csr.hpp"

namespace knit {
namespace {

using glm::dvec3;

struct Cell {
    int64_t x, y, z;
};

}  // namespace

double maxYarnStretch(const Polylines& yarns, ArrayView<double> restSegment) {
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

double totalYarnLength(const Polylines& yarns) {
    std::vector<double> perYarn(yarns.curveCount(), 0.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarns.curveCount(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t y = r.begin(); y < r.end(); ++y) {
            const uint32_t first = yarns.begin(y), e = yarns.end(y);
            double sum = 0;
            for (uint32_t i = first; i + 1 < e; ++i) sum += glm::length(yarns.points[i + 1] - yarns.points[i]);
            if (yarns.isClosed(y) && e - first > 2) sum += glm::length(yarns.points[first] - yarns.points[e - 1]);
            perYarn[y] = sum;
        }
    });
    double total = 0;
    for (double l : perYarn) total += l;
    return total;
}

namespace {

// A point of the search in float, relative to the frame's first point (so a garment far from
// the origin keeps its precision), with its centreline index, yarn and rest arc length.
using Packed = DistanceScratch::Point;

// Whether two points count as different yarns: distinct yarns, or farther apart along the rest
// yarn than `separation` (the short way round a closed yarn, whose rest length is `loop`).
bool different(const Packed& a, const Packed& b, const Polylines& centres, const std::vector<double>& loop,
               double separation) {
    if (a.yarn != b.yarn) return true;
    double along = std::abs(double(a.arc) - double(b.arc));
    if (along > separation && centres.isClosed(a.yarn)) along = std::min(along, loop[a.yarn] - along);
    return along > separation;
}

// The yarn of each centre point, for the points visited in order from the first: walked along
// the curve offsets (no per-point yarn index is kept: 4 bytes per resampled point, 38 MB on the
// 3M-vertex garment, for what the offsets already say).
class YarnWalk {
public:
    explicit YarnWalk(const std::vector<uint32_t>& offsets) : offsets_(offsets) {}
    uint32_t at(size_t i) {
        while (i >= offsets_[yarn_ + 1]) ++yarn_;  // skips empty yarns too
        return yarn_;
    }

private:
    const std::vector<uint32_t>& offsets_;
    uint32_t yarn_ = 0;
};

// The closest qualifying pair found: squared float distance and the two centreline points.
struct Closest {
    float d2;
    uint32_t i, j;
};

// Cells are grouped in blocks of 8 x 8 x 8 that are hashed together, so the neighbours of a cell
// are mostly in its own block: adjacent in the table and in memory (a hash per cell scatters
// them, and the search then waits on memory).
uint32_t bucketOf(const Cell& c, uint32_t blockMask) {
    const uint64_t h = static_cast<uint64_t>(c.x >> 3) * 73856093ull ^ static_cast<uint64_t>(c.y >> 3) * 19349663ull ^
                       static_cast<uint64_t>(c.z >> 3) * 83492791ull;
    const uint32_t block = static_cast<uint32_t>((h ^ (h >> 29)) & blockMask);
    return block << 9 | static_cast<uint32_t>(c.x & 7) | static_cast<uint32_t>(c.y & 7) << 3 |
           static_cast<uint32_t>(c.z & 7) << 6;
}

// The closest pair of qualifying points closer than `cell` ({+inf, 0, 0} when there is none):
// a hash of cells of that size, each pair checked once by a half stencil.
Closest closestWithin(const Polylines& centres, ArrayView<double> arc, const std::vector<double>& length,
                      double separation, double cell, DistanceScratch& scratch) {
    const size_t n = centres.pointCount();
    const dvec3* p = centres.points.data();
    const dvec3 origin = p[0];
    const double inv = 1.0 / cell;
    const auto pack = [&](size_t i, uint32_t yarn) {
        const dvec3 d = p[i] - origin;
        const auto f = [](double v) { return static_cast<float>(v); };
        return Packed{f(d.x), f(d.y), f(d.z), static_cast<uint32_t>(i), yarn, f(arc[i])};
    };
    // Cells of the packed (float) coordinates the distances are computed from. A coordinate
    // beyond float's range (a finite double far out) is infinite here: its cell index is clamped
    // (NaN to the low end) rather than converted out of int64's range.
    const auto axisCell = [inv](float v) {
        constexpr double kLimit = 4.0e18;
        const double c = std::floor(double(v) * inv);
        return static_cast<int64_t>(!(c > -kLimit) ? -kLimit : c < kLimit ? c : kLimit);
    };
    const auto cellOf = [&](const Packed& a) { return Cell{axisCell(a.x), axisCell(a.y), axisCell(a.z)}; };

    // Step 1: a table of at least 4n buckets (blocks of 512), filled by counting sort (CSR), with
    // the points packed in bucket order (neighbours are then read from contiguous memory).
    uint32_t blocks = 1;
    while (size_t(blocks) * 512 < 4 * n) blocks <<= 1;
    const uint32_t blockMask = blocks - 1;
    const size_t buckets = size_t(blocks) * 512;
    scratch.keys.resize(n);
    scratch.bucketStart.assign(buckets + 1, 0);
    scratch.packed.resize(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
        // (The yarn plays no part in the cell.)
        for (size_t i = r.begin(); i < r.end(); ++i) scratch.keys[i] = bucketOf(cellOf(pack(i, 0)), blockMask);
    });
    uint32_t* start = scratch.bucketStart.data();
    for (size_t i = 0; i < n; ++i) ++start[scratch.keys[i] + 1];
    util::countsToOffsets(scratch.bucketStart);
    // Filling advances each bucket's start to its end (the next bucket's start): shift back.
    YarnWalk walk(centres.offsets);
    for (size_t i = 0; i < n; ++i) scratch.packed[start[scratch.keys[i]]++] = pack(i, walk.at(i));
    for (size_t b = buckets; b > 0; --b) start[b] = start[b - 1];
    start[0] = 0;

    // Step 2: per point (in bucket order, so consecutive points share their neighbouring
    // cells), the nearest qualifying point closer than `cell`: each pair once, by a half
    // stencil (the later points of the own bucket and every point of the 13 cells after it).
    const Packed* q = scratch.packed.data();
    const float cell2 = static_cast<float>(cell * cell);
    tbb::combinable<Closest> best([&] { return Closest{cell2, 0, 0}; });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        Closest& b = best.local();
        Cell last{INT64_MIN, 0, 0};
        uint32_t own = 0, forward[13];
        const auto visit = [&](size_t k, uint32_t from, uint32_t to) {
            const Packed a = q[k];
            for (uint32_t kk = from; kk < to; ++kk) {
                const float dx = q[kk].x - a.x, dy = q[kk].y - a.y, dz = q[kk].z - a.z;
                const float d2 = dx * dx + dy * dy + dz * dz;
                if (d2 < b.d2 && different(a, q[kk], centres, length, separation)) b = Closest{d2, a.item, q[kk].item};
            }
        };
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const Cell c = cellOf(q[k]);
            if (c.x != last.x || c.y != last.y || c.z != last.z) {
                own = bucketOf(c, blockMask);
                for (int m = 14; m < 27; ++m)  // (dx, dy, dz) after (0, 0, 0) in z-major order
                    forward[m - 14] = bucketOf(Cell{c.x + m % 3 - 1, c.y + m / 3 % 3 - 1, c.z + m / 9 - 1}, blockMask);
                last = c;
            }
            visit(k, static_cast<uint32_t>(k + 1), start[own + 1]);
            for (const uint32_t f : forward) visit(k, start[f], start[f + 1]);
        }
    });
    const Closest c = best.combine([](const Closest& a, const Closest& b) { return b.d2 < a.d2 ? b : a; });
    if (c.d2 < cell2) return c;
    return Closest{std::numeric_limits<float>::infinity(), 0, 0};
}

}  // namespace

double minYarnDistance(const Polylines& centres, ArrayView<double> arc, const std::vector<double>& length,
                       double yarnRadius, const AnimatorOptions& options, DistanceScratch& scratch) {
    const double diameter = 2.0 * yarnRadius;
    const double cutoff = options.distanceCutoff * diameter;
    const size_t n = centres.pointCount();
    if (n == 0 || !(cutoff > 0.0)) return std::numeric_limits<double>::infinity();
    const double separation = options.sameYarnSeparation * diameter;
    const auto distance = [&](uint32_t i, uint32_t j) { return glm::length(centres.points[i] - centres.points[j]); };

    // Step 1: an upper bound, the previous frame's closest pair on this frame (frames change
    // little): the search then only needs cells of that size (its cost grows with the cube of
    // the cell size). Without one, start at one diameter (yarns in contact).
    const bool previous = scratch.hasPair && scratch.pair[0] < n && scratch.pair[1] < n;
    const double bound =
        previous ? distance(scratch.pair[0], scratch.pair[1]) : std::numeric_limits<double>::infinity();
    double cell = previous ? bound : std::min(cutoff, diameter);
    cell = std::min(cutoff, std::max(cell, 1e-6 * diameter));  // cell coordinates stay bounded

    // Step 2: every pair closer than the cell size is found, so the first search that finds one
    // (or that the bound undercuts) has the minimum; otherwise widen up to the cutoff.
    for (;;) {
        const Closest c = closestWithin(centres, arc, length, separation, cell, scratch);
        if (std::isfinite(c.d2)) {
            scratch.hasPair = true;
            scratch.pair = {c.i, c.j};
            // Rounded in float: take the exact distance, and the bound when it is as close.
            return std::min(distance(c.i, c.j), bound) / diameter;
        }
        if (bound <= cell) return bound / diameter;
        if (cell >= cutoff) {
            scratch.hasPair = false;
            return std::numeric_limits<double>::infinity();
        }
        cell = std::min(cutoff, 2.0 * cell);
    }
}

}  // namespace knit
