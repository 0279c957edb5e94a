// Ply BSDF: R (anisotropic GGX + dielectric Fresnel), TT (mirrored GGX), Lambertian body lobes.
#include "knit/ply_bsdf.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "microfacet.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

using util::kInvPi;
using util::kPi;

// Mirror a direction into the upper hemisphere (z >= 0).
glm::dvec3 upper(const glm::dvec3& w) { return {w.x, w.y, std::abs(w.z)}; }

// Unweighted microfacet reflection value D G2 / (4 o_z i_z) and the Fresnel cosine, for o, i with
// positive z. Returns 0 if the half vector is degenerate.
double microfacet(const glm::dvec3& o, const glm::dvec3& i, double ax, double ay, double& cosOH) {
    glm::dvec3 h = o + i;
    const double len = glm::length(h);
    if (len < 1e-12 || o.z <= 0 || i.z <= 0) return 0.0;
    h /= len;
    cosOH = std::abs(glm::dot(o, h));
    const double g2 = 1.0 / (1.0 + ggxLambda(o, ax, ay) + ggxLambda(i, ax, ay));
    return ggxD(h, ax, ay) * g2 / (4.0 * o.z * i.z);
}

// Density of reflecting o about a visible normal: G1(o) D(h) / (4 o_z), for o, i with positive z.
double reflectPdf(const glm::dvec3& o, const glm::dvec3& i, double ax, double ay) {
    glm::dvec3 h = o + i;
    const double len = glm::length(h);
    if (len < 1e-12 || o.z <= 0 || i.z <= 0) return 0.0;
    h /= len;
    return ggxG1(o, ax, ay) * ggxD(h, ax, ay) / (4.0 * o.z);
}

glm::dvec3 cosineHemisphere(glm::dvec2 u) {
    const double r = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x))};
}

}  // namespace

double luminance(const Rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

double fresnelDielectric(double cosTheta, double eta) {
    const double ci = std::min(1.0, std::abs(cosTheta));
    const double sin2t = (1.0 - ci * ci) / (eta * eta);
    if (sin2t >= 1.0) return 1.0;
    const double ct = std::sqrt(1.0 - sin2t);
    const double rPar = (eta * ci - ct) / (eta * ci + ct);
    const double rPerp = (ci - eta * ct) / (ci + eta * ct);
    return 0.5 * (rPar * rPar + rPerp * rPerp);
}

double ggxD(const glm::dvec3& h, double ax, double ay) {
    const double e = (h.x * h.x) / (ax * ax) + (h.y * h.y) / (ay * ay) + h.z * h.z;
    return 1.0 / (kPi * ax * ay * e * e);
}

double ggxLambda(const glm::dvec3& w, double ax, double ay) {
    const double z2 = w.z * w.z;
    if (z2 <= 0) return 1e30;
    const double a2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
    return 0.5 * (-1.0 + std::sqrt(1.0 + a2));
}

double ggxG1(const glm::dvec3& w, double ax, double ay) { return 1.0 / (1.0 + ggxLambda(w, ax, ay)); }

glm::dvec3 ggxSampleVisibleNormal(const glm::dvec3& w, double ax, double ay, glm::dvec2 u) {
    // Heitz 2018: stretch to the hemisphere configuration, sample the projected disk, unstretch.
    const glm::dvec3 vh = glm::normalize(glm::dvec3(ax * w.x, ay * w.y, w.z));
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const glm::dvec3 t1 = lensq > 0 ? glm::dvec3(-vh.y, vh.x, 0) / std::sqrt(lensq) : glm::dvec3(1, 0, 0);
    const glm::dvec3 t2 = glm::cross(vh, t1);
    const double r = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
    const double p1 = r * std::cos(phi);
    double p2 = r * std::sin(phi);
    const double s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
    const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::dvec3(ax * nh.x, ay * nh.y, std::max(1e-9, nh.z)));
}

PlyBsdf::PlyBsdf(const PlyMaterial& material, double shadow) : PlyBsdf(material, shadow, material.bodyAlbedo) {}

