// knit/scene.hpp — the whole pipeline as one composition of the stages, for the CLI, the
// renderer and benchmarks. Each step is a plain call of a stage function; nothing hidden.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "knit/base_mesh.hpp"
#include "knit/budget.hpp"
#include "knit/binding.hpp"
#include "knit/detail.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "knit/plies.hpp"
#include "knit/stitch.hpp"
#include "knit/strain.hpp"
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
    BindOptions bind;  // yarnRadius is set from the pattern and placement
    // false: no plies in the Scene; an exporter can still generate them from yarns and
    // plyOptions while writing (knit/export.hpp), which needs far less memory.
    bool buildPlies = true;
    PlyOptions plies;     // yarnRadius is set from the pattern and placement
    ProgressFn progress;  // optional
    // Each big stage estimates its memory from its counts first and refuses (knit::Error naming
    // the option that drives it) when over this budget.
    MemoryBudget budget;
    // Level of detail for a view (knit/detail.hpp): plies only for the pieces of yarn in ply-level
    // cells; none: the whole scene at full ply detail.
    std::optional<DetailOptions> detail;
    // Strain-aware deformation of the yarns (knit/strain.hpp); none by default.
    DeformOptions deform;
};

// What SceneOptions::detail made: the view used, the level of every cell and the yarn pieces per
// level (Scene::plies() holds the plies of the ply-level pieces only).
struct SceneDetail {
    View view;
    double margin = 0;  // the yarns' greatest height plus their radius (Scene::yarnMargin)
    CellLevels levels;
    LevelPieces pieces;
};

struct StageTime {
    std::string stage;
    double seconds = 0;
};

// The intermediate results between the UV grid and the binding, for diagnostics and tests
// (Scene::stages); exporters and renderers need none of them.
struct SceneStages {
    Tiling tiling;                      // tiles over every covered cell
    std::vector<Tiling> islandTilings;  // when UV islands overlap: one tiling per island, which the
                                        // yarns come from (empty otherwise)
    UvYarns uvYarns;                    // the stitched yarns in UV space, before binding
};

// What a Scene made without the pipeline stages holds (Scene::fromParts): synthetic scenes for
// renderer and export tests and benchmarks. Parts left empty stay empty in the Scene.
// What an Animator decides on the rest pose (libknit's own, internal): stored with a bound scene
// (knit/bound_scene.hpp) so that the Animator of a loaded scene adopts it instead of recomputing it.
struct AnimatorBindState;

struct SceneParts {
    BaseMesh mesh;
    std::vector<glm::dvec3> normals;  // rest-pose vertex normals
    double yarnRadius = 0;            // object space (metres)
    UvGrid grid;                      // the renderer's grid mode needs only cellSize
    Binding binding;                  // of `yarns` on `mesh`
    MappedYarns yarns;
    // True (a loaded bound scene): `yarns` is left empty and Scene::yarns evaluates the binding on
    // the rest mesh (and applies `deformer`) the first time it is asked, as buildScene did.
    bool lazyYarns = false;
    Plies plies;
    std::optional<SceneDetail> detail;     // a view's levels and pieces (of these yarns)
    std::optional<PlyOptions> plyOptions;  // none: the defaults with yarnRadius
    // A scene saved after binding (knit/bound_scene.hpp) keeps its pattern, placement and bind
    // statistics; synthetic scenes leave them empty.
    Pattern pattern;
    PatternPlacement placement;
    BindStats bindStats;
    // A loaded bound scene's Animator bind-time state (readBoundScene sets it); none: computed.
    std::shared_ptr<const AnimatorBindState> animatorState;
    // A loaded bound scene's deformation (readBoundScene sets them): the mode, table and why it
    // was chosen, the strain deformer (`yarns` already displaced by it) and what it did on the
    // rest mesh; none: geometric.
    DeformOptions deform;
    std::shared_ptr<const StrainDeformer> deformer;
    DeformStats deformStats;
};

// The result of the pipeline: read-only, made by buildScene (or Scene::fromParts).
class Scene {
public:
    // An empty scene (no mesh, no yarns), to assign a built one to later.
    Scene() = default;
    // A scene from parts made without the pipeline: no pattern, placement, stages, bind
    // statistics or timings; plyOptions are the parts' or the defaults with the parts' yarn radius.
    static Scene fromParts(SceneParts parts);

