// The whole pipeline as a plain composition of the stages (buildScene), and Scene::fromParts.
#include "knit/scene.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <utility>

#include "knit/error.hpp"
#include "scene_budget.hpp"

namespace knit {
namespace {

// The grid cells each UV island's triangles of non-zero UV area touch (a cell shared by several
// islands is listed for each; an island of zero-area triangles only gets none: nothing to tile).
std::vector<std::vector<glm::ivec2>> cellsPerIsland(const UvGrid& grid) {
    std::vector<std::vector<glm::ivec2>> cells(grid.islandCount);
    std::vector<uint32_t> seen;
    for (size_t k = 0; k < grid.cells.size(); ++k) {
        seen.clear();
        for (uint32_t i = grid.triOffsets[k]; i < grid.triOffsets[k + 1]; ++i) {
            if (grid.faceOrientation[grid.triangles[i]] == 0) continue;
            const uint32_t c = grid.islandOfFace[grid.triangles[i]];
            if (std::find(seen.begin(), seen.end(), c) != seen.end()) continue;
            seen.push_back(c);
            cells[c].push_back(grid.cells[k]);
        }
    }
    return cells;
}

// Progress: buildScene's stages in named groups, so the total the progress callback reports is
// the sum of the groups that run (SceneBuilder::run is called once per stage named here).
constexpr int kInputStages = 2;  // load_pattern, load_mesh (not when the inputs are given in memory)
constexpr int kGridStages = 2;   // normals, uv_grid
constexpr int kViewStages = 2;   // levels, detail (with a view)
constexpr int kYarnStages = 4;   // tiling, stitch, binding, evaluate (skipped when no cell needs yarns)
constexpr int kPlyStages = 1;    // plies (when asked for)

int deformStages(const SceneOptions& options) { return options.deform.mode == DeformMode::Strain ? 1 : 0; }

int stageCount(const SceneOptions& options, bool loadsInputs) {
    return (loadsInputs ? kInputStages : 0) + kGridStages + (options.detail ? kViewStages : 0) + kYarnStages +
           (options.buildPlies ? kPlyStages : 0) + deformStages(options);
}

bool needsYarns(const CellLevels& levels) {
    for (DetailLevel l : levels.level)
        if (l == DetailLevel::Yarns || l == DetailLevel::Plies) return true;
    return false;
}

}  // namespace

// Runs the stages into one Scene, each a named step with its wall time recorded (the only code
// besides Scene::fromParts that writes a Scene).
class SceneBuilder {
public:
    SceneBuilder(const SceneOptions& options, int stageCount) : options_(options), total_(stageCount) {}

    // load_pattern, load_mesh: the inputs named by the options.
    void loadInputs() {
        run("load_pattern", [&] { s_.pattern_ = loadPatternFileOrName(options_.pattern); });
        run("load_mesh", [&] {
            MeshLoadOptions load;
            load.budget = options_.budget;
            s_.mesh_ = loadMeshFileOrName(options_.mesh, options_.meshOptions, load);
            validateMesh(s_.mesh_);
        });
    }
    // In-memory inputs (validated by the caller).
    void adoptInputs(Pattern pattern, BaseMesh mesh) {
        s_.pattern_ = std::move(pattern);
        s_.mesh_ = std::move(mesh);
    }
    // The stages after the inputs, then the Scene.
    Scene finish() {
        // A table that does not fit the pattern is refused before any work.
        if (options_.deform.mode == DeformMode::Strain) {
            if (!options_.deform.table)
                throw Error("strain-aware deformation needs a strain table (the deform mode is strain)");
            checkStrainTable(*options_.deform.table, s_.pattern_);
        }
        s_.deformOptions_ = options_.deform;
        run("normals", [&] { s_.normals_ = vertexNormals(s_.mesh_.positions, s_.mesh_.faces); });
        run("uv_grid", [&] { placeAndGrid(); });
        // With a view, the level of every cell comes first (it needs only the mesh, the grid and
        // the pattern's heights): a view that needs yarns nowhere (every cell culled or at the
        // surface level, as a far view) builds none.
        if (options_.detail) run("levels", [&] { levels(*options_.detail); });
        if (!s_.detail_ || needsYarns(s_.detail_->levels)) {
            run("tiling", [&] { tile(); });
            run("stitch", [&] { stitch(); });
            run("binding", [&] { bind(); });
            run("evaluate", [&] {
                evaluateBinding(s_.bound_.binding, s_.mesh_.faces, s_.mesh_.positions, s_.normals_, s_.yarns_);
            });
            if (options_.deform.mode == DeformMode::Strain) run("deform", [&] { deform(); });
        } else {
            total_ -= kYarnStages + deformStages(options_);  // progress: the yarn stages are skipped
        }
        if (s_.detail_) run("detail", [&] { pieces(); });
        plies();
        return std::move(s_);
    }

private:
    // Runs one named stage, recording its wall time.
    template <class F>
    void run(const std::string& name, F&& stage) {
        if (options_.progress) options_.progress(name, index_, total_);
        const auto t0 = std::chrono::steady_clock::now();
        stage();
        const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
        s_.timings_.push_back({name, dt.count()});
        ++index_;
    }

