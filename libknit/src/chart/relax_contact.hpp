// relax_contact.hpp — contact pairs of a periodic yarn cell (internal to relax.cpp): segment
// closest points, which segments are neighbours along a yarn, and the spatial hash over the
// periodic images.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/pattern.hpp"

namespace knit::relax {

// A segment: vertex a in tile (0, 0) to vertex b in tile (dx, dy).
struct Seg {
    uint32_t a = 0, b = 0;
    int32_t dx = 0, dy = 0;
};

// Where each vertex sits along its yarn: index along the yarn, the yarn, the yarn's vertex count,
// the tile offset accumulated from the yarn's start, the yarn's winding (0 for an open yarn) and
// whether it is open (it has two ends; its first vertex is the one no segment arrives at).
struct YarnIndex {
    std::vector<int32_t> yarn, index, length, ux, uy, wx, wy;
    std::vector<bool> open;
};
// Throws knit::Error when two yarns merge, a vertex starts two segments, or (allowOpen false) a
// yarn is open.
YarnIndex indexYarns(const Pattern& p, const std::vector<Seg>& segs, bool allowOpen = false);

// Two segments, the second moved by (ix, iy) periods.
struct Pair {
    uint32_t s = 0, t = 0;
    int32_t ix = 0, iy = 0;
};

// True when segment t (moved by ix, iy) is within `gap` segments of segment s along a yarn.
bool nearAlongYarn(const YarnIndex& yi, const std::vector<Seg>& segs, const Pair& pr, int gap);

// Pairs (s < t, or s == t with a non-zero image) whose centrelines are closer than `cutoff`,
// excluding neighbours along a yarn. Positions in any unit; px, py the period.
std::vector<Pair> findPairs(const std::vector<glm::dvec3>& x, double px, double py, const std::vector<Seg>& segs,
                            const YarnIndex& yi, double cutoff);

// Closest points between segments p0p1 and q0q1: parameters s, t in [0, 1].
void closestParameters(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0, const glm::dvec3& q1,
                       double& s, double& t);

}  // namespace knit::relax
