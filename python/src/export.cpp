// python/src/export.cpp — export_scene: a built scene to a file (format by extension).
#include <vector>

#include "bindings.hpp"
#include "input_files.hpp"
#include "knit/budget.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "memory_budget_arg.hpp"

namespace knitpy {

namespace {

using namespace pybind11::literals;

knit::ExportWhat exportWhat(const std::string& what) {
    if (what == "yarns") return knit::ExportWhat::Yarns;
    if (what == "plies") return knit::ExportWhat::Plies;
    if (what == "tubes") return knit::ExportWhat::Tubes;
    throw knit::Error("what: expected 'yarns', 'plies' or 'tubes', got '" + what + "'");
}

py::dict statsDict(const knit::ExportStats& s) {
    return py::dict("format"_a = s.format, "curves"_a = s.curves, "vertices"_a = s.vertices,
                    "triangles"_a = s.triangles, "chunks"_a = s.chunks, "buffers"_a = s.buffers, "bytes"_a = s.bytes,
                    "seconds"_a = s.seconds);
}

}  // namespace

void registerExport(py::module_& m) {
    m.def(
        "export_scene",
        [](const knit::Scene& scene, const std::string& path, const std::string& what, int sides, bool caps, bool draco,
           bool quantize, bool yarnColors, bool meshopt, const std::string& maxMemory) {
            refuseWritingOverInputs(
                "path", path,
                {{"the scene's pattern file", scene.pattern().name}, {"the scene's mesh file", scene.mesh().name}});
            knit::ExportOptions o;
            o.path = path;
            o.what = exportWhat(what);
            o.sides = sides;
            o.caps = caps;
            o.draco = draco;
            o.quantize = quantize;
            o.meshopt = meshopt;
            o.yarnColors = yarnColors;
            o.budget = memoryBudgetArg(maxMemory);
            knit::ExportStats stats;
            {
                py::gil_scoped_release release;
                stats = knit::exportScene(scene, o);
            }
            return statsDict(stats);
        },
        "scene"_a, "path"_a, "what"_a = "plies", "sides"_a = 8, "caps"_a = true, "draco"_a = false,
        "quantize"_a = false, "yarn_colors"_a = false, "meshopt"_a = false, "max_memory"_a = "",
        "Writes the scene's yarns, plies or tube meshes; the format follows the extension of path "
        "(.obj .ply .bcc .pbrt .gltf .glb), written atomically. draco / quantize / meshopt: glTF "
        "compression: Draco meshes, quantized attributes, meshopt compression (meshopt: tubes only). max_memory: "
        "the memory budget as a size ('8G'; '' = min(4 GiB, half the physical memory)): "
        "an export whose estimated size is over it raises knit.Error before writing. Returns the export's "
        "counts. Raises knit.Error (an empty result, values beyond float32, bad options; naming the keyword "
        "of a setting it names), before any file is written.");
}

}  // namespace knitpy