    // Step: the pattern's placement, the yarn radius it implies, and the UV grid of that size.
    void placeAndGrid() {
        s_.placement_ = placePattern(s_.pattern_, s_.mesh_, options_.placement);
        s_.yarnRadius_ = s_.pattern_.radius * s_.placement_.scale;
        impl::checkGridBudget(s_.mesh_, s_.placement_, physicalSize(), options_.budget);
        UvGridOptions gridOptions;
        gridOptions.cellSize = s_.placement_.cellSize();
        gridOptions.maxEntries = std::numeric_limits<uint64_t>::max();  // bounded by the memory budget above
        s_.grid_ = buildUvGrid(s_.mesh_, gridOptions);
    }

    // Step: tiles over the covered cells (and over each island's cells when islands overlap).
    // With a view that keeps yarns somewhere (and DetailOptions::region), the tiles whose yarns
    // are kept are marked too: those reaching the cells of yarnRegion.
    void tile() {
        // Vertices within binding's clamp tolerance of the covered cells are tiled too (they are
        // clamped onto the UV boundary, not dropped because their own cell is empty).
        const glm::dvec2 metresPerUv = uvToMetreScale(s_.mesh_);
        const double tolUv = options_.bind.clampTolerance * s_.yarnRadius_ / std::max(metresPerUv.x, metresPerUv.y);
        const glm::dvec2 margin = tolUv * s_.placement_.repeats * glm::dvec2(s_.pattern_.px, s_.pattern_.py);
        const bool region = regionBuild();
        impl::checkTilingBudget(s_.pattern_, s_.grid_.cells.size(), s_.grid_.dims, tileReach(s_.pattern_, margin),
                                physicalSize(), options_.budget, region);
        SceneStages& st = s_.stages_;
        st.tiling = tilesForCells(s_.pattern_, s_.grid_.cells, margin);
        // Overlapping UV islands: each island is also tiled over its own cells, so that each gets
        // its own yarns (bound to that island only).
        if (!s_.grid_.overlappingIslands.empty()) {
            const std::vector<std::vector<glm::ivec2>> cells = cellsPerIsland(s_.grid_);
            for (const std::vector<glm::ivec2>& c : cells)
                st.islandTilings.push_back(c.empty() ? Tiling{} : tilesForCells(s_.pattern_, c, margin));
        }
        if (region) regionTiles_ = tilesForCells(s_.pattern_, yarnRegion(s_.detail_->levels), margin);
    }

    // A view's region build: the yarns of the view's region only (see tile()).
    bool regionBuild() const { return s_.detail_ && options_.detail && options_.detail->region; }

