// chart_intarsia.hpp — intarsia colourwork in a periodic cell (internal to chart_topology.cpp):
// the colour areas of a chart and the yarn's turn where an area ends in a row.
//
// Intarsia is knitted back and forth, each colour area with its own yarn. In a periodic cell the
// areas are vertical bands (each column keeps its colour on every row: parseChart refuses other
// layouts), so each area's yarn runs along its columns of row 0 to the right, turns at the area's
// boundary up into row 1, runs back to the left, turns at the other boundary, and so on: a
// serpentine that closes through the period in y (an even number of rows; an odd chart is
// stacked twice). Where two areas meet, the yarns turn on alternate rows, and each turn reaches
// past the boundary behind the work and hooks through its neighbours' turns above and below: a
// chain of interlocked turns along the boundary, the twist knitters make when they change
// colour, so the areas hold together (no slit) and no yarn floats.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "knit/chart.hpp"

namespace knit::intarsia {

// A colour area of every row: columns [first, first + count), cyclic over the chart's width.
struct Area {
    char colour = 0;
    int first = 0, count = 0;
};
// The areas of an intarsia chart (the runs of equal colour along row 0, cyclic), leftmost first
// (an area that wraps round the period is listed where it starts).
std::vector<Area> areas(const Chart& chart);

// An odd-height chart stacked twice (its rows repeated, cables copied), so each yarn's
// serpentine closes after an even number of rows; an even one unchanged.
Chart evenRows(const Chart& chart);

// One turn of a yarn at a colour boundary, in model units (yarn radius 0.8): from the foot
// `from` of its last loop in row g to the foot `to` of its first loop in row g + 1 (unwrapped).
// `boundary` is the boundary's x, `side` where the yarn's own area lies (-1 left, +1 right).
struct Turn {
    glm::dvec3 from{0.0}, to{0.0};
    double boundary = 0;
    int side = -1;
};
// The turn's vertices, `from` first, `to` excluded, about `spacing` apart: from the foot back
// behind the work, across the boundary to its far edge, up past the next row's foot, and back.
std::vector<glm::dvec3> turnPoints(const Turn& turn, double spacing);

// The feet of the loops beside a boundary stop this far (model units) short of it.
constexpr double kBoundaryInset = 1.2;

}  // namespace knit::intarsia
