// strain_planes: the measurements behind docs/deformation.md. Makes a pattern's strain table
// (timed: wall and process CPU seconds) or reads one, then maps the pattern onto planes strained
// uniformly by F (sx, sa, sy) and prints, per strain, the total yarn length over the rest plane's
// and the closest distance between yarns (radii) for `--deform none` and `--deform strain`.
//   strain_planes [--pattern P] [--table T.npy] [--samples NX NA NY] [--sx-range LO HI] [--sa-range LO HI]
//                 [--sy-range LO HI] [--size METRES] [--json]
//                 [--stretch W] [--bend W] [--contact W] [--barrier W] [--contact-distance R]
//                 [--barrier-distance R] [--iterations N] [--starts N]  (the table's solver)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/mat2x2.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "knit/strain.hpp"

namespace {

using glm::dvec3;

// A square in the xy plane, uv = position / size (isometric at the pattern's physical size).
knit::BaseMesh squarePlane(double size, int n) {
    knit::BaseMesh m;
    m.name = "square";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const glm::dvec2 uv(double(i) / n, double(j) / n);
            m.uvs.push_back(uv);
            m.positions.emplace_back(uv.x * size, uv.y * size, 0.0);
        }
    const auto id = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    m.faceUvs = m.faces;
    return m;
}

struct PlaneResult {
    double lengthRatio = 1, closestRadii = 0, clampedFraction = 0;
    // With --where (closestPairs): the closest yarns recounted over the resampled centrelines
    // (radii), how far that pair is from the plane's edge (periods), and the closest pair at least
    // `interiorMargin` periods inside the edges (the periodic cell's own state under this strain).
    double recountedRadii = 0, pairEdgePeriods = 0, pairEndRadii = 0, interiorRadii = 0;
};

// Closest points of different yarns (distinct centrelines, or one centreline's points more than
// `separation` apart along it), all of them and those whose pattern-space pre-image (F^-1 of the
// position) lies `margin` inside the plane's square [0, size]^2. A grid of cells `reach` wide:
// pairs farther apart than that are not seen (+inf).
struct ClosestPairs {
    double all = std::numeric_limits<double>::infinity(), interior = std::numeric_limits<double>::infinity();
    double pairEdge = 0;  // the closest pair's distance from the edge (metres, pattern space)
    double pairEnd = 0;   // ... and from the nearer end of an open centreline along it (metres; inf: closed)
};
ClosestPairs closestPairs(const knit::Polylines& c, const glm::dmat2& F, double size, double margin, double separation,
                          double reach) {
    const glm::dmat2 Finv = glm::inverse(F);
    const size_t n = c.pointCount();
    std::vector<uint32_t> curve(n);
    std::vector<double> arc(n, 0.0), edge(n);
    std::vector<double> curveLength(c.curveCount());
    for (size_t k = 0; k < c.curveCount(); ++k) {
        for (uint32_t i = c.begin(k); i < c.end(k); ++i) {
            curve[i] = uint32_t(k);
            if (i > c.begin(k)) arc[i] = arc[i - 1] + glm::length(c.points[i] - c.points[i - 1]);
        }
        const uint32_t last = c.end(k) - 1;
        curveLength[k] = arc[last] + (c.isClosed(k) ? glm::length(c.points[c.begin(k)] - c.points[last]) : 0.0);
    }
    std::unordered_map<int64_t, std::vector<uint32_t>> grid;
    const auto key = [](int64_t x, int64_t y) { return (x << 32) ^ (y & 0xffffffff); };
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 q = Finv * glm::dvec2(c.points[i]);
        edge[i] = std::min({q.x, size - q.x, q.y, size - q.y});
        grid[key(int64_t(std::floor(c.points[i].x / reach)), int64_t(std::floor(c.points[i].y / reach)))].push_back(
            uint32_t(i));
    }
    const auto fromEnd = [&](size_t i) {
        return c.isClosed(curve[i]) ? std::numeric_limits<double>::infinity()
                                    : std::min(arc[i], arc[c.end(curve[i]) - 1] - arc[i]);
    };
    ClosestPairs r;
    for (size_t i = 0; i < n; ++i) {
        const auto gx = int64_t(std::floor(c.points[i].x / reach)), gy = int64_t(std::floor(c.points[i].y / reach));
        for (int64_t dx = -1; dx <= 1; ++dx)
            for (int64_t dy = -1; dy <= 1; ++dy) {
                const auto it = grid.find(key(gx + dx, gy + dy));
                if (it == grid.end()) continue;
                for (const uint32_t j : it->second) {
                    if (j <= i) continue;
                    if (curve[i] == curve[j]) {
                        double along = std::abs(arc[i] - arc[j]);
                        if (c.isClosed(curve[i])) along = std::min(along, curveLength[curve[i]] - along);
                        if (along <= separation) continue;
                    }
                    const double d = glm::length(c.points[i] - c.points[j]);
                    if (d < r.all) {
                        r.all = d;
                        r.pairEdge = std::min(edge[i], edge[j]);
                        r.pairEnd = std::min(fromEnd(i), fromEnd(j));
                    }
                    if (edge[i] >= margin && edge[j] >= margin) r.interior = std::min(r.interior, d);
                }
            }
    }
    return r;
}