    // The stitch filter of a region build for `tiling`: its tiles that are region tiles, and the
    // memory check of the yarns kept, added to `kept` (the yarns kept so far by the filters of the
    // other islands: all islands' yarns are checked together). Null without a region build.
    std::unique_ptr<StitchFilter> regionFilter(const Tiling& tiling, uint64_t& kept) const {
        if (!regionBuild()) return nullptr;
        auto f = std::make_unique<StitchFilter>();
        f->keepTile.resize(tiling.tiles.size());
        for (size_t k = 0; k < tiling.tiles.size(); ++k) f->keepTile[k] = regionTiles_.slotOf(tiling.tiles[k]) >= 0;
        f->beforeAllocate = [this, &kept](uint64_t vertices) {
            kept += vertices;
            impl::checkRegionYarnBudget(kept, physicalSize(), options_.budget);
        };
        return f;
    }

    // Step: the tiles' segments walked into yarns (per island when islands overlap); a region
    // build keeps the yarns through its region.
    void stitch() {
        const PatternAdjacency adjacency = buildAdjacency(s_.pattern_);
        SceneStages& st = s_.stages_;
        uint64_t kept = 0;  // a region build's yarn vertices so far (of all islands together)
        if (st.islandTilings.empty()) {
            st.uvYarns =
                stitchYarns(s_.pattern_, adjacency, st.tiling, s_.placement_, regionFilter(st.tiling, kept).get());
        } else {
            st.uvYarns = UvYarns{};
            for (size_t c = 0; c < st.islandTilings.size(); ++c) {
                if (st.islandTilings[c].tiles.empty()) continue;
                std::unique_ptr<StitchFilter> filter = regionFilter(st.islandTilings[c], kept);
                appendIslandYarns(st.uvYarns,
                                  stitchYarns(s_.pattern_, adjacency, st.islandTilings[c], s_.placement_, filter.get()),
                                  uint32_t(c));
            }
        }
    }

    // Step: the UV yarns bound to the mesh, with the scene's yarn radius.
    void bind() {
        BindOptions o = options_.bind;
        o.yarnRadius = s_.yarnRadius_;
        s_.bound_ = bindYarns(s_.mesh_, s_.normals_, s_.grid_, s_.stages_.uvYarns, o);
    }

    // Step: the strain table's displacements added to the evaluated yarns (the rest mesh itself
    // may be strained against the pattern's layout: a non-isometric UV layout).
    void deform() {
        auto deformer = std::make_shared<const StrainDeformer>(s_.mesh_, s_.pattern_, s_.placement_, s_.bound_.binding,
                                                               options_.deform.table);
        s_.deformStats_ = deformer->apply(s_.bound_.binding, s_.mesh_.positions, s_.yarns_);
        s_.deformer_ = std::move(deformer);
    }

    // Step: the view (given, or framing the mesh grown by the yarns' margin) and the level of
    // every cell.
    void levels(const DetailOptions& o) {
        SceneDetail d;
        d.margin = s_.yarnMargin();
        d.view = o.view ? *o.view : frameMesh(s_.mesh_, d.margin, o.viewSettings);
        PlyOptions po = options_.plies;
        po.yarnRadius = s_.yarnRadius_;
        DetailInputs in;
        in.mesh = &s_.mesh_, in.grid = &s_.grid_, in.margin = d.margin;
        in.yarnRadius = s_.yarnRadius_, in.plyRadius = resolvePlyOptions(po).plyRadius;
        d.levels = classifyCells(in, d.view, o);
        s_.detail_ = std::move(d);
    }

    // Step: the yarns (none when no cell needs them) cut into pieces per level, and the
    // surface-level triangles.
    void pieces() {
        SceneDetail& d = *s_.detail_;
        d.pieces = splitByLevel(s_.yarns_, s_.bound_.binding, s_.mesh_, s_.grid_, d.levels);
    }