    const Pattern& pattern() const { return pattern_; }
    const BaseMesh& mesh() const { return mesh_; }
    const std::vector<glm::dvec3>& normals() const { return normals_; }  // rest-pose vertex normals
    const PatternPlacement& placement() const { return placement_; }
    double yarnRadius() const { return yarnRadius_; }  // object space (metres)
    const UvGrid& grid() const { return grid_; }
    const Binding& binding() const { return bound_.binding; }
    const BindStats& bindStats() const { return bound_.stats; }
    // The rest yarns. A scene loaded from a bound scene file (knit/bound_scene.hpp) evaluates
    // them on the first call (the binding on the rest mesh and normals, displaced by the strain
    // deformer when it has one: buildScene's evaluate and deform stages, bit for bit; thread-safe,
    // once per scene and its copies): the Animator of a loaded scene needs none of them (its
    // stored state has what it would derive), so a farm task that only bakes frames never pays
    // for them (141 MB and ~0.1 CPU-s on the 3M-vertex garment). A renderer or exporter pays on
    // its first call.
    const MappedYarns& yarns() const;
    // False while a loaded scene's rest yarns are unevaluated (yarns() not called yet); true for
    // a built scene.
    bool yarnsEvaluated() const;
    const Plies& plies() const { return plies_; }  // empty unless SceneOptions::buildPlies
    // Ply settings, yarnRadius set (resolved when the plies were built; else by their consumer).
    const PlyOptions& plyOptions() const { return plyOptions_; }
    const std::vector<StageTime>& timings() const { return timings_; }  // wall time per stage
    // Intermediate results (tiling, UV yarns) for diagnostics and tests.
    const SceneStages& stages() const { return stages_; }
    // The view and levels when built with SceneOptions::detail; empty for the full scene.
    const std::optional<SceneDetail>& detail() const { return detail_; }
    // The yarns' greatest height above or below the surface plus their radius, which frames the
    // default camera and light: from the pattern and placement (so a scene built for a view
    // frames as the full scene does, also when it built no yarns), from the binding for a scene
    // made from parts.
    double yarnMargin() const;
    // With SceneOptions::deform in Strain mode: the deformer (for animation) and what it did on
    // the scene's own mesh; null / zeros otherwise.
    const std::shared_ptr<const StrainDeformer>& deformer() const { return deformer_; }
    const DeformStats& deformStats() const { return deformStats_; }
    // SceneOptions::deform as built: the mode, its table and why (knit::decideDeform).
    const DeformOptions& deformOptions() const { return deformOptions_; }
    // A scene loaded from a bound scene file: the Animator's bind-time state it stores (every
    // Animator of this scene adopts it); null for a scene built here.
    const std::shared_ptr<const AnimatorBindState>& animatorState() const { return animatorState_; }

private:
    friend class SceneBuilder;  // scene.cpp: runs the stages of buildScene into a Scene

    Pattern pattern_;
    BaseMesh mesh_;
    std::vector<glm::dvec3> normals_;
    PatternPlacement placement_;
    double yarnRadius_ = 0;
    UvGrid grid_;
    SceneStages stages_;
    BindResult bound_;
    MappedYarns yarns_;
    struct LazyYarns;                       // scene.cpp: the rest yarns of a loaded scene, on first use
    std::shared_ptr<LazyYarns> lazyYarns_;  // null: yarns_ holds them
    Plies plies_;
    PlyOptions plyOptions_;
    std::vector<StageTime> timings_;
    std::optional<SceneDetail> detail_;
    std::shared_ptr<const StrainDeformer> deformer_;
    DeformStats deformStats_;
    DeformOptions deformOptions_;
    std::shared_ptr<const AnimatorBindState> animatorState_;
};

// Runs: load pattern -> load mesh -> normals -> placement -> UV grid -> tiling -> stitch ->
// binding -> evaluation -> plies. Throws knit::Error for bad input.
Scene buildScene(const SceneOptions& options);
// The same from an in-memory pattern and mesh (options.pattern / options.mesh are ignored).
Scene buildScene(Pattern pattern, BaseMesh mesh, const SceneOptions& options);

// What a scene built for a view (SceneOptions::detail) exports as curves: the yarn pieces of its
// ply-level cells, then those of its yarn-level cells (points, normals, colours), with its mesh,
// grid and ply options; with `withPlies` also the plies of every piece, cut from their yarns'
// plies so they are the full scene's plies point for point (piecePlies). Files have no yarn-level
// shading: a yarn-level cell keeps its plies there. Throws knit::Error for a scene without a view.
Scene viewPiecesScene(const Scene& built, bool withPlies);

// Lengths of the segments of a curve set (closed curves count their closing segment).
struct SegmentStats {
    size_t segments = 0;
    double medianLength = 0;   // the upper median; 0 without segments
    double longestLength = 0;  // 0 without segments
};

// Per level of detail (plies, yarns, surface): the cells and what is generated for them.
struct LevelStats {
    struct Level {
        size_t cells = 0;
        size_t yarnVertices = 0;
        size_t plyVertices = 0;
        size_t bytes = 0;  // float32 geometry: 16 bytes per curve point (xyz, radius); surface
                           // triangles 12 bytes each plus 32 per vertex (position, normal, uv)
    };
    Level plies, yarns, surface;
    size_t culledCells = 0;
};

// Counts, vertices per level, segment statistics and stage times of a scene: the numbers of the
// `knit build` report besides the pattern, mesh and placement (apps/knit/report.cpp).
struct SceneStats {
    size_t cells = 0;
    size_t tiles = 0;  // the tiles the yarns come from (all island tilings when islands overlap)
    size_t yarns = 0;
    size_t tiledYarns = 0;
    BindStats bind;  // closed loops, open ends, cut / clamped / boundary vertices, welds
    size_t tiledVertices = 0;
    size_t yarnVertices = 0;
    size_t plyVertices = 0;
    SegmentStats yarnSegments;
    std::optional<SegmentStats> plySegments;  // when the scene holds plies
    LevelStats levels;
    std::vector<StageTime> stageTimes;  // Scene::timings
    double totalSeconds = 0;            // their sum
};

SceneStats sceneStats(const Scene& scene);
// The levels part of sceneStats alone (cheap: no segment statistics).
LevelStats levelStats(const Scene& scene);

}  // namespace knit
