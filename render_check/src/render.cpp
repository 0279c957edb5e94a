// renderScene: validate, build tables and the Embree scene, place camera and light, render, write.
#include "knit/render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/image_io.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/scene.hpp"
#include "material_overrides.hpp"
#include "render_budget.hpp"
#include "render_image.hpp"
#include "scene_scale.hpp"
#include "trace_scene.hpp"
#include "trace_surface.hpp"
#include "util/math.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// An image path whose extension is not the format written to it (a .jpg holding PNG bytes).
void checkImageName(const std::string& path, const char* ext, const char* option, const char* format) {
    if (util::lowerExtension(path) != ext)
        throw Error(std::string("render: ") + option + " '" + path + "': only " + format +
                    " is written there (use a ." + ext + " name)");
}

}  // namespace

const char* lightPlacementName(LightPlacement light) {
    switch (light) {
        case LightPlacement::Front: return "front";
        case LightPlacement::Back: return "back";
    }
    return "?";
}

PlyMaterial resolveMaterial(const RenderOptions& o) {
    PlyMaterial m = o.material;
    if (!o.materialFile.empty()) m = loadMaterialFile(o.materialFile, m);
    if (!o.materialOverrides.empty()) m = applyMaterialOverrides(o.materialOverrides, m, "material flags");
    validateMaterial(m, o.materialFile.empty() ? "material" : "material file '" + o.materialFile + "'");
    return m;
}

