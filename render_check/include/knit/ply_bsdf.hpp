// knit/ply_bsdf.hpp — the ply BSDF in its local shading frame (x = fiber tangent, z = fiber normal).
//
// Lobes (f is symmetric in its two directions, both pointing away from the surface):
//   R  (same side):      kR  F(|o.h|) D(h) G2(o, i) / (4 |o_z| |i_z|),   h = normalize(o + i)
//   TT (opposite side):  kTT (1 - F(|o.h'|)) D(h') G2(o, flip i) / (4 |o_z| |i_z|),
//                        flip(w) = (w_x, w_y, -w_z), h' = normalize(o + flip i)
//   BR (same side):      rho_B r S' / pi
//   BT (opposite side):  rho_B (1 - r) S' / pi
// D, G2: anisotropic GGX (Smith, height-uncorrelated), alpha along x / across y for R and
// alphaTT for TT; F: exact dielectric Fresnel with eta. Directions below the surface are handled by
// mirroring both directions so that o_z > 0. Sampling picks a lobe with probabilities that depend on
// o only (luminance of kR F(|o_z|), kTT (1 - F(|o_z|)), rho_B r S', rho_B (1 - r) S'), then draws
// visible normals (Heitz 2018) for R / TT and cosine-weighted directions for the body lobes;
// pdf() is the full mixture, so it equals the density of sample().
#pragma once
#include <array>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/ply_material.hpp"

namespace knit {

double luminance(const Rgb& c);

struct BsdfSample {
    glm::dvec3 wi{0.0};  // sampled direction (local frame)
    Rgb weight{0.0};     // f |wi_z| / pdf
    double pdf = 0.0;    // mixture pdf (solid angle)
    int lobe = -1;
    bool valid = false;
};

class PlyBsdf {
public:
    enum Lobe { R = 0, TT = 1, BodyR = 2, BodyT = 3 };
    // `shadow` is the self-shadowing factor S' in [0, 1]; it scales the body lobes only.
    explicit PlyBsdf(const PlyMaterial& material, double shadow = 1.0);
    // The same with the body albedo rho_B of this ply instead of the material's (a yarn colour,
    // see yarnBodyAlbedo).
    PlyBsdf(const PlyMaterial& material, double shadow, const Rgb& bodyAlbedo);

    Rgb eval(const glm::dvec3& wo, const glm::dvec3& wi) const;
    double pdf(const glm::dvec3& wo, const glm::dvec3& wi) const;
    // uLobe picks the lobe, u drives the direction (all in [0, 1)).
    BsdfSample sample(const glm::dvec3& wo, double uLobe, glm::dvec2 u) const;
    std::array<double, 4> lobeProbabilities(const glm::dvec3& wo) const;

private:
    PlyMaterial m_;
    Rgb bodyR_, bodyT_;  // rho_B r S' / pi and rho_B (1 - r) S' / pi
};

}  // namespace knit