// Where the closest pairs are measured (--where): 1.5 periods inside the plane's edges.
constexpr double kInteriorMargin = 1.5;

PlaneResult measure(const knit::Scene& scene, const knit::Strain& s, double size = 0) {
    const glm::dmat2 F = knit::latticeMap(s);
    std::vector<dvec3> pose;
    for (const dvec3& p : scene.mesh().positions) {
        const glm::dvec2 q = F * glm::dvec2(p.x, p.y);
        pose.emplace_back(q.x, q.y, 0.0);
    }
    knit::AnimatorOptions o;
    o.plies = false;
    o.stats = true;
    const knit::Animator a(scene, o);
    knit::AnimationFrame f;
    a.evaluate(pose, f);
    PlaneResult r;
    r.lengthRatio = f.stats.yarnLengthRatio;
    r.closestRadii = 2 * f.stats.minYarnDistance;  // the statistic is in diameters
    r.clampedFraction = f.deform.total ? double(f.deform.clamped) / double(f.deform.total) : 0.0;
    if (size > 0) {  // --where
        const double radius = scene.yarnRadius();
        const double period = std::max(scene.pattern().px, scene.pattern().py) * scene.placement().scale;
        const ClosestPairs c = closestPairs(f.centres, F, size, kInteriorMargin * period, 8 * radius, 4 * radius);
        r.recountedRadii = c.all / radius;
        r.pairEdgePeriods = c.pairEdge / period;
        r.pairEndRadii = c.pairEnd / radius;
        r.interiorRadii = c.interior / radius;
    }
    return r;
}

// "sx,sa,sy;sx,sa,sy" as named planes.
std::vector<std::pair<std::string, knit::Strain>> parseStrains(const std::string& text) {
    std::vector<std::pair<std::string, knit::Strain>> out;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ';')) {
        knit::Strain s;
        char c1 = 0, c2 = 0;
        std::istringstream one(item);
        if (!(one >> s.sx >> c1 >> s.sa >> c2 >> s.sy) || c1 != ',' || c2 != ',')
            throw knit::Error("--strains: '" + item + "' is not sx,sa,sy");
        out.emplace_back(item, s);
    }
    return out;
}

// The table's samples around s (each axis: the two samples bracketing it, one where it sits on
// a sample or is clamped).
std::vector<knit::Strain> bracketingSamples(const knit::StrainTable& t, const knit::Strain& s) {
    const double v[3] = {s.sx, s.sa, s.sy};
    std::vector<double> around[3];
    for (size_t a = 0; a < 3; ++a) {
        const std::vector<double>& x = t.axes[a];
        const auto hi = std::lower_bound(x.begin(), x.end(), v[a]);
        if (hi != x.end() && *hi == v[a]) around[a] = {*hi};
        else if (hi == x.begin()) around[a] = {x.front()};
        else if (hi == x.end()) around[a] = {x.back()};
        else around[a] = {*(hi - 1), *hi};
    }
    std::vector<knit::Strain> out;
    for (const double sx : around[0])
        for (const double sa : around[1])
            for (const double sy : around[2]) out.push_back({sx, sa, sy});
    return out;
}

