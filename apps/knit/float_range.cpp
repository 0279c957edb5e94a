// Values checked against the float32 range before they are written (see float_range.hpp).
#include "float_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "knit/error.hpp"
#include "util/platform.hpp"

namespace knit::cli {
namespace {

constexpr double kFloatMax = double(std::numeric_limits<float>::max());

void require(double value, const std::string& what, const std::string& fix, const std::string& output) {
    if (std::abs(value) <= kFloatMax) return;
    std::ostringstream msg;
    msg << "cannot write '" << output << "': " << what << " " << value << " is beyond the float32 range (3.4e38); "
        << fix;
    throw Error(msg.str());
}

bool float32Format(const std::string& path) {
    const std::string ext = util::lowerExtension(path);
    return ext == "bcc" || ext == "gltf" || ext == "glb" || ext == "pbrt" || ext == "pc2" || ext == "mdd";
}

}  // namespace

void refuseValuesBeyondFloat32(const Scene& scene, const ExportOptions& options) {
    const std::string& out = options.path;
    require(scene.yarnRadius(), "the yarn radius", "lower the pattern's radius or raise --repeats", out);
    if (options.what != ExportWhat::Yarns) {
        const PlyOptions o = resolvePlyOptions(scene.plyOptions());
        require(o.pitch, "the ply pitch", "lower --ply-pitch", out);
        require(o.plyRadius, "the ply radius", "lower --ply-radius", out);
        require(o.centerRadius, "the ply centre radius", "lower --ply-center-radius", out);
    }
    if (!float32Format(out)) return;
    // Every written point lies within a yarn radius of its yarn's centreline.
    double reach = 0;
    for (const glm::dvec3& p : scene.yarns().curves.points)
        reach = std::max(reach, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
    require(reach + scene.yarnRadius(), "a coordinate of the curves",
            "scale the mesh '" + scene.mesh().name + "' down or write .obj/.ply (double precision)", out);
}

}  // namespace knit::cli
