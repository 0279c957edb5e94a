// knit/render.hpp — `knit render`: render a Scene's plies with the ply BSDF, front-lit or back-lit,
// in one of three geometry modes, and report time, rays/s and memory.
//
// View: the scene's own when it was built for one (SceneOptions::detail), else RenderOptions::view,
// else the default camera (knit::frameMesh): it looks at the bounding sphere of the base mesh grown
// by the yarns' height and radius along the mesh's mean normal (the cloth's front); for a closed or
// nearly closed mesh (mean normal below 1e-3 of the mean normal length, e.g. a cylinder or sphere)
// along the shortest axis of those bounds instead. Camera and light come from the base mesh, never
// from generated geometry, so every level of detail frames and lights a scene identically.
// A scene built for a view renders the plies of its ply-level cells, the yarn curves of its
// yarn-level cells (curves mode; the ply BSDF on a curve of the yarn radius) and the base-mesh
// triangles of its surface-level cells shaded with the pattern baked with the render's material
// (knit/bake.hpp: coverage as an alpha mask, baked albedo; RenderOptions::viewBakeSize). `front` puts the rectangular light on the camera side (up and to the right),
// `back` puts it behind the cloth facing the camera, so the image shows transmitted light.
// The base mesh is the cloth's mid-surface: it lies inside the yarns and would hide the back
// plies and block transmission, so it is NOT rendered unless `baseMesh` is set (then as an
// opaque two-sided diffuse surface).
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "knit/budget.hpp"
#include "knit/path_tracer.hpp"
#include "knit/pattern.hpp"
#include "knit/ply_material.hpp"
#include "knit/trace_mode.hpp"
#include "knit/view.hpp"

namespace knit {

class Scene;
struct SurfaceBake;

// Where the area light is: on the camera side (reflection) or behind the cloth (transmission).
enum class LightPlacement { Front, Back };
const char* lightPlacementName(LightPlacement light);  // "front" | "back" (as in the report)

struct RenderOptions {
    LightPlacement light = LightPlacement::Front;
    GeometryMode mode = GeometryMode::Curves;
    int spp = 16;
    int width = 512, height = 384;
    std::string output;  // PNG (sRGB); empty = no file
    std::string exr;     // linear EXR; empty = none
    uint64_t seed = 1;
    PlyMaterial material;      // base material
    std::string materialFile;  // JSON material (fields override `material`)
    // Explicit per-field overrides applied after the file (field -> 1 or 3 numbers).
    std::map<std::string, std::vector<double>> materialOverrides;
    int maxDepth = 16;
    double environment = 0.05;     // constant environment radiance
    double lightIrradiance = 3.0;  // irradiance the light gives at the cloth centre (W/m^2-ish units)
    double fovDegrees = 30;
    // Eye, target and up of the camera (its field of view and image size are the fields above);
    // none: the default camera. Ignored for a scene built for a view (it renders that view).
    std::optional<View> view;
    bool baseMesh = false;
    double baseAlbedo = 0.5;
    int tubeSides = 8;
    bool progress = true;  // progress on stderr for renders of more than ~1e6 samples
    // Surface level (knit/bake.hpp): the base mesh shaded with this bake as the surface GLB shows
    // it (alpha MASK at 0.5 of the coverage, the baked albedo, one texture tile per pattern
    // period) instead of the plies, which the scene then need not have. Framed by the mesh's
    // bounds grown by the yarn radius.
    const SurfaceBake* surface = nullptr;
    double surfaceRepeats[2] = {0, 0};  // texture tiles across u and v; 0 = the scene's placement
    // A scene built for a view (--detail view) draws its surface-level cells as the base mesh
    // with the pattern baked at this width (pixels per pattern period) with the render's material;
    // 0 = viewBakeWidth: what the surface level can need.
    int viewBakeSize = 0;
    // Paths per direction bin, on average, of the scattering table of that bake
    // (knit/surface_scattering.hpp, BakeOptions::scatteringFocus: most go to the directions the
    // view's camera and light need): the surface level is shaded with the measured scattering of
    // the plies, for every light and view direction; 0 = the Lambertian albedo and the coverage
    // MASK of the exported material.
    int surfaceScatteringPaths = 6144;
    // The image buffers (--width x --height) and the geometry of the mode (Embree curves,
    // tubes of tubeSides, grid cells) are estimated before either is allocated and refused over
    // this budget (the CLI passes --max-memory).
    MemoryBudget budget;
};

// The bake width a view's surface level needs: 4 texels per pixel where its pattern period looks
// largest, period / yarn radius x `yarnPixels` pixels (the largest projected yarn radius of the
// view's surface-level cells), rounded up to a multiple of 16, within 64..256.
int viewBakeWidth(const Pattern& pattern, double yarnPixels);

struct RenderResult {
    Image image;
    GeometryMode mode = GeometryMode::Curves;
    LightPlacement light = LightPlacement::Front;
    int spp = 0;
    PlyMaterial material;  // as resolved and validated
    double tableSeconds = 0, buildSeconds = 0, renderSeconds = 0;
    uint64_t rays = 0;
    double raysPerSecond = 0;
    TraceMemory memory;
    size_t tableBytes = 0;
    int64_t peakMemoryBytes = 0;  // process peak resident set size
    size_t segments = 0, primitives = 0;
    Camera camera;                 // the view used (world space)
    View view;                     // the same as a knit::View
    size_t surfaceTriangles = 0;   // base-mesh triangles of the surface level (scene built for a view)
    bool surfaceTextured = false;  // those triangles were shaded with a bake of the pattern
    double bakeSeconds = 0;        // time of that bake
    RectLight areaLight;           // the area light used (world space)
    std::vector<std::string> written;
};

// Resolves the material (defaults <- file <- overrides), validates everything before rendering
// (knit::Error: bad material, spp < 1, bad size, unknown light/mode, empty scene, unwritable
// output path), builds the tables and the Embree scene, renders and writes the images.
RenderResult renderScene(const Scene& scene, const RenderOptions& options);

// The view renderScene renders the scene with (see the file comment); knit::Error naming the
// option for a bad view.
View renderView(const Scene& scene, const RenderOptions& options);

// Resolved + validated material of the options (used by renderScene).
PlyMaterial resolveMaterial(const RenderOptions& options);

}  // namespace knit
