// crossings.hpp — the crossing structure of a periodic yarn cell, measured from its geometry:
// every crossing of two segments in the plane projection (any periodic image) and which one
// passes in front (larger z) there. Independent of how the cell was built, so the chart tests
// can check the over/under that chartToCell promises and that relaxation keeps. "Front" is +z
// of a frame: the pattern's own (flat cells), or a stitch's local one (relaxed cells, where
// ribs fold and stitches lean, so a stitch's plane tilts far from the pattern's): its normal is
// the stitch's course x wale (stitchFrame).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "knit/chart_topology.hpp"
#include "knit/pattern.hpp"

namespace knit::test {

struct Crossing {
    uint32_t a = 0, b = 0;  // the segments' first vertices (edge v0)
    glm::dvec3 at{0.0};     // crossing point on a (x, y, z of a)
    double zb = 0;          // z of b at the crossing
};

struct Segment {
    uint32_t v0 = 0;
    glm::dvec3 p{0.0}, q{0.0};
};

// An orthonormal frame; coordinates in it are (e1, e2, n) components.
struct Frame {
    glm::dvec3 e1{1, 0, 0}, e2{0, 1, 0}, n{0, 0, 1};
    glm::dvec3 operator()(const glm::dvec3& p) const { return {glm::dot(p, e1), glm::dot(p, e2), glm::dot(p, n)}; }
};

inline std::vector<Segment> segmentsOf(const Pattern& p, const Frame& f = {}) {
    std::vector<Segment> s;
    for (const PeriodicEdge& e : p.edges)
        s.push_back({e.v0, f(p.points[e.v0]), f(p.points[e.v1] + glm::dvec3(e.dx * p.px, e.dy * p.py, 0))});
    return s;
}

// Proper crossings in the plane between segment a and segment b moved by (ix px, iy py).
inline bool crossAt(const Segment& a, const Segment& b, glm::dvec3 shift, Crossing& out) {
    const glm::dvec3 bp = b.p + shift, bq = b.q + shift;
    const double rx = a.q.x - a.p.x, ry = a.q.y - a.p.y, sx = bq.x - bp.x, sy = bq.y - bp.y;
    const double den = rx * sy - ry * sx;
    if (std::abs(den) < 1e-300) return false;
    const double qx = bp.x - a.p.x, qy = bp.y - a.p.y;
    const double t = (qx * sy - qy * sx) / den, u = (qx * ry - qy * rx) / den;
    if (!(t > 0 && t < 1 && u > 0 && u < 1)) return false;
    out.a = a.v0;
    out.b = b.v0;
    out.at = a.p + t * (a.q - a.p);
    out.zb = bp.z + u * (bq.z - bp.z);
    return true;
}

// Crossings between the segments starting in vertex range A and those starting in range B,
// B moved by iy periods along y (and any of -1, 0, 1 along x), seen in frame f.
inline std::vector<Crossing> crossingsBetween(const Pattern& p, uint32_t a0, uint32_t a1, uint32_t b0, uint32_t b1,
                                              int iy, const Frame& f = {}) {
    const std::vector<Segment> segs = segmentsOf(p, f);
    std::vector<Crossing> out;
    for (const Segment& a : segs) {
        if (a.v0 < a0 || a.v0 >= a1) continue;
        for (const Segment& b : segs) {
            if (b.v0 < b0 || b.v0 >= b1) continue;
            for (int ix = -1; ix <= 1; ++ix) {
                if (b.v0 == a.v0 && ix == 0 && iy == 0) continue;
                Crossing c;
                if (crossAt(a, b, f(glm::dvec3(ix * p.px, iy * p.py, 0)), c)) out.push_back(c);
            }
        }
    }
    return out;
}

// The local frame of stitch (row, column), made of the stitch's own axes: the course (from the
// loop's left foot to its right one) and the wale (from the centre of the loop below,
// moved to the image this loop is pulled through, to this loop's centre). n = course x wale
// (+z for a flat cell: courses run in +x, wales in +y), not flipped towards +z, so a stitch
// folded by 90 degrees or more, as the purl columns beside a cable do, keeps its own front;
// e2 = the wale in the plane normal to n. A stitch can turn about the wale, as a rib
// folds, and lean about the course, as the loops at a knit/purl row change do (the garter-like
// ridges at basketweave's block corners and below a cable lean by 30-45 degrees): a frame that
// only turns about the pattern's y axis then sorts the crossings wrongly along the wale.
inline Frame stitchFrame(const ChartCell& cell, int row, int column) {
    const Pattern& p = cell.pattern;
    const StitchLoop& l = cell.loop(row, column);
    const StitchLoop& below = cell.loop((row + cell.height - 1) % cell.height, l.sourceColumn);
    auto centre = [&](const StitchLoop& s) {
        glm::dvec3 c(0.0);
        for (uint32_t i = 0; i < s.count; ++i) c += p.points[s.first + i];
        return c / double(s.count);
    };
    const glm::dvec3 cl = centre(l), cb = centre(below);
    const glm::dvec3 shift(-std::round((cb.x - cl.x) / p.px) * p.px, row == 0 ? -p.py : 0.0, 0);
    const glm::dvec3 wale = glm::normalize(cl - (cb + shift));
    const glm::dvec3 course = (l.reversed ? -1.0 : 1.0) * (p.points[l.first + l.count - 1] - p.points[l.first]);
    const glm::dvec3 n = glm::normalize(glm::cross(course, wale));
    Frame f;
    f.n = n;
    f.e2 = glm::normalize(wale - glm::dot(wale, n) * n);
    f.e1 = glm::cross(f.e2, n);
    return f;
}

// The crossings of loop (row, column) with the loop of the row below it is pulled through,
// bottom to top (along e2 of frame f). Each segment of the loop below is taken at its one
// periodic image nearest the new loop (its x period moved to lie within half a period of the new
// loop's centre): the loop the new one is pulled through. Seen along a stitch's own normal, the
// other images lie a period away in depth but on top of it in the projection: a stitch turned by
// 90 degrees (n along x, at the steep edge of a bulging intarsia area: docs/charts.md, "Issue 25
// round 10") counted crossings with the loop below's image a period behind it.
inline std::vector<Crossing> stitchCrossings(const ChartCell& cell, int row, int column, const Frame& f = {}) {
    const Pattern& p = cell.pattern;
    const StitchLoop& l = cell.loop(row, column);
    const StitchLoop& below = cell.loop((row + cell.height - 1) % cell.height, l.sourceColumn);
    double cx = 0;
    for (uint32_t i = l.first; i < l.first + l.count; ++i) cx += p.points[i].x / double(l.count);
    const std::vector<Segment> mine = segmentsOf(p, f);
    const glm::dvec3 up = f(glm::dvec3(0, row == 0 ? -p.py : 0.0, 0));
    std::vector<Crossing> c;
    for (size_t k = 0; k < p.edges.size(); ++k) {  // mine[k] is edge k
        const PeriodicEdge& eb = p.edges[k];
        if (eb.v0 < below.first || eb.v0 >= below.first + below.count) continue;
        const double mid = 0.5 * (p.points[eb.v0].x + p.points[eb.v1].x + eb.dx * p.px);
        const glm::dvec3 shift = f(glm::dvec3(-std::round((mid - cx) / p.px) * p.px, 0, 0)) + up;
        for (const Segment& a : mine) {
            if (a.v0 < l.first || a.v0 >= l.first + l.count) continue;
            Crossing x;
            if (crossAt(a, mine[k], shift, x)) c.push_back(x);
        }
    }
    std::sort(c.begin(), c.end(), [](const Crossing& x, const Crossing& y) { return x.at.y < y.at.y; });
    return c;
}

// The promise of knit/chart_topology.hpp for one stitch: four crossings with the loop below;
// at the upper two the new loop is in front for knit (behind for purl), at the lower two behind
// for knit (in front for purl). Returns "" or what is wrong.
inline std::string checkStitch(const ChartCell& cell, int row, int column) {
    const std::vector<Crossing> c = stitchCrossings(cell, row, column);
    const std::string where = "stitch (" + std::to_string(row) + ", " + std::to_string(column) + ")";
    if (c.size() != 4) return where + ": " + std::to_string(c.size()) + " crossings with the loop below, expected 4";
    const bool knit = cell.loop(row, column).kind == StitchKind::Knit;
    for (size_t i = 0; i < 4; ++i) {
        const bool front = c[i].at.z > c[i].zb;
        const bool upper = i >= 2;
        if (front != (upper == knit))
            return where + ": crossing " + std::to_string(i) + " (from the bottom) has the new loop " +
                   (front ? "in front" : "behind");
    }
    return "";
}

// The part of the promise that survives relaxation (where stitches lean, roll and, in ribs, fold
// so that a knit loop's feet run back into the purl column beside it and no longer cross the legs
// below in any projection): the highest crossing with the loop below (the new loop's legs over
// its head) has the new loop in front for knit, behind for purl, seen along the stitch's own
// normal (stitchFrame). That the yarns did not pass through each other on the way is the
// relaxation's own bound (RelaxResult::closestApproach).
inline std::string checkStitchEnds(const ChartCell& cell, int row, int column) {
    const std::vector<Crossing> c = stitchCrossings(cell, row, column, stitchFrame(cell, row, column));
    const std::string where = "stitch (" + std::to_string(row) + ", " + std::to_string(column) + ")";
    if (c.size() < 2)
        return where + ": " + std::to_string(c.size()) + " crossings with the loop below, expected at least 2";
    const bool knit = cell.loop(row, column).kind == StitchKind::Knit;
    if ((c.back().at.z > c.back().zb) != knit)
        return where + ": the new loop's legs are on the wrong side of the head below";
    return "";
}

// Stitch (knitRow, knitCol) knit and (purlRow, purlCol) purl: at its highest crossing with the
// loop below, the knit loop is in front and the purl loop behind. "" or what is wrong.
inline std::string knitInFrontPurlBehind(const ChartCell& cell, int knitRow, int knitCol, int purlRow, int purlCol) {
    const std::vector<Crossing> k = stitchCrossings(cell, knitRow, knitCol),
                                p = stitchCrossings(cell, purlRow, purlCol);
    if (k.size() != 4 || p.size() != 4) return "expected 4 crossings per stitch";
    if (!(k[3].at.z > k[3].zb)) return "the knit loop is not in front of the head below";
    if (!(p[3].at.z < p[3].zb)) return "the purl loop is not behind the head below";
    return "";
}

}  // namespace knit::test