RenderResult renderScene(const Scene& scene, const RenderOptions& o) {
    // Step 0: a scene far from metre size is traced as a copy at unit size (any scale renders).
    if (const std::optional<Scene> scaled = detail::sceneAtTracingScale(scene)) return renderScene(*scaled, o);
    // Step 1: validate every option before any work.
    if (o.light != LightPlacement::Front && o.light != LightPlacement::Back)
        throw Error("render: unknown light placement " + std::to_string(int(o.light)) + " (expected front or back)");
    const GeometryMode mode = o.mode;
    if (mode != GeometryMode::Curves && mode != GeometryMode::Tubes && mode != GeometryMode::Grid)
        throw Error("render: unknown geometry mode " + std::to_string(int(mode)) + " (expected curves, tubes or grid)");
    if (o.spp < 1) throw Error("render: samples per pixel must be at least 1 (got " + std::to_string(o.spp) + ")");
    if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
        throw Error("render: image size " + std::to_string(o.width) + " x " + std::to_string(o.height) +
                    " is outside 1..16384");
    if (o.maxDepth < 1 || o.maxDepth > 1000) throw Error("render: max depth must be in 1..1000");
    if (!(o.environment >= 0) || !(o.lightIrradiance >= 0) || !std::isfinite(o.environment) ||
        !std::isfinite(o.lightIrradiance))
        throw Error("render: environment and light irradiance must be finite and >= 0");
    if (!(o.fovDegrees > 1 && o.fovDegrees < 170)) throw Error("render: field of view must be in (1, 170) degrees");
    if (!(o.baseAlbedo >= 0 && o.baseAlbedo <= 1)) throw Error("render: base albedo must be in [0, 1]");
    if (mode == GeometryMode::Tubes && o.tubeSides < 3) throw Error("render: tube sides must be >= 3");
    RenderResult res;
    res.material = resolveMaterial(o);
    if (!o.surface && (scene.plies().curves.curveCount() == 0 || scene.plies().curves.pointCount() == 0))
        throw Error("render: the scene has no ply curves (nothing to render; were plies built?)");
    if (o.surface && scene.mesh().faces.empty()) throw Error("render: the surface level needs a base mesh");
    if (!o.output.empty()) checkImageName(o.output, "png", "--output", "PNG");
    if (!o.exr.empty()) checkImageName(o.exr, "exr", "--exr", "EXR");
    if (!o.output.empty()) checkWritable(o.output);
    if (!o.exr.empty()) checkWritable(o.exr);
    detail::checkRenderBudget(scene.plies(), o);
    res.mode = mode;
    res.light = o.light;
    res.spp = o.spp;
    // Step 2: ply segments relative to the centre of their bounds.
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : scene.plies().curves.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (o.surface) detail::surfaceBounds(scene, lo, hi);  // no plies: the mesh and the yarn height
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6);
    const PlyGeometry geometry = o.surface ? detail::surfaceFrame(scene, centre)
                                           : buildPlyGeometry(scene.plies(), centre, res.material.fiberTwist);
    res.segments = geometry.segmentCount();
    // Step 3: fiber tables.
    auto t0 = std::chrono::steady_clock::now();
    int plyCount = 1;
    for (uint8_t p : scene.plies().plyOfCurve) plyCount = std::max(plyCount, int(p) + 1);
    const FiberTables tables = buildFiberTables(fiberTableOptions(res.material, plyCount));
    res.tableSeconds = secondsSince(t0);
    res.tableBytes = tables.bytes();
    // Step 4: Embree scene of the chosen mode.
    t0 = std::chrono::steady_clock::now();
    EmbreeDevice device;
    std::vector<int64_t> cells;
    TraceSceneOptions so;
    so.mode = mode;
    so.tubeSides = o.tubeSides;
    so.baseMesh = o.baseMesh || o.surface ? &scene.mesh() : nullptr;
    const SurfaceTexture texture = detail::surfaceTexture(scene, o);
    so.baseTexture = o.surface ? &texture : nullptr;
    if (mode == GeometryMode::Grid && !o.surface) {
        cells = segmentCells(scene, geometry);
        so.segmentCells = &cells;
    }
    const TraceScene traceScene(device, geometry, so);
    res.buildSeconds = secondsSince(t0);
    res.memory = traceScene.memory();
    res.primitives = traceScene.primitiveCount();
    // Step 5: view. Cloth front = area-weighted mean normal of the base mesh.
    // A closed mesh has no front (its normals cancel up to rounding): look along the shortest
    // axis of the plies' bounds instead.
    glm::dvec3 normal(0.0);
    double normalLengths = 0;
    const std::vector<glm::dvec3>& positions = scene.mesh().positions;
    for (const glm::uvec3& f : scene.mesh().faces)
        if (f.x < positions.size() && f.y < positions.size() && f.z < positions.size()) {
            const glm::dvec3 n = glm::cross(positions[f.y] - positions[f.x], positions[f.z] - positions[f.x]);
            normal += n, normalLengths += glm::length(n);
        }
    if (glm::length(normal) > 1e-3 * normalLengths && normalLengths > 0) {
        normal = glm::normalize(normal);
    } else {
        const glm::dvec3 ext = hi - lo;
        const int axis = ext.x <= ext.y && ext.x <= ext.z ? 0 : (ext.y <= ext.z ? 1 : 2);
        normal = glm::dvec3(0.0);
        normal[axis] = 1.0;
    }
    // Image up: +y (glTF's up) unless the cloth faces +-y (lies flat); then -z, glTF's forward, so
    // a flat +Y-up cloth is framed as the same cloth standing in the xy plane would be.
    const glm::dvec3 helper = std::abs(normal.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, -1);
    const glm::dvec3 right = glm::normalize(glm::cross(helper, normal)), up = glm::cross(normal, right);
    TraceSettings ts;
    ts.width = o.width, ts.height = o.height, ts.spp = o.spp, ts.seed = o.seed, ts.maxDepth = o.maxDepth;
    const double dist = radius / std::sin(o.fovDegrees * util::kPi / 360.0);
    ts.camera.eye = centre + dist * normal;
    ts.camera.target = centre;
    ts.camera.up = up;
    ts.camera.fovYDegrees = o.fovDegrees;
    ts.environment = Rgb(o.environment);
    ts.baseAlbedo = Rgb(o.baseAlbedo);
    // Front: a light of the cloth's radius up and to the right of the camera. Back: a lightbox
    // larger than the cloth behind it, so transmission shows everywhere.
    const bool front = o.light == LightPlacement::Front;
    const double lightSize = front ? radius : 3.0 * radius, lightDist = 2.5 * radius;
    const glm::dvec3 dir = front ? glm::normalize(normal + 0.4 * right + 0.4 * up) : -normal;
    const glm::dvec3 lc = centre + lightDist * dir;
    // Light facing the centre: edges perpendicular to dir, cross(edgeU, edgeV) = -dir.
    const glm::dvec3 lh = std::abs(dir.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 eu = glm::normalize(glm::cross(dir, lh)) * lightSize;
    const glm::dvec3 ev = glm::normalize(glm::cross(eu, dir)) * lightSize;
    ts.light.corner = lc - 0.5 * eu - 0.5 * ev;
    ts.light.edgeU = eu;
    ts.light.edgeV = ev;
    // Irradiance at the centre ~ L A / d^2 (light facing it): choose L for the requested irradiance.
    ts.light.radiance = Rgb(o.lightIrradiance * lightDist * lightDist / (lightSize * lightSize));
    // Step 6: render, with progress on stderr for long renders.
    std::mutex progressMutex;
    int lastDecile = 0;
    if (o.progress && double(o.width) * o.height * o.spp > 1e6) {
        ts.progress = [&](double f) {
            std::lock_guard<std::mutex> lock(progressMutex);
            const int decile = static_cast<int>(f * 10);
            if (decile > lastDecile) {
                lastDecile = decile;
                std::fprintf(stderr, "render: %d%%\n", decile * 10);
            }
        };
    }
    res.camera = ts.camera;
    res.areaLight = ts.light;
    TraceStats stats;
    res.image = renderImage(traceScene, res.material, tables, ts, &stats);
    res.renderSeconds = stats.seconds;
    res.rays = stats.rays;
    res.raysPerSecond = stats.seconds > 0 ? stats.rays / stats.seconds : 0;
    // Step 7: images.
    if (!o.output.empty()) writePng(o.output, res.image), res.written.push_back(o.output);
    if (!o.exr.empty()) writeExr(o.exr, res.image), res.written.push_back(o.exr);
    res.peakMemoryBytes = int64_t(util::peakResidentBytes());
    return res;
}

}  // namespace knit
