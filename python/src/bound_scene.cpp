// python/src/bound_scene.cpp — bound scene files (knit/bound_scene.hpp) and the frame numbers of
// a mesh sequence, for knit.distributed: a scene bound once, saved, and loaded by every worker.
#include <memory>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "input_files.hpp"
#include "knit/animation.hpp"
#include "knit/bound_scene.hpp"
#include "knit/scene.hpp"
#include "memory_budget_arg.hpp"

namespace knitpy {

using namespace pybind11::literals;

void registerBoundScene(py::module_& m) {
    m.def(
        "load_bound_scene",
        [](const std::string& path, const std::string& maxMemory) {
            const knit::MemoryBudget budget = memoryBudgetArg(maxMemory);
            py::gil_scoped_release release;
            return std::make_shared<knit::Scene>(knit::readBoundScene(path, budget).scene);
        },
        "path"_a, "max_memory"_a = "",
        "The Scene of a bound scene file (`knit bind`): pattern, placement, rest mesh and binding as saved, "
        "evaluating every pose to the same bytes as the scene that was saved. A file of another format "
        "version or a damaged one raises knit.Error saying which. The file is memory-mapped and its largest "
        "arrays are used in place while the Scene lives: replace it by rename (as save_bound_scene and "
        "`knit bind` do), never truncate or rewrite it in place meanwhile.");
    m.def(
        "save_bound_scene",
        [](const knit::Scene& scene, const std::string& path, const std::string& settings) {
            refuseWritingOverInputs(
                "path", path,
                {{"the scene's pattern file", scene.pattern().name}, {"the scene's mesh file", scene.mesh().name}});
            knit::BoundSceneInfo info;
            info.settings = settings;
            py::gil_scoped_release release;
            knit::writeBoundScene(path, scene, info);
        },
        "scene"_a, "path"_a, "settings"_a = "",
        "Writes `scene` (from build_scene) as a bound scene file, atomically; `settings` is free text kept "
        "with it (JSON by convention).");
    m.def(
        "frame_numbers",
        [](const std::string& frames, int first, int last, int step) {
            knit::FrameRange range;
            range.first = first, range.last = last, range.step = step;
            const knit::FrameSequence seq(frames, range);
            std::vector<int> numbers;
            for (const knit::FrameFile& f : seq.frames()) numbers.push_back(f.number);
            return numbers;
        },
        "frames"_a, "first"_a = -1, "last"_a = -1, "step"_a = 1,
        "The frame numbers `knit animate --frames FRAMES --first --last --step` evaluates (-1: from the files "
        "found). Raises knit.Error for a missing frame, naming it.");
}

}  // namespace knitpy
