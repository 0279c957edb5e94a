// detail_geometry.hpp (internal) — what renderScene traces for a scene built for a view
// (knit/detail.hpp): the ply level's plies and the yarn level's yarn curves in one PlyGeometry,
// and the surface level's base-mesh triangles. A scene without a view gives its plies alone.
#pragma once
#include "knit/base_mesh.hpp"
#include "knit/plies.hpp"
#include "knit/ply_geometry.hpp"

namespace knit {
class Scene;
}

namespace knit::impl {

// The radius of a yarn-level curve for these (resolved) ply options: the ply bundle's mean
// projected half-width across the yarn, rp + Rc E[max_i |cos(theta + 2 pi i / n)|] over the
// twist phase theta, so a yarn covers as much of the image as its plies (0.818 of the yarn
// radius for 2 touching plies, the whole radius for one).
double yarnLevelRadius(const PlyOptions& resolved);

// PlyGeometry::bundleHelix for these (resolved) ply options: the ply sweep's dtheta/ds times the
// centre radius (-2 pi Rc / pitch for S twist, +2 pi Rc / pitch for Z), 0 without a pitch.
double bundleHelix(const PlyOptions& resolved);

// The plies, plus (scene built for a view) the yarn-level pieces as single curves of
// yarnLevelRadius, in the plies' scene units (each point carries its curve's radius: every mode
// traces both). Empty (no segments) when neither level has any curve.
PlyGeometry renderCurves(const Scene& scene, const glm::dvec3& origin, double fiberTwist);

// The base-mesh triangles of the surface-level cells (meshSubset: only the vertices they use;
// empty without a view).
BaseMesh surfaceMesh(const Scene& scene);

}  // namespace knit::impl