    // Step: the ply settings with the scene's yarn radius; the plies when asked for (of the
    // ply-level pieces only with a view).
    void plies() {
        PlyOptions o = options_.plies;
        o.yarnRadius = s_.yarnRadius_;
        s_.plyOptions_ = o;  // resolved below when the plies are built; else by their consumer
        if (options_.buildPlies)
            run("plies", [&] {
                s_.plyOptions_ = resolvePlyOptions(o);
                const MappedYarns& source = s_.detail_ ? s_.detail_->pieces.plies : s_.yarns_;
                impl::checkPlyBudget(source, s_.plyOptions_, options_.budget);
                // With a view: the plies of the ply-level pieces cut from their yarns' plies (the
                // full scene's plies there, point for point); each names its source yarn.
                s_.plies_ = s_.detail_ ? piecePlies(s_.yarns_, s_.detail_->pieces.plySpans, s_.plyOptions_)
                                       : makePlies(source, s_.plyOptions_);
            });
    }

    bool physicalSize() const { return options_.placement.repeats == glm::dvec2(0.0); }

    const SceneOptions& options_;
    Scene s_;
    Tiling regionTiles_;  // a region build: the tiles whose yarns are kept
    int total_;
    int index_ = 0;
};

Scene buildScene(const SceneOptions& options) {
    SceneBuilder builder(options, stageCount(options, true));
    builder.loadInputs();
    return builder.finish();
}

Scene buildScene(Pattern pattern, BaseMesh mesh, const SceneOptions& options) {
    validatePattern(pattern, pattern.name);
    validateMesh(mesh);
    SceneBuilder builder(options, stageCount(options, false));
    builder.adoptInputs(std::move(pattern), std::move(mesh));
    return builder.finish();
}

double Scene::yarnMargin() const {
    if (!pattern_.points.empty() && placement_.scale > 0)
        return knit::yarnMargin(pattern_, placement_.scale, yarnRadius_);
    return knit::yarnMargin(bound_.binding, yarnRadius_);
}

// The rest yarns of a loaded bound scene, evaluated on first use (Scene::yarns); shared by the
// copies of the scene (they hold the same binding and mesh).
struct Scene::LazyYarns {
    std::once_flag once;
    std::atomic<bool> done{false};
    MappedYarns yarns;
};

const MappedYarns& Scene::yarns() const {
    if (!lazyYarns_) return yarns_;
    std::call_once(lazyYarns_->once, [this] {
        // buildScene's evaluate stage, then its deform stage (the deform statistics are the
        // stored ones: the same pass on the same input).
        MappedYarns& y = lazyYarns_->yarns;
        evaluateBinding(bound_.binding, mesh_.faces, mesh_.positions, normals_, y);
        if (deformer_) (void)deformer_->apply(bound_.binding, mesh_.positions, y);
        lazyYarns_->done = true;
    });
    return lazyYarns_->yarns;
}

bool Scene::yarnsEvaluated() const { return !lazyYarns_ || lazyYarns_->done; }

Scene Scene::fromParts(SceneParts parts) {
    Scene s;
    s.mesh_ = std::move(parts.mesh);
    s.normals_ = std::move(parts.normals);
    s.yarnRadius_ = parts.yarnRadius;
    s.grid_ = std::move(parts.grid);
    s.bound_.binding = std::move(parts.binding);
    s.bound_.stats = parts.bindStats;
    s.pattern_ = std::move(parts.pattern);
    s.placement_ = parts.placement;
    s.yarns_ = std::move(parts.yarns);
    if (parts.lazyYarns) {
        if (!s.yarns_.curves.points.empty()) throw Error("a scene with lazily evaluated yarns is given yarns");
        s.lazyYarns_ = std::make_shared<LazyYarns>();
    }
    s.plies_ = std::move(parts.plies);
    s.detail_ = std::move(parts.detail);
    if (parts.plyOptions) s.plyOptions_ = *parts.plyOptions;
    s.plyOptions_.yarnRadius = parts.yarnRadius;
    s.animatorState_ = std::move(parts.animatorState);
    s.deformOptions_ = std::move(parts.deform);
    s.deformer_ = std::move(parts.deformer);
    s.deformStats_ = parts.deformStats;
    return s;
}

}  // namespace knit
