// The whole pipeline as a plain composition of the stages, plus its JSON report.
#include "knit/scene.hpp"

#include <algorithm>
#include <chrono>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "knit/error.hpp"

namespace knit {
namespace {

class StageClock {
public:
    StageClock(Scene& scene, const ProgressFn& progress, int total) : scene_(scene), progress_(progress), total_(total) {}
    // Runs one named stage, recording its wall time.
    template <class F>
    void run(const std::string& name, F&& stage) {
        if (progress_) progress_(name, index_, total_);
        const auto t0 = std::chrono::steady_clock::now();
        stage();
        const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
        scene_.timings.push_back({name, dt.count()});
        ++index_;
    }

private:
    Scene& scene_;
    const ProgressFn& progress_;
    int total_;
    int index_ = 0;
};

nlohmann::json segmentStats(const Polylines& curves) {
    std::vector<double> lengths;
    lengths.reserve(curves.pointCount());
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const uint32_t b = curves.begin(c), n = curves.size(c);
        for (uint32_t s = 0; s < curves.segmentCount(c); ++s)
            lengths.push_back(glm::distance(curves.points[b + s], curves.points[b + (s + 1) % n]));
    }
    nlohmann::json j;
    j["segments"] = lengths.size();
    if (lengths.empty()) return j;
    const auto mid = lengths.begin() + lengths.size() / 2;
    std::nth_element(lengths.begin(), mid, lengths.end());
    j["median_segment_length"] = *mid;
    j["longest_segment_length"] = *std::max_element(lengths.begin(), lengths.end());
    return j;
}

}  // namespace

namespace {

// The grid cells each UV chart's triangles of non-zero UV area touch (a cell shared by several
// charts is listed for each; a chart of zero-area triangles only gets none: nothing to tile).
std::vector<std::vector<glm::ivec2>> cellsPerChart(const UvGrid& grid) {
    std::vector<std::vector<glm::ivec2>> cells(grid.chartCount);
    std::vector<uint32_t> seen;
    for (size_t k = 0; k < grid.cells.size(); ++k) {
        seen.clear();
        for (uint32_t i = grid.triOffsets[k]; i < grid.triOffsets[k + 1]; ++i) {
            if (grid.faceOrientation[grid.triangles[i]] == 0) continue;
            const uint32_t c = grid.chartOfFace[grid.triangles[i]];
            if (std::find(seen.begin(), seen.end(), c) != seen.end()) continue;
            seen.push_back(c);
            cells[c].push_back(grid.cells[k]);
        }
    }
    return cells;
}

void runStages(Scene& scene, const SceneOptions& options, StageClock& clock) {
    std::vector<Tiling>& chartTilings = scene.chartTilings;
    clock.run("normals", [&] { scene.normals = vertexNormals(scene.mesh.positions, scene.mesh.faces); });
    clock.run("uv_grid", [&] {
        scene.placement = placePattern(scene.pattern, scene.mesh, options.placement);
        scene.yarnRadius = scene.pattern.radius * scene.placement.scale;
        UvGridOptions gridOptions;
        gridOptions.cellSize = scene.placement.cellSize();
        scene.grid = buildUvGrid(scene.mesh, gridOptions);
    });
    clock.run("tiling", [&] {
        // Vertices within binding's clamp tolerance of the covered cells are tiled too (they are
        // clamped onto the UV boundary, not dropped because their own cell is empty).
        const glm::dvec2 metresPerUv = uvToMetreScale(scene.mesh);
        const double tolUv = options.bind.clampTolerance * scene.yarnRadius / std::max(metresPerUv.x, metresPerUv.y);
        const glm::dvec2 margin = tolUv * scene.placement.repeats * glm::dvec2(scene.pattern.px, scene.pattern.py);
        scene.tiling = tilesForCells(scene.pattern, scene.grid.cells, margin);
        // Overlapping UV charts: each chart is also tiled over its own cells, so that each gets
        // its own yarns (bound to that chart only).
        if (!scene.grid.overlappingCharts.empty()) {
            const std::vector<std::vector<glm::ivec2>> cells = cellsPerChart(scene.grid);
            for (const std::vector<glm::ivec2>& c : cells)
                chartTilings.push_back(c.empty() ? Tiling{} : tilesForCells(scene.pattern, c, margin));
        }
    });
    clock.run("stitch", [&] {
        const PatternAdjacency adjacency = buildAdjacency(scene.pattern);
        if (chartTilings.empty()) {
            scene.uvYarns = stitchYarns(scene.pattern, adjacency, scene.tiling, scene.placement);
        } else {
            scene.uvYarns = UvYarns{};
            for (size_t c = 0; c < chartTilings.size(); ++c)
                if (!chartTilings[c].tiles.empty())
                    appendChartYarns(scene.uvYarns,
                                     stitchYarns(scene.pattern, adjacency, chartTilings[c], scene.placement), uint32_t(c));
        }
    });
    clock.run("binding", [&] {
        BindOptions bind = options.bind;
        bind.yarnRadius = scene.yarnRadius;
        scene.bound = bindYarns(scene.mesh, scene.normals, scene.grid, scene.uvYarns, bind);
    });
    clock.run("evaluate", [&] {
        evaluateBinding(scene.bound.binding, scene.mesh.faces, scene.mesh.positions, scene.normals, scene.yarns);
    });
    PlyOptions plies = options.plies;
    plies.yarnRadius = scene.yarnRadius;
    scene.plyOptions = plies;  // resolved below when the plies are built; else by their consumer
    if (options.buildPlies)
        clock.run("plies", [&] {
            scene.plyOptions = resolvePlyOptions(plies);
            scene.plies = makePlies(scene.yarns, scene.plyOptions);
        });
}

int stageCount(const SceneOptions& options) { return options.buildPlies ? 9 : 8; }

}  // namespace

