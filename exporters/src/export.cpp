// export.cpp — exportScene(): pick the curves, validate options, dispatch on the extension.
#include "knit/export.hpp"

#include <chrono>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "export_budget.hpp"
#include "formats.hpp"
#include "knit/error.hpp"
#include "material_extras.hpp"
#include "scene_checks.hpp"
#include "surface_gltf.hpp"
#include "util/checks.hpp"
#include "util/csr.hpp"
#include "util/platform.hpp"

namespace knit {

namespace {

// A scene format (one exportScene writes), or null.
const impl::Format* sceneFormat(const std::string& path) {
    const impl::Format* f = impl::formatOf(path);
    return f && !f->pointCache ? f : nullptr;
}
bool isGltf(const std::string& path) {
    const impl::Format* f = sceneFormat(path);
    return f && f->gltf;
}

const char* whatName(ExportWhat w) {
    switch (w) {
        case ExportWhat::Yarns: return "yarns";
        case ExportWhat::Plies: return "plies";
        case ExportWhat::Tubes: return "tubes";
    }
    return "?";
}

// Step: the offsets span the points and never decrease, so every curve's range lies inside the
// points; checked for all curves before any point is read.
void validateOffsets(const Polylines& c) {
    if (!util::offsetEnds(c.offsets, c.curveCount(), c.pointCount()))
        throw Error("cannot export: inconsistent curve offsets (" + std::to_string(c.offsets.size()) + " offsets, " +
                    std::to_string(c.closed.size()) + " curves, " + std::to_string(c.points.size()) + " points)");
    for (size_t k = 0; k < c.curveCount(); ++k) {
        if (c.offsets[k + 1] > c.pointCount())
            throw Error("cannot export: curve " + std::to_string(k) + " ends at offset " +
                        std::to_string(c.offsets[k + 1]) + ", past the " + std::to_string(c.pointCount()) + " points");
        if (c.offsets[k + 1] < c.offsets[k])
            throw Error("cannot export: curve " + std::to_string(k) + " has decreasing offsets");
    }
}

// Step: every point finite (user data problems are reported before any numeric loop runs).
// Generated plies were validated by their PlyGenerator.
void validateInput(const ExportInput& in, bool tubes) {
    if (!in.curves && !in.plies) throw Error("cannot export: no curves given");
    if (in.curves && in.plies) throw Error("cannot export: both curves and a ply generator given; pass one");
    impl::parseMaterialExtras(in.materialExtrasJson);  // throws unless empty or a JSON object
    if (in.plies) {
        if (!util::positiveFinite(in.radius))
            throw Error("cannot export: radius must be a positive number, got " + std::to_string(in.radius));
        return;
    }
    const Polylines& c = *in.curves;
    validateOffsets(c);
    for (size_t k = 0; k < c.curveCount(); ++k) {
        for (uint32_t i = c.begin(k); i < c.end(k); ++i) {
            if (!util::finite(c.points[i]))
                throw Error("cannot export: curve " + std::to_string(k) + " point " + std::to_string(i - c.begin(k)) +
                            " is not finite");
        }
    }
    (void)tubes;
    if (!util::positiveFinite(in.radius))
        throw Error("cannot export: radius must be a positive number, got " + std::to_string(in.radius));
    if (in.yarnOfCurve && in.yarnOfCurve->size() != c.curveCount())
        throw Error("cannot export: " + std::to_string(in.yarnOfCurve->size()) + " yarn indices for " +
                    std::to_string(c.curveCount()) + " curves");
    if (in.seedNormals && in.seedNormals->size() != c.points.size())
        throw Error("cannot export: " + std::to_string(in.seedNormals->size()) + " surface normals for " +
                    std::to_string(c.points.size()) + " points");
    if (in.colours && in.colours->size() != c.points.size())
        throw Error("cannot export: colours have " + std::to_string(in.colours->size()) + " entries for " +
                    std::to_string(c.points.size()) + " points");
}

// A tube-mesh glTF extension (mesh quantization, meshopt compression) needs a .glb/.gltf output
// and tubes.
void requireGltfTubes(const ExportOptions& o, bool tubes, const char* setting, const char* extension) {
    if (!isGltf(o.path))
        throw Error("cannot export '" + o.path + "': " + setting + " needs a .glb or .gltf output (" + extension +
                    " is a glTF extension)");
    if (!tubes)
        throw Error("cannot export '" + o.path + "': " + setting + " applies to tube meshes only; what to export is " +
                    whatName(o.what) + ", not tubes");
}

}  // namespace

bool streamsPlies(const ExportOptions& o) { return o.what == ExportWhat::Plies && isGltf(o.path); }

void validateExportOptions(const ExportOptions& o) {
    const std::string ext = util::lowerExtension(o.path);
    if (o.path.empty()) throw Error("cannot export: no output path given");
    const impl::Format* format = sceneFormat(o.path);
    if (!format)
        throw Error("cannot export '" + o.path + "': unknown extension '" + (ext.empty() ? "" : "." + ext) +
                    "' (supported: " + impl::sceneFormatList(", ") + ")");
    const bool tubes = o.what == ExportWhat::Tubes;
    if (tubes && !format->tubes)
        throw Error("cannot export '" + o.path + "': ." + ext + " holds curves only: what to export must be yarns or " +
                    "plies (tubes need " + impl::sceneFormatList("/", true) + ")");
    if (o.sides < 3 || o.sides > 1024)
        throw Error("cannot export: the number of tube sides must be in [3, 1024], got " + std::to_string(o.sides));
    if (o.draco) {
        if (!format->gltf)
            throw Error("cannot export '" + o.path + "': Draco compression needs a .glb or .gltf output, not ." + ext);
        if (!tubes)
            throw Error("cannot export '" + o.path + "': Draco compression applies to tube meshes only, not to " +
                        "curves; what to export is " + whatName(o.what) + ", not tubes");
        if (o.quantize)
            throw Error("cannot export '" + o.path +
                        "': Draco compression and mesh quantization are alternatives; choose one");
    }
    if (o.quantize) requireGltfTubes(o, tubes, "mesh quantization", "KHR_mesh_quantization");
    if (o.meshopt) {
        requireGltfTubes(o, tubes, "meshopt compression", "EXT_meshopt_compression");
        if (o.draco)
            throw Error("cannot export '" + o.path +
                        "': Draco compression and meshopt compression are alternatives; choose one");
    }
    if (o.dracoBits < 1 || o.dracoBits > 30)
        throw Error("cannot export: the Draco position bits must be in [1, 30], got " + std::to_string(o.dracoBits));
    if (o.dracoNormalBits < 1 || o.dracoNormalBits > 30 || o.dracoTexcoordBits < 1 || o.dracoTexcoordBits > 30)
        throw Error("cannot export: Draco normal/texcoord bits must be in [1, 30]");
    if (o.dracoLevel < 0 || o.dracoLevel > 10)
        throw Error("cannot export: the Draco level must be in [0, 10], got " + std::to_string(o.dracoLevel));
    if (o.chunkVertices != 0 && o.chunkVertices < 16)
        throw Error("cannot export: the vertices per chunk must be 0 (auto) or at least 16, got " +
                    std::to_string(o.chunkVertices));
    if (o.maxBufferBytes < 1024 || o.maxBufferBytes > 0xFFFFFFF0ull)
        throw Error("cannot export: the glTF buffer size limit must be in [1024, 4294967280] bytes");
}

ExportStats exportCurves(const ExportInput& input, const ExportOptions& requested) {
    const auto t0 = std::chrono::steady_clock::now();
    // Step 1: validate options, the output folder and the data before anything is written.
    validateExportOptions(requested);
    ExportOptions options = requested;
    if (options.chunkVertices == 0)
        options.chunkVertices = options.draco                         ? size_t(1) << 18
                                : options.quantize || options.meshopt ? size_t(65535)
                                                                      : size_t(1) << 20;
    impl::checkOutputFolder(options.path);
    const bool tubes = options.what == ExportWhat::Tubes;
    validateInput(input, tubes);
    const std::string ext = util::lowerExtension(options.path);
    if (input.surface) {
        if (!isGltf(options.path))
            throw Error("cannot export '" + options.path +
                        "': the view's surface level (base-mesh triangles with the baked knit material) is written "
                        "to .glb or .gltf only");
        impl::validateSurfaceData(input.surface->mesh, input.surface->images, input.surface->material,
                                  "cannot export '" + options.path + "': the surface level: ");
    }
    if (input.plies && !streamsPlies(options)) {
        // Only glTF curves stream generated plies; the other writers take all curves at once.
        const Plies plies = makePlies(*input.plies);
        ExportInput all = input;
        all.plies = nullptr;
        all.curves = &plies.curves;
        all.yarnOfCurve = &plies.yarnOfCurve;
        all.seedNormals = &plies.radial;
        all.colours = plies.colour.empty() ? nullptr : &plies.colour;
        ExportStats stats = exportCurves(all, requested);
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return stats;
    }

    ExportStats stats;
    stats.format = ext;
    impl::FormatJob job{input, options, TubeOptions{}, tubes, std::string(), stats};
    job.tube.sides = options.sides;
    job.tube.caps = options.caps;
    job.tube.seedNormals = input.seedNormals;
    job.tube.pointColours = input.colours;
    {
        std::ostringstream h;
        const size_t curves =
            input.curves ? input.curves->curveCount() : input.plies->yarnCount() * size_t(input.plies->options().count);
        h << "libknit export: " << curves << " curves, " << whatName(options.what) << ", radius " << input.radius
          << " m";
        job.header = h.str();
    }
    if (tubes && input.curves) impl::checkTubeExportBudget(*input.curves, job.tube, options, isGltf(options.path));
    // Step 2: the format's writer (formats.cpp).
    sceneFormat(options.path)->write(job);

    stats.peakMemoryBytes = util::peakResidentBytes();
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return stats;
}

ExportStats exportScene(const Scene& scene, const ExportOptions& options, const SurfaceLayer* surface) {
    validateExportOptions(options);
    checkSceneExport(scene, options, surface);
    // Step: choose the curves (yarn centrelines, built plies, or plies generated while writing)
    // and their radius.
    const bool havePlies = scene.plies().curves.curveCount() > 0;
    const bool usePlies = impl::exportsPlies(scene, options);
    nlohmann::json extras = {{"generator", "libknit"}, {"yarnRadius", scene.yarnRadius()}};
    std::vector<uint32_t> yarnIds;
    ExportInput in;
    std::unique_ptr<PlyGenerator> generator;
    if (usePlies && !havePlies) {
        // Generated from the yarns while writing (validates scene.plyOptions()).
        generator = std::make_unique<PlyGenerator>(scene.yarns(), scene.plyOptions());
        const PlyOptions& o = generator->options();
        extras["curves"] = "plies";
        extras["plyCount"] = o.count;
        extras["plyRadius"] = o.plyRadius;
        extras["plyCenterRadius"] = o.centerRadius;
        extras["plyPitch"] = o.pitch;
        in.plies = generator.get();
        in.radius = o.plyRadius;
    } else if (usePlies) {
        const Plies& p = scene.plies();
        int count = 0;
        for (uint8_t i : p.plyOfCurve) count = std::max(count, int(i) + 1);
        extras["curves"] = "plies";
        extras["plyCount"] = count;
        extras["plyRadius"] = p.plyRadius;
        extras["plyCenterRadius"] = p.centerRadius;
        extras["plyPitch"] = p.pitch;
        in.curves = &p.curves;
        in.radius = p.plyRadius;
        if (p.yarnOfCurve.size() == p.curves.curveCount()) in.yarnOfCurve = &p.yarnOfCurve;
        if (p.radial.size() == p.curves.pointCount()) in.seedNormals = &p.radial;
        if (!p.colour.empty()) in.colours = &p.colour;
    } else {
        extras["curves"] = "yarns";
        in.curves = &scene.yarns().curves;
        in.radius = scene.yarnRadius();
        yarnIds.resize(scene.yarns().curves.curveCount());
        for (size_t i = 0; i < yarnIds.size(); ++i) yarnIds[i] = static_cast<uint32_t>(i);
        in.yarnOfCurve = &yarnIds;
        if (scene.yarns().normals.size() == scene.yarns().curves.pointCount()) in.seedNormals = &scene.yarns().normals;
        if (!scene.yarns().colour.empty()) in.colours = &scene.yarns().colour;
    }
    in.materialExtrasJson = extras.dump();
    in.surface = surface;
    return exportCurves(in, options);
}

}  // namespace knit
