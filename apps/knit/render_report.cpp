// The render result as the JSON of `knit render` (see render_report.hpp).
#include "render_report.hpp"

namespace knit::cli {

nlohmann::json renderReport(const RenderResult& r) {
    const Rgb m = r.image.mean();
    return {{"mode", modeName(r.mode)},
            {"light", lightPlacementName(r.light)},
            {"width", r.image.width},
            {"height", r.image.height},
            {"spp", r.spp},
            {"segments", r.segments},
            {"primitives", r.primitives},
            {"tableSeconds", r.tableSeconds},
            {"buildSeconds", r.buildSeconds},
            {"renderSeconds", r.renderSeconds},
            {"bakeSeconds", r.bakeSeconds},
            {"seconds", r.bakeSeconds + r.tableSeconds + r.buildSeconds + r.renderSeconds},
            {"rays", r.rays},
            {"raysPerSecond", r.raysPerSecond},
            {"sceneMemoryBytes", r.memory.sceneBytes()},
            {"embreeMemoryBytes", r.memory.embreeBytes},
            {"geometryMemoryBytes", r.memory.geometryBytes},
            {"shadingMemoryBytes", r.memory.shadingBytes},
            {"tableMemoryBytes", r.tableBytes},
            {"peakMemoryBytes", r.peakMemoryBytes},
            {"meanRadiance", {m.x, m.y, m.z}},
            {"material", nlohmann::json::parse(materialJsonText(r.material))},
            {"written", r.written}};
}

}  // namespace knit::cli