// --where: per plane, where its closest yarns are (docs/deformation.md, "Where the stiff tables'
// close pairs come from").
void printWhere(const knit::Pattern& pattern, const knit::StrainTable& table, const knit::StrainTableOptions& solver,
                const knit::Scene& scene, const std::vector<std::pair<std::string, knit::Strain>>& cases, double size,
                nlohmann::json& out, bool json) {
    if (!json)
        std::printf("| plane | closest (r) | pair from edge (periods) | pair from a yarn end (r) | interior (r) | "
                    "samples around: interior (r) | "
                    "cell relaxed at the strain (r) |\n|---|---|---|---|---|---|---|\n");
    for (const auto& [name, s] : cases) {
        const PlaneResult d = measure(scene, s, size);
        std::string corners;
        double worst = std::numeric_limits<double>::infinity();
        for (const knit::Strain& c : bracketingSamples(table, s)) {
            const double r = measure(scene, c, size).interiorRadii;
            worst = std::min(worst, r);
            char buf[96];
            std::snprintf(buf, sizeof buf, "%s(%.3g,%.3g,%.3g) %.2f", corners.empty() ? "" : ", ", c.sx, c.sa, c.sy, r);
            corners += buf;
        }
        const knit::StrainCellResult cell = knit::relaxStrainCell(pattern, s, solver);
        out["where"].push_back({{"name", name},
                                {"strain", {s.sx, s.sa, s.sy}},
                                {"closest_radii", d.recountedRadii},
                                {"pair_edge_periods", d.pairEdgePeriods},
                                {"pair_end_radii", d.pairEndRadii},
                                {"interior_radii", d.interiorRadii},
                                {"samples_interior_min_radii", worst},
                                {"cell_radii", cell.closestRadii},
                                {"cell_length_ratio", cell.lengthRatio}});
        if (!json)
            std::printf("| %s | %.2f | %.2f | %.2f | %.2f | min %.2f: %s | %.2f |\n", name.c_str(), d.recountedRadii,
                        d.pairEdgePeriods, d.pairEndRadii, d.interiorRadii, worst, corners.c_str(), cell.closestRadii);
    }
}

