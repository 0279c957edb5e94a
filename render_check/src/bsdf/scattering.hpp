// scattering.hpp (internal) — what the path tracer scatters light with at a hit, one of three kinds
// behind one interface (tracing/path_tracer.cpp calls only eval and sample):
//   - the ply BSDF (knit/ply_bsdf.hpp): plies and yarn-level curves;
//   - the surface level's measured scattering table (knit/surface_scattering.hpp) times the
//     texel's tint over the probability that the surface filter keeps the hit;
//   - a two-sided Lambertian reflector with diffuse transmission: the base mesh, and a surface bake
//     without a table.
// Directions are local to the shading frame (z the shading normal), both pointing away from the
// surface; values include |cos wi|. The caller rejects directions whose shading and geometric sides
// disagree before asking.
#pragma once
#include <algorithm>
#include <cmath>
#include <variant>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/ply_bsdf.hpp"
#include "knit/surface_scattering.hpp"
#include "util/math.hpp"

namespace knit::impl {

// A sampled incident direction, its weight f |cos wi| / pdf and its pdf; not valid: end the path.
struct ScatterSample {
    glm::dvec3 wi{0.0};
    Rgb weight{0.0};
    double pdf = 0;
    bool valid = false;
};

// The ply BSDF as the tracer uses it.
struct PlyScattering {
    PlyBsdf bsdf;

    Rgb eval(const glm::dvec3& wo, const glm::dvec3& wi, double& pdf) const {
        pdf = bsdf.pdf(wo, wi);
        return bsdf.eval(wo, wi) * std::abs(wi.z);
    }
    template <class Random>
    ScatterSample sample(const glm::dvec3& wo, Random& rng) const {
        // The three numbers drawn in a set order (a braced list is sequenced; call arguments are not,
        // so the image for a seed would depend on the compiler).
        const double u[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
        const BsdfSample bs = bsdf.sample(wo, u[0], glm::dvec2(u[1], u[2]));
        return {bs.wi, bs.weight, bs.pdf, bs.valid};
    }
};

// The measured scattering of the surface level; `scale` is the texel's tint over the probability
// of the hit (1 - pass of the outgoing direction).
struct TableScattering {
    const SurfaceScattering* table;
    Rgb scale;

    Rgb eval(const glm::dvec3& wo, const glm::dvec3& wi, double& pdf) const {
        pdf = table->pdf(wo, wi);
        return scale * table->eval(wo, wi);
    }
    template <class Random>
    ScatterSample sample(const glm::dvec3& wo, Random& rng) const {
        ScatterSample s;
        const double u[4] = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
        s.wi = table->sample(wo, u, s.pdf);
        if (!(s.pdf > 0)) return s;
        s.weight = scale * table->eval(wo, s.wi) / s.pdf;
        s.valid = true;
        return s;
    }
};

// Lambertian reflection (albedo) on both sides plus diffuse transmission (transmit); sampled on
// the reflection side with probability reflectChance.
struct DiffuseScattering {
    Rgb albedo{0.0}, transmit{0.0};
    double reflectChance = 1;

    Rgb eval(const glm::dvec3& wo, const glm::dvec3& wi, double& pdf) const {
        if (wi.z == 0 || wo.z == 0) return Rgb(0.0);
        const double c = std::abs(wi.z) / util::kPi;
        const bool reflect = wi.z * wo.z > 0;
        pdf = (reflect ? reflectChance : 1 - reflectChance) * c;
        return (reflect ? albedo : transmit) * c;
    }
    template <class Random>
    ScatterSample sample(const glm::dvec3& wo, Random& rng) const {
        // The side by reflectChance (no extra random number without transmission), then a
        // cosine-weighted direction on it.
        ScatterSample s;
        const bool reflect = reflectChance >= 1 || rng.uniform() < reflectChance;
        const double u1 = rng.uniform(), u2 = rng.uniform();
        const double rr = std::sqrt(u1), ph = 2 * util::kPi * u2;
        s.wi = glm::dvec3(rr * std::cos(ph), rr * std::sin(ph), std::sqrt(std::max(0.0, 1 - u1)));
        if ((wo.z < 0) == reflect) s.wi.z = -s.wi.z;
        const double chance = reflect ? reflectChance : 1 - reflectChance;
        s.weight = (reflect ? albedo : transmit) / chance;
        s.pdf = chance * std::abs(s.wi.z) / util::kPi;
        s.valid = s.pdf > 0;
        return s;
    }
};

// One of the three kinds; eval and sample dispatch to it.
class Scattering {
public:
    Scattering(PlyScattering s) : kind_(s) {}      // NOLINT(google-explicit-constructor)
    Scattering(TableScattering s) : kind_(s) {}    // NOLINT(google-explicit-constructor)
    Scattering(DiffuseScattering s) : kind_(s) {}  // NOLINT(google-explicit-constructor)

    // f |cos wi| and the pdf sample() draws wi with (pdf 0 where it never does).
    Rgb eval(const glm::dvec3& wo, const glm::dvec3& wi, double& pdf) const {
        pdf = 0;
        return std::visit([&](const auto& k) { return k.eval(wo, wi, pdf); }, kind_);
    }
    // An incident direction for wo, drawn with the numbers of rng.uniform().
    template <class Random>
    ScatterSample sample(const glm::dvec3& wo, Random& rng) const {
        return std::visit([&](const auto& k) { return k.sample(wo, rng); }, kind_);
    }

private:
    std::variant<PlyScattering, TableScattering, DiffuseScattering> kind_;
};

}  // namespace knit::impl
