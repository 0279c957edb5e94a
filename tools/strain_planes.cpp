// strain_planes: the measurements behind docs/deformation.md. Makes a pattern's strain table
// (timed: wall and process CPU seconds) or reads one, then maps the pattern onto planes strained
// uniformly by F (sx, sa, sy) and prints, per strain, the total yarn length over the rest plane's
// and the closest distance between yarns (radii) for `--deform none` and `--deform strain`.
//   strain_planes [--pattern P] [--table T.npy] [--samples NX NA NY] [--sx-range LO HI] [--sa-range LO HI]
//                 [--sy-range LO HI] [--size METRES] [--json]
//                 [--stretch W] [--bend W] [--contact W] [--barrier W] [--contact-distance R]
//                 [--barrier-distance R] [--iterations N] [--starts N]  (the table's solver)
#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/mat2x2.hpp>
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
};

PlaneResult measure(const knit::Scene& scene, const knit::Strain& s) {
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
    return r;
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
        const std::vector<std::pair<std::string, knit::Strain>> cases = {
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
