// strain_bound: how short can a pattern's yarn be on a strained lattice? The feasibility bound
// behind docs/deformation.md's targets. Per strain plane, the pattern's cell is relaxed (the strain
// tables' solver, knit::relaxStrainCell, from the pattern's own cell through the lattice stages)
//   * taut: rest lengths a fraction of the pattern's (--taut-scale), so the yarn is under tension
//     everywhere and pulls itself as short as its crossings allow, against a contact barrier
//     starting at each of the --distances (radii): the shortest yarn with the crossing structure
//     kept and no two centrelines closer than about that distance;
//   * stiff: the tables' energy with the yarn's stretch weight and the barrier raised (--stiff):
//     a nearly inextensible yarn, whose contacts then show how hard it must press its crossings.
// Prints per plane the cell's yarn length over the rest cell's and the closest centrelines (radii).
//   strain_bound [--pattern P] [--taut-scale S] [--taut-stretch W] [--taut-barrier W] [--distances D...]
//                [--stiff W] [--iterations N] [--json]
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "knit/generator.hpp"
#include "knit/strain.hpp"

namespace {

int run(int argc, char** argv) {
    CLI::App app("The shortest yarn a strained lattice allows (docs/deformation.md, feasibility)");
    std::string patternName = "stockinette";
    double tautScale = 0.8, tautStretch = 200, tautBarrier = 2000, stiff = 1e5;
    int iterations = 2000;
    std::vector<double> distances{2.0, 1.5, 1.25, 1.0};
    bool json = false;
    app.add_option("--pattern", patternName, "Pattern file or built-in name")->capture_default_str();
    app.add_option("--taut-scale", tautScale, "Rest lengths of the taut yarn, as a fraction of the pattern's")
        ->capture_default_str();
    app.add_option("--taut-stretch", tautStretch, "Stretch weight of the taut yarn (its tension)")
        ->capture_default_str();
    app.add_option("--taut-barrier", tautBarrier, "Barrier weight of the taut yarn's contacts")->capture_default_str();
    app.add_option("--distances", distances, "Contact barrier distances of the taut yarn (radii)")
        ->capture_default_str();
    app.add_option("--stiff", stiff, "Stretch and barrier weight of the stiff yarn")->capture_default_str();
    app.add_option("--iterations", iterations, "Newton iteration cap per lattice stage")->capture_default_str();
    app.add_flag("--json", json, "JSON instead of a Markdown table");
    CLI11_PARSE(app, argc, argv);
    const knit::Pattern pattern = knit::loadPatternFileOrName(patternName);
    const std::vector<std::pair<std::string, knit::Strain>> cases = {
        {"rest", {0, 0, 0}},
        {"courses 33 %", {0.33, 0, 0}},
        {"courses 40 %", {0.4, 0, 0}},
        {"courses 45 %", {0.45, 0, 0}},
        {"courses 50 %", {0.5, 0, 0}},
        {"courses 100 %", {1.0, 0, 0}},
        {"wales 33 %", {0, 0, 0.33}},
        {"wales 40 %", {0, 0, 0.4}},
        {"wales 45 %", {0, 0, 0.45}},
        {"wales 50 %", {0, 0, 0.5}},
        {"wales 100 %", {0, 0, 1.0}},
        {"biaxial 30 %", {0.3, 0, 0.3}},
        {"biaxial 40 %", {0.4, 0, 0.4}},
        {"biaxial 45 %", {0.45, 0, 0.45}},
        {"biaxial 50 %", {0.5, 0, 0.5}},
        {"biaxial 100 %", {1.0, 0, 1.0}},
    };
    nlohmann::json out;
    if (!json) {
        std::printf("| plane |");
        for (double d : distances) std::printf(" taut, barrier %.2f r |", d);
        std::printf(" stiff (%g) |\n|---|", stiff);
        for (size_t k = 0; k <= distances.size(); ++k) std::printf("---|");
        std::printf("\n");
    }
    for (const auto& [name, s] : cases) {
        nlohmann::json row = {{"name", name}, {"strain", {s.sx, s.sa, s.sy}}};
        if (!json) std::printf("| %s |", name.c_str());
        std::vector<knit::StrainCellResult> runs;
        for (double d : distances) {
            knit::StrainTableOptions o;
            o.stretch = tautStretch;
            o.contact = 0;
            o.contactDistance = d;
            o.barrierDistance = d;
            o.barrier = tautBarrier;
            o.maxIterations = iterations;
            runs.push_back(knit::relaxStrainCell(pattern, s, o, tautScale));
        }
        knit::StrainTableOptions o;
        o.stretch = stiff;
        o.barrier = stiff;
        o.maxIterations = iterations;
        runs.push_back(knit::relaxStrainCell(pattern, s, o));
        for (size_t k = 0; k < runs.size(); ++k) {
            const knit::StrainCellResult& r = runs[k];
            row[k < distances.size() ? "taut" : "stiff"].push_back({{"length_ratio", r.lengthRatio},
                                                                    {"closest_radii", r.closestRadii},
                                                                    {"iterations", r.iterations},
                                                                    {"converged", r.converged}});
            if (!json) std::printf(" %.3f / %.2f%s |", r.lengthRatio, r.closestRadii, r.converged ? "" : "*");
        }
        if (!json) std::printf("\n");
        std::fflush(stdout);
        out["planes"].push_back(row);
    }
    if (json) std::cout << out.dump(2) << '\n';
    return 0;
}

}  // namespace

// A failure (a pattern that cannot be read or relaxed: knit::Error) is one line on stderr; CLI11
// reports its own option errors.
int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strain_bound: %s\n", e.what());
        return 1;
    }
}