int run(int argc, char** argv) {
    CLI::App app("Strain tables on uniformly strained planes (docs/deformation.md)");
    std::string patternName = "stockinette", tablePath;
    std::vector<int> samples{9, 9, 9};
    double size = 0.06;
    bool json = false;
    knit::StrainTableOptions tableOptions;
    app.add_option("--pattern", patternName, "Pattern file or built-in name")->capture_default_str();
    app.add_option("--table", tablePath, "Read this table instead of making one");
    app.add_option("--samples", samples, "Samples along sx, sa, sy when making the table")->expected(3);
    std::vector<double> sxRange{-0.2, 1.0}, saRange{-0.7, 0.7}, syRange{-0.2, 1.0};
    app.add_option("--sx-range", sxRange, "The table's sx range when making it")->expected(2);
    app.add_option("--sa-range", saRange, "The table's sa range when making it")->expected(2);
    app.add_option("--sy-range", syRange, "The table's sy range when making it")->expected(2);
    app.add_option("--size", size, "Side of the plane (metres)")->capture_default_str();
    app.add_option("--stretch", tableOptions.stretch, "The table solver's stretch weight")->capture_default_str();
    app.add_option("--bend", tableOptions.bend, "The table solver's bending weight")->capture_default_str();
    app.add_option("--contact", tableOptions.contact, "The table solver's contact weight")->capture_default_str();
    app.add_option("--barrier", tableOptions.barrier, "The table solver's contact barrier weight")
        ->capture_default_str();
    app.add_option("--contact-distance", tableOptions.contactDistance, "The table solver's contact distance (radii)")
        ->capture_default_str();
    app.add_option("--barrier-distance", tableOptions.barrierDistance,
                   "Where the table solver's contact barrier starts (radii)")
        ->capture_default_str();
    app.add_option("--iterations", tableOptions.maxIterations, "The table solver's iteration cap per sample")
        ->capture_default_str();
    app.add_option("--starts", tableOptions.startsPerSample,
                   "Relax each sample from this many lower neighbours (1-3), keep the lowest energy")
        ->capture_default_str();
    app.add_flag("--json", json, "JSON instead of a Markdown table");
    bool where = false;
    std::string savePath, strainList;
    app.add_flag("--where", where,
                 "Also where the closest yarns are: recounted, their distance from the plane's edge (periods), the "
                 "closest 1.5 periods inside the edges, the same inside the planes at the table's 8 samples around "
                 "the strain, and the cell relaxed at the strain itself (relaxStrainCell)");
    app.add_option("--save", savePath, "Write the table made to this file (.npy and its axes)");
    app.add_option("--strains", strainList, "Only these planes: 'sx,sa,sy;sx,sa,sy;...'");
    CLI11_PARSE(app, argc, argv);
    try {
        const knit::Pattern pattern = knit::loadPatternFileOrName(patternName);
        nlohmann::json out;
        std::shared_ptr<const knit::StrainTable> table;
        if (tablePath.empty()) {
            knit::StrainTableOptions to = tableOptions;
            to.samples = {samples[0], samples[1], samples[2]};
            to.sxRange = {sxRange[0], sxRange[1]};
            to.saRange = {saRange[0], saRange[1]};
            to.syRange = {syRange[0], syRange[1]};
            knit::StrainTableStats st;
            const std::clock_t c0 = std::clock();
            table = std::make_shared<const knit::StrainTable>(knit::makeStrainTable(pattern, to, &st));
            const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
            out["table"] = {{"vertices", table->vertexCount}, {"samples", table->samples()},
                            {"wall_seconds", st.seconds},     {"cpu_seconds", cpu},
                            {"unconverged", st.unconverged},  {"iterations", st.iterations},
                            {"closest_radii", st.minDistance}};
        } else {
            table = std::make_shared<const knit::StrainTable>(knit::loadStrainTable(tablePath));
            out["table"] = {{"file", tablePath}, {"vertices", table->vertexCount}, {"samples", table->samples()}};
        }
        knit::SceneOptions so;
        so.buildPlies = false;
        const knit::BaseMesh mesh = squarePlane(size, 24);
        const knit::Scene none = knit::buildScene(pattern, mesh, so);
        so.deform = {knit::DeformMode::Strain, table};
        const knit::Scene strain = knit::buildScene(pattern, mesh, so);
        if (!savePath.empty()) writeStrainTable(*table, savePath);
        std::vector<std::pair<std::string, knit::Strain>> cases = {
            {"rest", {0, 0, 0}},
            {"stretch along courses 33 %", {0.33, 0, 0}},
            {"stretch along courses 50 %", {0.5, 0, 0}},
            {"stretch along courses 100 %", {1.0, 0, 0}},
            {"stretch along wales 50 %", {0, 0, 0.5}},
            {"stretch along wales 100 %", {0, 0, 1.0}},
            {"biaxial stretch 50 %", {0.5, 0, 0.5}},
            {"biaxial stretch 100 %", {1.0, 0, 1.0}},
            {"compression -20 % both", {-0.2, 0, -0.2}},
            {"compression -20 % courses", {-0.2, 0, 0}},
            {"shear sa 0.7", {0, 0.7, 0}},
            {"shear sa -0.7", {0, -0.7, 0}},
            {"shear 0.7 + stretch 50 %", {0.5, 0.7, 0}},
        };
        if (!strainList.empty()) cases = parseStrains(strainList);
        if (where) {
            printWhere(pattern, *table, tableOptions, strain, cases, size, out, json);
            if (json) std::cout << out.dump(2) << '\n';
            return 0;
        }
        if (!json) {
            std::printf("| plane | sx | sa | sy | length ratio none | length ratio strain | closest none (r) | closest "
                        "strain (r) | clamped |\n|---|---|---|---|---|---|---|---|---|\n");
        }
        for (const auto& [name, s] : cases) {
            const PlaneResult g = measure(none, s), d = measure(strain, s);
            out["planes"].push_back({{"name", name},
                                     {"strain", {s.sx, s.sa, s.sy}},
                                     {"none", {{"length_ratio", g.lengthRatio}, {"closest_radii", g.closestRadii}}},
                                     {"strain", {{"length_ratio", d.lengthRatio}, {"closest_radii", d.closestRadii}}},
                                     {"clamped_fraction", d.clampedFraction}});
            if (!json)
                std::printf("| %s | %.2f | %.2f | %.2f | %.3f | %.3f | %.2f | %.2f | %.0f %% |\n", name.c_str(), s.sx,
                            s.sa, s.sy, g.lengthRatio, d.lengthRatio, g.closestRadii, d.closestRadii,
                            100 * d.clampedFraction);
        }
        // Stretch sequences on a 30 cm sheet (the runs of issue 23): a third along the courses while
        // the wales contract by a tenth, then released; a biaxial stretch by 30 % and release. Per
        // sequence: the range of the frames' yarn length ratio and the closest yarns (diameters).
        const knit::BaseMesh sheet = squarePlane(0.3, 30);
        knit::SceneOptions sheetOptions;
        sheetOptions.buildPlies = false;
        const knit::Scene sheetNone = knit::buildScene(pattern, sheet, sheetOptions);
        sheetOptions.deform = {knit::DeformMode::Strain, table};
        const knit::Scene sheetStrain = knit::buildScene(pattern, sheet, sheetOptions);
        const std::vector<std::pair<std::string, knit::Strain>> sequences = {
            {"courses +33 %, wales -10 %, and back", {1.0 / 3, 0, -0.1}}, {"biaxial +30 % and back", {0.3, 0, 0.3}}};
        if (!json)
            std::printf("\n| sequence (21 frames) | length ratio none | length ratio strain | closest none (diam.) | "
                        "closest strain (diam.) |\n|---|---|---|---|---|\n");
        for (const auto& [name, peak] : sequences) {
            double lo[2] = {1e9, 1e9}, hi[2] = {0, 0}, closest[2] = {1e9, 1e9};
            for (int k = 0; k <= 20; ++k) {
                const double w = k <= 10 ? k / 10.0 : (20 - k) / 10.0;
                const knit::Strain s{w * peak.sx, 0, w * peak.sy};
                const PlaneResult r[2] = {measure(sheetNone, s), measure(sheetStrain, s)};
                for (int m = 0; m < 2; ++m) {
                    lo[m] = std::min(lo[m], r[m].lengthRatio);
                    hi[m] = std::max(hi[m], r[m].lengthRatio);
                    closest[m] = std::min(closest[m], r[m].closestRadii / 2);
                }
            }
            out["sequences"].push_back(
                {{"name", name},
                 {"none", {{"length_ratio", {lo[0], hi[0]}}, {"closest_diameters", closest[0]}}},
                 {"strain", {{"length_ratio", {lo[1], hi[1]}}, {"closest_diameters", closest[1]}}}});
            if (!json)
                std::printf("| %s | %.3f - %.3f | %.3f - %.3f | %.2f | %.2f |\n", name.c_str(), lo[0], hi[0], lo[1],
                            hi[1], closest[0], closest[1]);
        }
        if (json) std::cout << out.dump(2) << '\n';
        else std::cout << "\ntable: " << out["table"].dump() << '\n';
    } catch (const knit::Error& e) {
        std::fprintf(stderr, "strain_planes: %s\n", e.what());
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strain_planes: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "strain_planes: unknown error\n");
    }
    return 1;
}
