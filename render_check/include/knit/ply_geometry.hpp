// knit/ply_geometry.hpp — ply curves as float32 segments relative to a scene origin, shared by the
// three geometry modes, plus the assignment of segments to UV-grid cells (two-stage mode).
//
// Scene units: positions are (p - origin) / unit with unit = the ply radius, so the ply radius is 1.
// Embree's round linear curve intersector has absolute tolerances: with metre coordinates and a
// 0.37 mm radius its hits at joints were measured up to 1.48 radii from the curve (exact at r = 1).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "knit/plies.hpp"

namespace knit {

class Scene;

// Per curve the points are stored "expanded" so that every segment is (points[s], points[s+1]) and
// its neighbours, when they exist, start at points[s-1] / end at points[s+2] (Embree's linear
// curve neighbour rule): an open curve stores p0..p(n-1); a closed curve stores
// p(n-1), p0, ..., p(n-1), p0, p1. Consecutive repeated points are dropped.
struct PlyGeometry {
    glm::dvec3 origin{0.0};
    double unit = 1.0;                       // metres per scene unit (= the ply radius)
    float radius = 0;                        // in scene units (1)
    std::vector<glm::vec4> points;           // (x, y, z, radius), scene units relative to origin
    std::vector<glm::vec3> radial;           // unit direction from the yarn centre, per point
    std::vector<glm::vec3> colour;           // linear yarn colour per point; empty without colours
    std::vector<float> arc;                  // fiber parameter v: arc length along the ply (ply radii), per
                                             // point; rescaled on closed curves (see buildPlyGeometry)
    std::vector<uint32_t> segments;          // first point of each segment
    std::vector<uint8_t> flags;              // per segment: bit 0 left neighbour, bit 1 right neighbour
    std::vector<uint32_t> curveOfSegment;    // source ply curve
    std::vector<uint32_t> curveSegments{0};  // per source curve: range into segments
    // Segments from this index on are yarn-level curves (a view's plies folded into one curve of
    // the bundle's width: knit/detail.hpp); none by default.
    size_t firstBundleSegment = SIZE_MAX;
    // On those curves the visible plies' direction: the plies wind around the yarn as helices,
    // so where the bundle faces n their tangent is T + bundleHelix (T x n) (bundleHelix = -+2 pi
    // centre radius / pitch for S / Z twist: the ply sweep's dtheta/ds times its centre radius).
    double bundleHelix = 0;

    size_t segmentCount() const { return segments.size(); }
    bool hasLeft(size_t s) const { return flags[s] & 1u; }
    bool hasRight(size_t s) const { return flags[s] & 2u; }
    // Bytes of the intersection data (points) and of the shading attributes (radial, arc).
    size_t intersectionBytes() const;
    size_t shadingBytes() const;
    glm::vec3 toScene(const glm::dvec3& world) const { return glm::vec3((world - origin) / unit); }
    glm::dvec3 toWorld(const glm::vec3& scene) const { return origin + unit * glm::dvec3(scene); }
};

// Throws knit::Error when plies are empty, the radius is not positive, or points are not finite.
// fiberTwist (tau_f, radians per ply radius; PlyMaterial::fiberTwist): on a closed curve of length
// L the fiber texture phase tau_f v must close on whole turns or the fiber tables show a seam where
// the loop closes; so v = arc * K 2 pi / (|tau_f| L) with K = max(1, round(|tau_f| L / 2 pi)), a
// change of the effective twist by at most pi / (|tau_f| L) relative. 0 = plain arc length.
PlyGeometry buildPlyGeometry(const Plies& plies, const glm::dvec3& origin, double fiberTwist = 0.0);

// Two-stage mode: the UV-grid cell (i, j) of every segment, packed as (int64(i) << 32) | uint32(j).
// A ply segment takes the cell of the UV position of the nearest vertex of its source yarn
// (binding: triangle + barycentrics, evaluated with the mesh's UVs; cells of size
// scene.grid().cellSize). Throws knit::Error when the scene has no binding / grid for its yarns.
std::vector<int64_t> segmentCells(const Scene& scene, const PlyGeometry& geometry);

}  // namespace knit
