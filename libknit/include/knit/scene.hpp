// knit/scene.hpp — the whole pipeline as one composition of the stages, for the CLI, the
// renderer and benchmarks. Each step is a plain call of a stage function; nothing hidden.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "knit/plies.hpp"
#include "knit/stitch.hpp"
#include "knit/tiling.hpp"
#include "knit/uv_grid.hpp"

namespace knit {

// Called between stages with the stage name and its index/total; used for progress output.
using ProgressFn = std::function<void(const std::string& stage, int index, int total)>;

struct SceneOptions {
    std::string pattern = "stockinette";  // file (.pyp / .json) or built-in name
    std::string mesh = "drape";           // file (.obj / .ply / .off / .gltf / .glb) or built-in name
    ProceduralMeshOptions meshOptions;    // for built-in meshes
    PlacementOptions placement;
    BindOptions bind;                     // yarnRadius is set from the pattern and placement
    // false: no plies in the Scene; an exporter can still generate them from yarns and
    // plyOptions while writing (knit/export.hpp), which needs far less memory.
    bool buildPlies = true;
    PlyOptions plies;                     // yarnRadius is set from the pattern and placement
    ProgressFn progress;                  // optional
};

struct StageTime {
    std::string stage;
    double seconds = 0;
};

struct Scene {
    Pattern pattern;
    BaseMesh mesh;
    std::vector<glm::dvec3> normals;  // rest-pose vertex normals
    PatternPlacement placement;
    double yarnRadius = 0;            // object space (metres)
    UvGrid grid;
    Tiling tiling;                    // tiles over every covered cell
    std::vector<Tiling> chartTilings; // when UV charts overlap: one tiling per chart, which the
                                      // yarns come from (empty otherwise)
    UvYarns uvYarns;
    BindResult bound;
    MappedYarns yarns;
    Plies plies;                      // empty unless SceneOptions::buildPlies
    PlyOptions plyOptions;            // ply settings, yarnRadius set (resolved when plies were built)
    std::vector<StageTime> timings;
};

// Runs: load pattern -> load mesh -> normals -> placement -> UV grid -> tiling -> stitch ->
// binding -> evaluation -> plies. Throws knit::Error for bad input.
Scene buildScene(const SceneOptions& options);
// The same from an in-memory pattern and mesh (options.pattern / options.mesh are ignored).
Scene buildScene(Pattern pattern, BaseMesh mesh, const SceneOptions& options);

// Counts, per-stage wall times and segment statistics (the JSON report of `knit build`).
nlohmann::json sceneReport(const Scene& scene);

}  // namespace knit