Scene buildScene(const SceneOptions& options) {
    Scene scene;
    StageClock clock(scene, options.progress, stageCount(options));
    clock.run("load_pattern", [&] { scene.pattern = loadPatternFileOrName(options.pattern); });
    clock.run("load_mesh", [&] {
        scene.mesh = loadMeshFileOrName(options.mesh, options.meshOptions);
        validateMesh(scene.mesh);
    });
    runStages(scene, options, clock);
    return scene;
}

Scene buildScene(Pattern pattern, BaseMesh mesh, const SceneOptions& options) {
    validatePattern(pattern, pattern.name);
    validateMesh(mesh);
    Scene scene;
    scene.pattern = std::move(pattern);
    scene.mesh = std::move(mesh);
    StageClock clock(scene, options.progress, stageCount(options) - 2);
    runStages(scene, options, clock);
    return scene;
}

nlohmann::json sceneReport(const Scene& s) {
    nlohmann::json j;
    j["pattern"] = {{"name", s.pattern.name},
                    {"period", {s.pattern.px, s.pattern.py}},
                    {"radius", s.pattern.radius},
                    {"vertices", s.pattern.points.size()}};
    j["mesh"] = {{"name", s.mesh.name},
                 {"vertices", s.mesh.positions.size()},
                 {"uvs", s.mesh.uvs.size()},
                 {"faces", s.mesh.faces.size()},
                 {"degenerate_uv_faces", s.grid.degenerateUvFaces},
                 {"uv_charts", s.grid.chartCount},
                 {"overlapping_uv_charts", nlohmann::json::array()}};
    for (const glm::uvec2& pair : s.grid.overlappingCharts) j["mesh"]["overlapping_uv_charts"].push_back({pair.x, pair.y});
    j["placement"] = {{"repeats", {s.placement.repeats.x, s.placement.repeats.y}},
                      {"scale", s.placement.scale},
                      {"yarn_radius", s.yarnRadius}};
    const BindStats& b = s.bound.stats;
    size_t tileCount = s.tiling.tiles.size();  // the tiles the yarns come from
    if (!s.chartTilings.empty()) {
        tileCount = 0;
        for (const Tiling& t : s.chartTilings) tileCount += t.tiles.size();
    }
    j["counts"] = {{"cells", s.grid.cells.size()},
                   {"tiles", tileCount},
                   {"yarns", s.yarns.curves.curveCount()},
                   {"closed_loops", b.closedLoops},
                   {"open_ends", b.openEnds},
                   {"cut_vertices", b.cutVertices},
                   {"clamped_vertices", b.clampedVertices},
                   {"boundary_vertices", b.boundaryVertices},
                   {"welded_ends", b.weldedEnds},
                   {"tiled_yarns", s.uvYarns.yarnCount()}};
    j["vertices"] = {{"tiled", s.uvYarns.vertexCount()},
                     {"yarn", s.yarns.curves.pointCount()},
                     {"ply", s.plies.curves.pointCount()}};
    j["yarn_segments"] = segmentStats(s.yarns.curves);
    if (s.plies.curves.curveCount() > 0) {
        j["ply_segments"] = segmentStats(s.plies.curves);
        j["plies"] = {{"curves", s.plies.curves.curveCount()},
                      {"ply_radius", s.plies.plyRadius},
                      {"center_radius", s.plies.centerRadius},
                      {"pitch", s.plies.pitch}};
    }
    nlohmann::json times = nlohmann::json::object();
    double total = 0;
    for (const StageTime& t : s.timings) {
        times[t.stage] = t.seconds;
        total += t.seconds;
    }
    times["total"] = total;
    j["seconds"] = times;
    return j;
}

}  // namespace knit