PlyBsdf::PlyBsdf(const PlyMaterial& material, double shadow, const Rgb& bodyAlbedo) : m_(material) {
    const double s = std::clamp(shadow, 0.0, 1.0);
    m_.bodyAlbedo = bodyAlbedo;
    bodyR_ = m_.bodyAlbedo * (m_.reflectFraction * s * kInvPi);
    bodyT_ = m_.bodyAlbedo * ((1.0 - m_.reflectFraction) * s * kInvPi);
}

Rgb PlyBsdf::eval(const glm::dvec3& wo, const glm::dvec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return Rgb(0.0);
    const glm::dvec3 o = upper(wo), i = upper(wi);  // i = flip(wi) mirrored up for TT
    double cosOH = 1.0;
    if (wo.z * wi.z > 0) {
        const double spec = microfacet(o, i, m_.alphaAlong, m_.alphaAcross, cosOH);
        return m_.kR * (spec * fresnelDielectric(cosOH, m_.eta)) + bodyR_;
    }
    const double spec = microfacet(o, i, m_.alphaTT, m_.alphaTT, cosOH);
    return m_.kTT * (spec * (1.0 - fresnelDielectric(cosOH, m_.eta))) + bodyT_;
}

std::array<double, 4> PlyBsdf::lobeProbabilities(const glm::dvec3& wo) const {
    const double f = fresnelDielectric(wo.z, m_.eta);
    std::array<double, 4> w = {luminance(m_.kR) * f, luminance(m_.kTT) * (1.0 - f), luminance(bodyR_),
                               luminance(bodyT_)};
    const double sum = w[0] + w[1] + w[2] + w[3];
    for (double& x : w) x = sum > 0 ? x / sum : 0.0;
    return w;
}

double PlyBsdf::pdf(const glm::dvec3& wo, const glm::dvec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return 0.0;
    const std::array<double, 4> p = lobeProbabilities(wo);
    const glm::dvec3 o = upper(wo), i = upper(wi);
    if (wo.z * wi.z > 0) return p[R] * reflectPdf(o, i, m_.alphaAlong, m_.alphaAcross) + p[BodyR] * i.z * kInvPi;
    return p[TT] * reflectPdf(o, i, m_.alphaTT, m_.alphaTT) + p[BodyT] * i.z * kInvPi;
}

BsdfSample PlyBsdf::sample(const glm::dvec3& wo, double uLobe, glm::dvec2 u) const {
    BsdfSample out;
    if (wo.z == 0) return out;
    const std::array<double, 4> p = lobeProbabilities(wo);
    // Step 1: pick the lobe.
    int lobe = 0;
    double acc = p[0];
    while (lobe < 3 && uLobe >= acc) acc += p[++lobe];
    if (p[lobe] <= 0) return out;
    // Step 2: draw a direction in the upper hemisphere for o mirrored up.
    const double side = wo.z > 0 ? 1.0 : -1.0;
    const glm::dvec3 o = upper(wo);
    glm::dvec3 i;
    if (lobe == R || lobe == TT) {
        const double ax = lobe == R ? m_.alphaAlong : m_.alphaTT, ay = lobe == R ? m_.alphaAcross : m_.alphaTT;
        const glm::dvec3 h = ggxSampleVisibleNormal(o, ax, ay, u);
        i = 2.0 * glm::dot(o, h) * h - o;
        if (i.z <= 0) return out;
    } else {
        i = cosineHemisphere(u);
        if (i.z <= 0) return out;
    }
    // Step 3: put it on the side of the lobe (same side as wo for R / BR, opposite for TT / BT).
    const bool sameSide = lobe == R || lobe == BodyR;
    out.wi = glm::dvec3(i.x, i.y, (sameSide ? side : -side) * i.z);
    out.lobe = lobe;
    out.pdf = pdf(wo, out.wi);
    if (!(out.pdf > 0)) return out;
    out.weight = eval(wo, out.wi) * (std::abs(out.wi.z) / out.pdf);
    out.valid = true;
    return out;
}

}  // namespace knit
