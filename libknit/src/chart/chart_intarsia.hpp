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
//
// Motifs: when the areas change from row to row, the rows fall into blocks of rows with the same
// areas. A block of one colour is knitted as plain courses (the background's yarn, closing
// through the period in x); in a block of several areas each area's yarn is an open serpentine
// over the block's rows with a tail at each end, run behind two stitches of its own area (the
// tails a knitter weaves in), and the yarns turn and interlock at the boundaries as above.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "knit/chart.hpp"

namespace knit::intarsia {

// A colour area of every row: columns [first, first + count), cyclic over the chart's width.
struct Area {
    char colour = 0;
    int first = 0, count = 0;
    bool operator==(const Area& o) const { return colour == o.colour && first == o.first && count == o.count; }
};
// The areas of a row of an intarsia chart (the runs of equal colour along it, cyclic), leftmost
// first (an area that wraps round the period is listed where it starts).
std::vector<Area> areas(const Chart& chart, int row = 0);

// Consecutive rows with the same areas: rows first .. first + rows - 1, cyclic (a block may run
// past the last row into row 0; its rows are then unwrapped, above the chart's height).
struct RowBlock {
    int first = 0, rows = 0;
    std::vector<Area> areas;
};
// The chart's blocks in row order: one block of every row when the areas are vertical bands
// (each yarn a closed serpentine), else starting at the lowest row whose areas differ from the
// row below's (cyclic).
std::vector<RowBlock> rowBlocks(const Chart& chart);

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

// A motif yarn's tail (model units): from the foot `foot` of its first or last loop in a row whose
// loop centres lie at y = rowY, behind the work into its own area (inward: +1 to the right, -1 to
// the left) across `stitches` stitches' worth (1 or 2), ending clear of the area's far boundary.
// The points run from the foot outwards, `foot` excluded, about `spacing` apart; a starting
// tail takes them in reverse order.
std::vector<glm::dvec3> tailPoints(const glm::dvec3& foot, double rowY, int inward, int stitches, double spacing);

}  // namespace knit::intarsia
