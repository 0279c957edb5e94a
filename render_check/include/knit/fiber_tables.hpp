// knit/fiber_tables.hpp — fiber-level detail of a ply: 1D tables built by 2D ray casting, and the
// shading frame they produce at a point on a ply.
//
// A ply cross-section is modelled as a ring of N touching fibers (ring radius 1/(1 + sin(pi/N)) and
// fiber radius ring * sin(pi/N), in ply radii). For each of `size` angles a around the ply a 2D ray
// is cast towards the centre; the first fiber hit gives
//   delta: the angle from the ply normal (cos a, sin a) to the fiber normal at the hit,
//   phase: the angular offset of the visible fiber's centre from a,
//   shadow: the fraction of `aoRays` stratified rays (over the half-plane around the fiber normal,
//           length one ply radius) blocked by other fibers, min-max normalised and inverted, then
//           remapped S' = S (1 - floor) + floor.
// A second table does the same for the plies around their yarn (ring of `plyCount` touching plies,
// rays of one yarn radius) and gives the ply-level shadow, indexed by the ply phase.
// Tables are indexed by u = frac((phi_ply + tau_f v) / 2 pi) (fiber tables) and u = frac(phi_ply/2pi)
// (ply table); the 2D x axis is the ply's radial direction, y = tangent x radial.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "knit/ply_material.hpp"

namespace knit {

struct FiberTableOptions {
    int fiberCount = 40;
    int plyCount = 2;
    int size = 1000;
    int aoRays = 1000;
    double fiberShadowFloor = 0.4;
    double plyShadowFloor = 0.3;
};
FiberTableOptions fiberTableOptions(const PlyMaterial& material, int plyCount);

struct FiberTables {
    int size = 0;
    double ringRadius = 0, fiberRadius = 0;        // in ply radii
    std::vector<float> delta, phase, fiberShadow;  // fiberShadow already remapped (S')
    std::vector<float> plyShadow;                  // remapped, indexed by ply phase
    // The ply shadow averaged over the bundle of plies as seen from outside (every direction
    // across the yarn, every point of its projected width): what a yarn-level curve, which has
    // no plies and so no crevices, shows on average.
    double visiblePlyShadow = 1;

    struct Texel {
        double delta = 0, phase = 0, shadow = 1;
    };
    Texel fiber(double u) const;  // nearest texel for delta/phase, linear for shadow
    double ply(double u) const;   // linear, wraps
    size_t bytes() const;
};

// Deterministic (stratified rays, no random numbers); parallel over texels.
FiberTables buildFiberTables(const FiberTableOptions& options);

// A point on a ply surface: ply tangent, outward ply normal (from the ply centreline), the unit
// radial direction of the ply from its yarn centre, and arc length along the ply in ply radii.
struct PlySurfacePoint {
    glm::dvec3 tangent{0, 0, 1};
    glm::dvec3 normal{1, 0, 0};
    glm::dvec3 radial{1, 0, 0};
    double v = 0;
    bool bundle = false;  // on a yarn-level curve: the ply shadow is FiberTables::visiblePlyShadow
};

struct ShadingFrame {
    glm::dvec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};  // x = fiber tangent, z = fiber normal
    double shadow = 1.0;                            // S' for the body lobes
    glm::dvec3 toLocal(const glm::dvec3& w) const;
    glm::dvec3 toWorld(const glm::dvec3& w) const;
};

// Fiber tangent t_f (helix of rate tau_f around the ply, at the visible fiber's centre), fiber normal
// n_f = the ply normal (tangential part removed) rotated about t_f by delta; shadow = fiber S' times
// ply S'. With material.fiberDetail off the frame is the ply frame and only the ply shadow applies.
ShadingFrame plyShadingFrame(const PlySurfacePoint& point, const PlyMaterial& material, const FiberTables& tables);

}  // namespace knit
