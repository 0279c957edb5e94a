#include <gtest/gtest.h>
#include <cstdio>
#include <cstdlib>
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/relax.hpp"
namespace knit {
TEST(ZzProbe, energy) {
    const char* text = std::getenv("PROBE_CHART");
    if (!text) GTEST_SKIP();
    const ChartCell cell = chartToCell(parseChart(text, "probe"));
    RelaxOptions o;
    o.restLength = 0.8;
    o.restScale = cell.restScale;
    o.maxIterations = std::getenv("PROBE_ITERS") ? std::atoi(std::getenv("PROBE_ITERS")) : 4000;
    o.affinePeriod = std::getenv("PROBE_AFFINE0") == nullptr;
    const RelaxResult r = relaxYarn(cell.pattern, o);
    std::printf("done %d conv %d E %.6f min %.3f evals %d rebuilds %d px %.3f py %.3f\n", r.iterations, r.converged, r.energy,
                r.minDistance, r.evaluations, r.pairRebuilds, r.pattern.px / r.pattern.radius, r.pattern.py / r.pattern.radius);
}
}  // namespace knit
