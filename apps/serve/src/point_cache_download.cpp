// The yarns as a one-frame PC2 (point_cache_download.hpp).
#include "point_cache_download.hpp"

#include <cstdio>

#include "knit/cache.hpp"
#include "knit/error.hpp"
#include "knit/scene.hpp"

namespace knit::serve {

std::string yarnPointCache(const Pattern& pattern, const BaseMesh& mesh, const GarmentSettings& settings,
                           TempFolder& temp) {
    SceneOptions options;
    options.buildPlies = false;
    options.placement.repeats = {settings.repeats[0], settings.repeats[1]};
    options.placement.gauge = settings.gauge;
    options.budget = settings.budget;
    const Scene scene = buildScene(pattern, mesh, options);
    const std::vector<glm::dvec3>& points = scene.yarns().curves.points;
    const double estimate = 32.0 + 12.0 * double(points.size());
    if (estimate > double(settings.maxFileBytes))
        throw Error("the point cache would take about " + std::to_string(int64_t(estimate / 1048576)) +
                    " MB, over the page's limit of " + std::to_string(settings.maxFileBytes >> 20) +
                    " MB; lower the repeats or the gauge");
    if (points.empty()) throw Error("no yarn lies on the mesh; nothing to download");
    const std::string path = temp.newFile("download", "pc2");
    {
        CacheInfo info;
        info.points = points.size();
        info.frames = 1;
        PointCacheWriter writer(path, info);
        writer.writeFrame(points);
        writer.commit();
    }
    std::string bytes;
    const bool read = readWholeFile(path, bytes);
    std::remove(path.c_str());
    if (!read) throw Error("cannot read back the point cache the server wrote");
    return bytes;
}

}  // namespace knit::serve
