// Empty exports refused with their cause (see empty_result.hpp).
#include "empty_result.hpp"

#include <sstream>

#include "knit/error.hpp"

namespace knit::cli {
namespace {

[[noreturn]] void refuse(const std::string& why) { throw Error("nothing to export: " + why + "; no file written"); }

// Why the scene has no yarn vertex.
std::string whyNoYarns(const Scene& s) {
    if (s.pattern().edges.empty()) return "the pattern '" + s.pattern().name + "' has no edges, so it makes no yarns";
    std::ostringstream why;
    why << "no yarn of pattern '" << s.pattern().name << "' lands on mesh '" << s.mesh().name << "' (repeats "
        << s.placement().repeats.x << " x " << s.placement().repeats.y << ", " << s.bindStats().cutVertices
        << " yarn vertices cut outside the UV region); raise --repeats so a pattern period fits the mesh";
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

}  // namespace

void refuseEmptyExport(const Scene& scene, const ExportOptions& options) {
    if (scene.yarns().curves.pointCount() == 0) refuse(whyNoYarns(scene));
    const bool needsPlies = options.what == ExportWhat::Plies ||
                            (options.what == ExportWhat::Tubes && options.tubesOf == TubeSource::Plies);
    if (!needsPlies || plyPoints(scene) > 0) return;
    const PlyOptions o = resolvePlyOptions(scene.plyOptions());
    std::ostringstream why;
    why << "every yarn is shorter than one ply sample (--ply-pitch " << o.pitch << " m / --samples-per-turn "
        << o.samplesPerTurn << "), so no ply curve was made; lower --ply-pitch";
    refuse(why.str());
}

}  // namespace knit::cli
