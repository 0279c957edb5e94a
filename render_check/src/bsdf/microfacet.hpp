// microfacet.hpp (internal) — the Fresnel and GGX terms of the ply BSDF's R and TT lobes
// (defined in ply_bsdf.cpp).
#pragma once
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace knit {

// Exact Fresnel reflectance of a dielectric interface for light arriving from the outside with
// |cos theta| = cosTheta (relative index eta = n_inside / n_outside).
double fresnelDielectric(double cosTheta, double eta);

// Anisotropic GGX in a frame with z = normal (alpha x along local x, y along local y).
double ggxD(const glm::dvec3& h, double ax, double ay);
double ggxLambda(const glm::dvec3& w, double ax, double ay);
double ggxG1(const glm::dvec3& w, double ax, double ay);
// Visible-normal sample for a direction w with w_z > 0; u in [0,1)^2.
glm::dvec3 ggxSampleVisibleNormal(const glm::dvec3& w, double ax, double ay, glm::dvec2 u);

}  // namespace knit
