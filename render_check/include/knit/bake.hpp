// knit/bake.hpp — the surface level of detail: one periodic pattern cell baked into tileable
// textures (albedo, tangent-space normal, height, coverage) with the project's Embree tracer.
//
// Conventions (docs/views.md, "Surface level: baked textures"):
// - The cell is the pattern's tile (0, 0): pattern x in [0, px), y in [0, py). Image column i and
//   row r (row 0 at the top) sample the pattern point ((i + a) / N px, (1 - (r + b) / M) py) for
//   sub-pixel offsets a, b in (0, 1), so the image's up is +y (+v) as in glTF's texture space,
//   and the texture repeats exactly where the pattern does (pixel centres sit at (i + 0.5) / N of
//   the period: the left and right columns are neighbours across the period, as are the top and
//   bottom rows).
// - The plies are generated on the tiles around the cell (tileReach plus one tile each way, one
//   more towards +x and +y for a shifted origin: at least 4 x 4) lying flat in z = 0 (surface normal +z), so the cell's edges see their
//   neighbours. Each yarn's ply pitch is adjusted so that one period of the yarn holds a whole
//   number of ply turns (after the frame's own rotation over the period): the plies, and so the
//   textures, repeat with the pattern.
// - Rays are orthographic, straight down (-z). Per sub-pixel sample the first hit gives coverage
//   (hit or not), height and the normal; albedo is the radiance the hit sends straight up under a
//   uniform white sky over the cloth (radiance 1 from every direction with z > 0, black below:
//   the body under the garment), path traced with the ply BSDF. A Lambertian surface of albedo a
//   sends exactly a there, so it is the diffuse colour the base mesh needs under even light.
//   The same paths give the transmittance: the radiance sent straight up under a white sky below
//   the cloth alone (the light that comes through the yarns, not through the holes), which the
//   renderer's surface level uses as diffuse transmission (back light, an environment behind).
// - Normals are tangent space: x along +u (pattern x), y along +v (pattern y), z out of the cloth.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/pattern.hpp"
#include "knit/plies.hpp"
#include "knit/tiling.hpp"
#include "knit/ply_material.hpp"
#include "knit/surface_scattering.hpp"

namespace knit {

// A direction (the cell's tangent space, knit/surface_scattering.hpp) where a render needs the
// scattering table most, with its weight (e.g. the projected area of the surface seen or lit so).
struct ScatteringFocus {
    glm::dvec3 direction{0, 0, 1};
    double weight = 1;
};

struct BakeOptions {
    int width = 256;         // N, pixels along the period px; M = round(N py / px), at least 1
    int samplesPerAxis = 4;  // s x s stratified sub-pixel samples (coverage, height, normal)
    int albedoPaths = 1;     // paths per sub-pixel sample that hits yarn (albedo)
    int maxBounces = 4;      // path length of the albedo estimate
    PlyOptions plies;        // yarnRadius 0 = the pattern's radius; pitch 0 = 6 yarn radii
    PlyMaterial material;    // the ply BSDF (validated)
    uint64_t seed = 1;       // albedo paths; the same seed gives the same textures
    // Paths per direction bin of SurfaceBake::scattering on average (0 = no table). The
    // renderer's surface level shades with the table when there is one.
    int scatteringPaths = 0;
    int scatteringSide = 12;  // SurfaceScattering::side (1..32): 2 x 12 x 12 bins of ~0.044 sr
    // Where the table is needed most (a render's camera and light seen from its surface-level
    // triangles): `scatteringFocusShare` of the paths go to the bins of these directions (split
    // between each direction's interpolation corners by weight), the rest evenly to every bin.
    // A table entry is estimated from the paths of its row and, by reciprocity, of its column,
    // so the entries between the camera's and the light's directions get most of the paths.
    // Empty: every bin gets scatteringPaths.
    std::vector<ScatteringFocus> scatteringFocus;
    double scatteringFocusShare = 0.75;
    bool periodicPitch = true;  // adjust each yarn's ply pitch so the plies repeat (see above)
    // Where the baked cell starts, in periods (each in [0, 1)): the cell is
    // [origin[0], origin[0] + 1) px x [origin[1], origin[1] + 1) py (the image's bottom-left corner
    // at origin). A shifted origin rolls the texture (same pattern, other seam).
    double origin[2] = {0, 0};
    // How the placement stretches the pattern along x and y at constant area (placementStretch):
    // the cell is baked as it lies on the mesh (a square period on the mesh squeezes the
    // stockinette's wide stitch by 15% across and stretches it along the wale).
    double stretch[2] = {1, 1};
};

struct SurfaceBake {
    int width = 0, height = 0;            // N x M pixels, row-major from the top
    std::vector<float> albedo;            // linear RGB, 3 per pixel, averaged over the hits (straight
                                          // colour: pixels without any hit take the mean of the others)
    std::vector<float> transmittance;     // linear RGB, 3 per pixel, as albedo (light through the yarn)
    std::vector<float> normal;            // unit tangent-space normal, 3 per pixel ((0, 0, 1) without hit)
    std::vector<float> heights;           // first-hit height in [0, 1] over [heightMin, heightMax] (0 without hit)
    std::vector<float> coverage;          // fraction of the sub-pixel rays that hit yarn, [0, 1]
    double period[2] = {0, 0};            // px, py (metres, pattern space)
    double heightMin = 0, heightMax = 0;  // metres above the mid-surface mapped to height 0 and 1
    std::vector<double> yarnPitch;        // ply pitch used per generated yarn (metres)
    SurfaceScattering scattering;         // the cell as a surface (BakeOptions::scatteringPaths)
    size_t plySegments = 0;               // traced ply segments (all tiles)
    double seconds = 0;                   // wall time of the bake
    double meanCoverage() const;
};

// Throws knit::Error naming the option (width 1..8192, samplesPerAxis 1..64, albedoPaths 0..1024,
// maxBounces 1..64, origin in [0, 1)) or the pattern / material / ply problem. Deterministic for any thread count.
SurfaceBake bakeSurface(const Pattern& pattern, const BakeOptions& options);

// Ply options given in object-space metres (a scene's, placed at `scale` pattern units to the
// metre) as the bake needs them: in the pattern's own units, the yarn radius the pattern's.
PlyOptions patternPlyOptions(PlyOptions plies, const Pattern& pattern, double scale);

// The placement's per-axis factors over their geometric mean: (sx / scale, sy / scale) with
// sx = periodMetres.x / px, sy = periodMetres.y / py (knit/tiling.hpp); (1, 1) when unknown.
glm::dvec2 placementStretch(const Pattern& pattern, const PatternPlacement& placement);

// 8-bit images of a bake, row-major from the top (PNG-ready):
// base colour RGBA (sRGB albedo, alpha = coverage), normal RGB ((n + 1) / 2), height grey.
std::vector<uint8_t> baseColorRgba8(const SurfaceBake& bake);
std::vector<uint8_t> normalRgb8(const SurfaceBake& bake);
std::vector<uint8_t> heightGray8(const SurfaceBake& bake);

}  // namespace knit
