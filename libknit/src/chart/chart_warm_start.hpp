// chart_warm_start.hpp — a relaxed chart cell carried to a finer sampling of the same chart
// (internal to chart_pattern.cpp): relaxChart starts its full relaxation from the chart relaxed
// at fewer samples per stitch.
//
// The two cells are chartToCell of one chart at two samplings: the same yarns in the same order,
// each yarn the same curve sampled more or less densely. A vertex of the fine cell is carried by
// its arc-length fraction along its yarn in the fine initial cell, which falls between the
// fractions of two coarse vertices (where they lie on the fine polyline): the vertex goes to the
// same place between where those two came to rest. So every fine vertex lies on the relaxed coarse
// polyline: no yarn passes through another that the coarse relaxation kept apart.
#pragma once
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/pattern.hpp"

namespace knit::warmstart {

struct FineStart {
    std::vector<glm::dvec3> points;  // one per vertex of the fine cell (metres)
    double px = 0, py = 0;           // the relaxed coarse period
    // The check of the correspondence: the largest distance, in yarn radii, between a vertex of
    // the fine initial cell and where the same map takes it from the coarse initial cell (the
    // coarse polyline's chord error where the two samplings follow one curve).
    double mismatch = 0;
};

// std::nullopt when the two cells' yarns do not correspond (their count, open or closed, the
// periods a closed yarn goes round). coarseRelaxed has coarseInitial's vertices and edges.
std::optional<FineStart> carryRelaxed(const Pattern& coarseInitial, const Pattern& coarseRelaxed,
                                      const Pattern& fineInitial);

}  // namespace knit::warmstart
