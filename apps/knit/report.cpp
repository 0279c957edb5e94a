// JSON reports and scene notes of the commands (see report.hpp).
#include "report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "knit/error.hpp"
#include "knit/export.hpp"

namespace knit::cli {

void checkReportPath(const std::string& path) {
    if (path.empty()) return;
    requireWritableFolder(path, "report");
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error("cannot write report '" + path + "': a folder with that name exists");
}

void writeReport(const std::string& path, const nlohmann::json& report) {
    writeFileAtomically(
        path, [&](std::ostream& out) { out << report.dump(2) << '\n'; }, false);
}

namespace {

nlohmann::json segmentReport(const SegmentStats& st) {
    nlohmann::json j;
    j["segments"] = st.segments;
    if (st.segments == 0) return j;
    j["median_segment_length"] = st.medianLength;
    j["longest_segment_length"] = st.longestLength;
    return j;
}

// Stitches and rows per 10 cm the placement achieves (the pattern's stitches and rows per period
// over the period's size on the mesh).
nlohmann::json gaugeReport(const Pattern& p, const PatternPlacement& placement) {
    if (!(placement.periodMetres.x > 0 && placement.periodMetres.y > 0)) return nullptr;  // no placement
    return {{"stitches_per_10cm", 0.1 * p.stitchesPerPeriod / placement.periodMetres.x},
            {"rows_per_10cm", 0.1 * p.rowsPerPeriod / placement.periodMetres.y},
            {"stitches_per_period", p.stitchesPerPeriod},
            {"rows_per_period", p.rowsPerPeriod}};
}

}  // namespace

std::string deformWhy(const DeformOptions& d) {
    char buf[160];
    switch (d.reason) {
        case DeformReason::TableGiven: return "--strain-table given";
        case DeformReason::Cached: return "the pattern's strain table was in the cache";
        case DeformReason::Made:
            std::snprintf(buf, sizeof buf, "the pattern's strain table was made now (%.1f s) and cached",
                          d.tableSeconds);
            return buf;
        case DeformReason::TooSlowToMake:
            std::snprintf(
                buf, sizeof buf,
                "no strain table at hand and making one takes about %.0f s (knit strain-table, or --deform strain)",
                d.tableSeconds);
            return buf;
        case DeformReason::CannotMake: return "the pattern cannot have a strain table (its yarns cannot be relaxed)";
        case DeformReason::Asked: break;
    }
    return d.mode == DeformMode::Strain ? "--deform strain" : "--deform none";
}

nlohmann::json sceneReport(const Scene& s, const SceneStats& st) {
    // Step 1: the inputs and their placement.
    nlohmann::json j;
    const Pattern& p = s.pattern();
    j["pattern"] = {{"name", p.name}, {"period", {p.px, p.py}}, {"radius", p.radius}, {"vertices", p.points.size()}};
    const BaseMesh& m = s.mesh();
    j["mesh"] = {{"name", m.name},
                 {"vertices", m.positions.size()},
                 {"uvs", m.uvs.size()},
                 {"faces", m.faces.size()},
                 {"degenerate_uv_faces", s.grid().degenerateUvFaces},
                 {"uv_charts", s.grid().islandCount},
                 {"folded_uv_faces", s.grid().foldedUvFaces},
                 {"overlapping_uv_charts", nlohmann::json::array()}};
    for (const glm::uvec2& pair : s.grid().overlappingIslands)
        j["mesh"]["overlapping_uv_charts"].push_back({pair.x, pair.y});
    if (s.grid().foldedUvFaces > 0) j["mesh"]["folded_uv_face_example"] = s.grid().foldedUvFaceExample;
    j["placement"] = {{"repeats", {s.placement().repeats.x, s.placement().repeats.y}},
                      {"scale", s.placement().scale},
                      {"yarn_radius", s.yarnRadius()},
                      {"gauge", gaugeReport(p, s.placement())}};
    // Step 2: the statistics.
    j["counts"] = {{"cells", st.cells},
                   {"tiles", st.tiles},
                   {"yarns", st.yarns},
                   {"closed_loops", st.bind.closedLoops},
                   {"open_ends", st.bind.openEnds},
                   {"cut_vertices", st.bind.cutVertices},
                   {"clamped_vertices", st.bind.clampedVertices},
                   {"boundary_vertices", st.bind.boundaryVertices},
                   {"welded_ends", st.bind.weldedEnds},
                   {"tiled_yarns", st.tiledYarns}};
    j["vertices"] = {{"tiled", st.tiledVertices}, {"yarn", st.yarnVertices}, {"ply", st.plyVertices}};
    j["yarn_segments"] = segmentReport(st.yarnSegments);
    if (st.plySegments) {
        const Plies& pl = s.plies();
        j["ply_segments"] = segmentReport(*st.plySegments);
        j["plies"] = {{"curves", pl.curves.curveCount()},
                      {"ply_radius", pl.plyRadius},
                      {"center_radius", pl.centerRadius},
                      {"pitch", pl.pitch}};
    }
    // Strain-aware deformation: the mode, the table and what it did on this mesh.
    const DeformStats& ds = s.deformStats();
    if (s.deformer()) {
        const StrainTable& t = s.deformer()->table();
        j["deform"] = {{"mode", "strain"},
                       {"strain_table", t.source},
                       {"samples", {t.axes[0].size(), t.axes[1].size(), t.axes[2].size()}},
                       {"displaced_vertices", ds.vertices},
                       {"clamped_fraction", ds.total ? double(ds.clamped) / double(ds.total) : 0.0},
                       {"degenerate_vertices", ds.degenerate}};
    } else {
        j["deform"] = {{"mode", "none"}};
    }
    j["deform"]["why"] = deformWhy(s.deformOptions());
    // Step 3: wall time per stage and in all.
    nlohmann::json times = nlohmann::json::object();
    for (const StageTime& t : st.stageTimes) times[t.stage] = t.seconds;
    times["total"] = st.totalSeconds;
    j["seconds"] = times;
    return j;
}

// A chart folded over itself: the folded layer gets no yarns of its own where it lies over the
// rest of the chart (see UvGrid::foldedUvFaces).
void printFoldWarning(const Scene& s) {
    const UvGrid& g = s.grid();
    if (g.foldedUvFaces == 0) return;
    const glm::dvec2 uv = s.mesh().uvs[s.mesh().faceUvs[g.foldedUvFaceExample].x];
    std::fprintf(stderr,
                 "knit: warning: %s: %zu triangles fold their UV chart over itself (e.g. triangle %u at uv %.4g, "
                 "%.4g): where the fold covers the chart twice, only one layer gets yarns; unfold the UV layout\n",
                 s.mesh().name.c_str(), g.foldedUvFaces, g.foldedUvFaceExample, uv.x, uv.y);
}

void printWarnings(const Scene& s) {
    printFoldWarning(s);
    if (s.grid().overlappingIslands.empty()) return;
    std::string pairs;
    const size_t shown = std::min<size_t>(s.grid().overlappingIslands.size(), 8);
    for (size_t k = 0; k < shown; ++k)
        pairs += (pairs.empty() ? "" : ", ") + std::to_string(s.grid().overlappingIslands[k].x) + "/" +
                 std::to_string(s.grid().overlappingIslands[k].y);
    if (shown < s.grid().overlappingIslands.size())
        pairs += " and " + std::to_string(s.grid().overlappingIslands.size() - shown) + " more pairs";
    std::fprintf(stderr, "knit: note: %s: UV charts overlap (%s); each chart is tiled and knitted on its own\n",
                 s.mesh().name.c_str(), pairs.c_str());
}

}  // namespace knit::cli
