// scene_checks.cpp — checkSceneExport(): what no file should hold, refused before anything is
// written, for every caller (the CLI, Python, C++): values beyond the float32 range and an export
// without a curve, each with its cause.
#include "scene_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "formats.hpp"
#include "knit/error.hpp"

namespace knit {

namespace impl {

bool exportsPlies(const Scene& scene, const ExportOptions& options) {
    switch (options.what) {
        case ExportWhat::Yarns: return false;
        case ExportWhat::Plies: return true;
        case ExportWhat::Tubes:
            return options.tubesOf == TubeSource::Plies ||
                   (options.tubesOf == TubeSource::Auto && scene.plies().curves.curveCount() > 0);
    }
    return false;
}

}  // namespace impl

namespace {

constexpr double kFloatMax = double(std::numeric_limits<float>::max());

void require(double value, const std::string& what, const std::string& fix, const std::string& output) {
    if (std::abs(value) <= kFloatMax) return;
    std::ostringstream msg;
    msg << "cannot write '" << output << "': " << what << " " << value << " is beyond the float32 range (3.4e38); "
        << fix;
    throw Error(msg.str());
}

// Step: the yarn radius, the ply radii and pitch (when plies are asked for: ply curves, or tubes,
// of the plies when the scene has them) and, in a float32 format, the coordinates.
void refuseValuesBeyondFloat32(const Scene& scene, const ExportOptions& options) {
    const std::string& out = options.path;
    require(scene.yarnRadius(), "the yarn radius", "lower the pattern's radius or raise the repeats", out);
    if (options.what != ExportWhat::Yarns) {
        const PlyOptions o = resolvePlyOptions(scene.plyOptions());
        require(o.pitch, "the ply pitch", "lower the ply pitch", out);
        require(o.plyRadius, "the ply radius", "lower the ply radius", out);
        require(o.centerRadius, "the ply centre radius", "lower the ply centre radius", out);
    }
    const impl::Format* format = impl::formatOf(out);
    if (!format || !format->float32) return;
    // Every written point lies within a yarn radius of its yarn's centreline.
    double reach = 0;
    for (const glm::dvec3& p : scene.yarns().curves.points)
        reach = std::max(reach, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
    require(reach + scene.yarnRadius(), "a coordinate of the curves",
            "scale the mesh '" + scene.mesh().name + "' down or write .obj/.ply (double precision)", out);
}

[[noreturn]] void refuse(const std::string& why) { throw Error("nothing to export: " + why + "; no file written"); }

// Why the scene has no yarn vertex.
std::string whyNoYarns(const Scene& s) {
    if (s.pattern().name.empty()) return "the scene has no yarns";  // made from parts, not by the pipeline
    if (s.pattern().edges.empty()) return "the pattern '" + s.pattern().name + "' has no edges, so it makes no yarns";
    std::ostringstream why;
    why << "no yarn of pattern '" << s.pattern().name << "' lands on mesh '" << s.mesh().name << "' (repeats "
        << s.placement().repeats.x << " x " << s.placement().repeats.y << ", " << s.bindStats().cutVertices
        << " yarn vertices cut outside the UV region); raise the repeats so a pattern period fits the mesh";
    return why.str();
}

// The ply points the plies of `scene` have (built) or will have (generated while writing).
size_t plyPoints(const Scene& s) {
    if (s.plies().curves.pointCount() > 0) return s.plies().curves.pointCount();
    const PlyGenerator generator(s.yarns(), s.plyOptions());
    size_t points = 0;
    for (size_t y = 0; y < generator.yarnCount() && points == 0; ++y) points += generator.estimatePoints(y);
    return points;
}

// Step: an export that would hold no curve (a pattern without edges, repeats so small that no
// yarn lands on the mesh, a ply pitch longer than every yarn), with why nothing was made.
void refuseEmptyExport(const Scene& scene, const ExportOptions& options) {
    if (scene.yarns().curves.pointCount() == 0) refuse(whyNoYarns(scene));
    if (!impl::exportsPlies(scene, options) || plyPoints(scene) > 0) return;
    const PlyOptions o = resolvePlyOptions(scene.plyOptions());
    std::ostringstream why;
    why << "every yarn is shorter than one ply sample, the ply pitch " << o.pitch << " m over the samples per turn "
        << o.samplesPerTurn << ", so no ply curve was made; lower the ply pitch";
    refuse(why.str());
}

}  // namespace

void checkSceneExport(const Scene& scene, const ExportOptions& options, const SurfaceLayer* surface) {
    refuseValuesBeyondFloat32(scene, options);
    if (!surface) refuseEmptyExport(scene, options);
}

}  // namespace knit
