// knit/surface_scattering.hpp — the cloth seen from afar as a surface: how one pattern cell of
// plies scatters light, averaged over the cell, tabulated over pairs of directions (a measured
// BSDF of the knit, with the light that passes through the holes kept apart).
//
// Directions are in the cell's tangent space, as the baked normal map: x = +u (pattern x),
// y = +v (pattern y), z out of the cloth's front (the side the yarn heights grow towards).
// Each side of the cloth (hemisphere) is cut into side x side bins of equal solid angle
// (2 pi / side^2): the hemisphere is mapped to the unit disk by Lambert's equal-area projection
// (disk radius sqrt(1 - |z|), same azimuth), the disk to the square [-1, 1]^2 by Shirley and
// Chiu's concentric map (area-preserving), and the square into a side x side grid. Bin
// h side^2 + row side + column: h = 0 for the back (z < 0), 1 for the front (z >= 0), so no bin
// straddles the cloth. Unlike bands of z, no bin meets the normal in a point: the directions near
// the normal, where a far camera and its light mostly are, are resolved as finely as the others.
// For light leaving towards `out` (a direction away from the cloth, on either side):
// - pass(out): the fraction of straight lines along -out that cross the cloth without touching
//   yarn (the holes, as seen from `out`);
// - table(out, in): the fraction of radiance arriving from the directions of bin `in` (uniform
//   over the bin) that the yarns scatter towards `out`, per unit of the cloth's projected area.
//   A surface with BSDF f has table(out, in) = integral over bin `in` of f(wi, out) |cos theta_i|,
//   so f |cos theta_i| = table / binSolidAngle(), interpolated between bin centres.
// The radiance towards `out` is then pass(out) L(-out) + sum over `in` of table(out, in) L(in):
// exact for light uniform over each bin, up to the noise of the measurement (bake.hpp).
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "knit/ply_bsdf.hpp"

namespace knit {

struct SurfaceScattering {
    int side = 0;              // bins along each side of a hemisphere's square
    std::vector<float> table;  // bins() x bins() x 3 (linear RGB), row = out bin, column = in bin
    std::vector<float> pass;   // bins()
    size_t paths = 0;          // measured paths (all bins)

    bool empty() const { return table.empty(); }
    int bins() const { return 2 * side * side; }
    double binSolidAngle() const;
    int binOf(const glm::dvec3& w) const;  // w need not be normalized (it must not be zero)
    // A unit direction in bin `bin` from two uniform numbers in [0, 1): uniform in solid angle
    // over the bin; (0.5, 0.5) is the bin's centre.
    glm::dvec3 binDirection(int bin, double u, double v) const;
    // The mean |cos theta| over the bin.
    double binCosine(int bin) const;

    // Tabulates the sampling distributions of the rows (call after filling table and pass).
    void prepare();

    // Pass fraction towards `out`, interpolated between bin centres on out's side of the cloth.
    double passAt(const glm::dvec3& out) const;
    // f(in, out) |cos theta_in| in 1/sr, interpolated in both directions (each on its own side).
    Rgb eval(const glm::dvec3& out, const glm::dvec3& in) const;
    // Density (1/sr) with which sample() picks `in` for `out`.
    double pdf(const glm::dvec3& out, const glm::dvec3& in) const;
    // A direction for `out` from four uniform numbers in [0, 1): a row by the interpolation
    // weights, a bin of that row by its tabulated luminance (with a uniform floor), a uniform
    // direction in the bin. pdf = 0 when nothing can be sampled.
    glm::dvec3 sample(const glm::dvec3& out, const double u[4], double& pdf) const;
    // The bins and weights (summing to 1) that eval and passAt interpolate between for `w`.
    void interpolationCorners(const glm::dvec3& w, int bins[4], double weights[4]) const;

    // Tabulated per row after prepare(): the cumulative probability of each bin.
    std::vector<float> cdf;
};

}  // namespace knit
