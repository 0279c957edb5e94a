// chart_intarsia.hpp — intarsia colourwork in a periodic cell (internal to chart_topology.cpp):
// the colour areas of a chart and the yarn's turn where an area ends in a row.
//
// Intarsia is knitted back and forth, each colour area with its own yarn. When every row's areas
// continue from the row below's (vertical bands, or boundaries that step a column between rows),
// each area's yarn runs along its columns of row 0 to the right, turns at the area's boundary up
// into row 1, runs back to the left, turns at the other boundary, and so on: a serpentine that
// closes through the period in y (an even number of rows; an odd chart is stacked twice, and
// areas that move round the period onto another area of their colour are stacked until each comes
// back to itself). Where
// two areas meet, the yarns turn on alternate rows, and each turn reaches past the boundary
// behind the work and hooks through its neighbours' turns above and below: a chain of
// interlocked turns along the boundary, the twist knitters make when they change colour, so the
// areas hold together (no slit) and no yarn floats. Where the boundary moves a column between
// two rows (a diagonal; or two or more columns, a steep one), the turn between them is carried that
// many stitches on behind the work, its ends at each row's boundary, so it still hooks through the
// neighbour's turns of both rows.
//
// Motifs: when the areas do not continue from row to row (an area starts or ends, a boundary
// jumps by half the width: either way round), the rows fall into blocks of rows whose areas continue. A block
// of one colour is knitted as plain courses (the background's yarn, closing through the period
// in x); in a block of several areas each area's yarn is an open serpentine over the block's rows
// with a tail at each end, run behind two stitches of its own area (the tails a knitter weaves
// in), and the yarns turn and interlock at the boundaries as above.
#pragma once
#include <optional>
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

// Where an area lies in one row of its block: columns [first, first + count) with `first`
// unwrapped along the block (below 0 or past the width once the area has moved across the
// period's edge), and its index among areas(chart, row) (the row's yarn that knits it).
struct Place {
    int first = 0, count = 0, index = 0;
};

// Up to this many columns a boundary's move between two rows is read as since issue 25 round 5
// (cyclically from -kMaxMove). A longer move is read the shorter way round the period (at most
// half the width): the area's yarn is carried that many stitches on behind the work (issue 25
// round 9), unless it is a tie (half the width either way, or two shifts of the areas as near).
constexpr int kMaxMove = 2;

// Two rows whose areas would continue but for a boundary that could move either way round the
// period: the upper row, the boundary's column in the row below (its left edge: the first column
// of the area to its right, unwrapped) and how many columns it moves either way.
struct Tie {
    int row = 0, column = 0, columns = 0;
};
// The tie between row - 1 and `row` (cyclic), if any.
std::optional<Tie> tiedMove(const Chart& chart, int row);

// Consecutive rows whose areas continue from row to row: the same colours in the same order, each
// boundary in the same column or moved the shorter way round the period (a diagonal: the area's
// yarn knits some stitches more or fewer on the next row, carried across the step). Rows first .. first +
// rows - 1, cyclic (a block may run past the last row into row 0; its rows are then unwrapped,
// above the chart's height). places[a][k] is area a's place in the block's row k (areas[a] in row 0); a closed
// block (every row continues, round the period) has one place more, row 0 one period up, and
// `returns` says whether each area comes back there to itself (its yarn then closes).
struct RowBlock {
    int first = 0, rows = 0;
    std::vector<Area> areas;  // the block's first row's
    std::vector<std::vector<Place>> places;
    bool closed = false, returns = true;
};
// The chart's blocks in row order: one closed block of every row when every row continues from
// the row below (vertical bands, a zigzag boundary: each yarn a closed serpentine), else starting
// at the lowest row whose areas do not continue from the row below's (cyclic).
std::vector<RowBlock> rowBlocks(const Chart& chart);

// How many times a chart whose every row continues into the next (one closed block) is stacked
// so each area's yarn closes: its serpentine needs an even number of rows (an odd chart is stacked
// twice), and areas that move round the period and arrive on another area of their colour (`B A B
// A` / `A B A B`) need the rows repeated until each comes back to itself. `wandering` says the
// latter set the count; `rows` is the stacked cell's height.
struct Closing {
    int times = 1, rows = 0;
    bool wandering = false;
};
Closing closing(const Chart& chart);

// The chart's rows repeated `times` times (cables copied).
Chart repeatRows(const Chart& chart, int times);

// One turn of a yarn at a colour boundary, in model units (yarn radius 0.8): from the foot
// `from` of its last loop in row g to the foot `to` of its first loop in row g + 1 (unwrapped).
// `boundary` is the boundary's x in row g, `boundaryAbove` in row g + 1 (a column over where the
// boundary steps), `side` where the yarn's own area lies (-1 left, +1 right).
struct Turn {
    glm::dvec3 from{0.0}, to{0.0};
    double boundary = 0, boundaryAbove = 0;
    int side = -1;
};
// The turn's vertices, `from` first, `to` excluded, about `spacing` apart: from the foot back
// behind the work, across the boundary to its far edge, up past the next row's foot, and back.
// Where the boundary steps, the far edge stays at each row's boundary over the band where it
// hooks through the neighbour's turn of that row and crosses over between the two (behind the
// stitches at the step: the yarn carried as many stitches on). `held` marks the points of
// a crossover two stitches long or longer: it lies on the back of the stitches it passes and is anchored
// there, as a knitter's carried yarn is held by them. Drawn tight as a free strand, it pulled
// those stitches together and folded one of them over. A crossover one stitch long stays free:
// held, the diamond's turns came unhooked from their neighbours' (issue 25 round 6,
// docs/charts.md "Diagonals").
// `crossover` marks the points of any crossover (the yarn carried behind the stitches at the step:
// a float, ChartFloat::carried).
struct TurnPoints {
    std::vector<glm::dvec3> points;
    std::vector<bool> held, crossover;
};
TurnPoints turnPoints(const Turn& turn, double spacing);

// The feet of the loops beside a boundary stop this far (model units) short of it.
constexpr double kBoundaryInset = 1.2;

// A motif yarn's tail (model units): from the foot `foot` of its first or last loop in a row whose
// loop centres lie at y = rowY, behind the work into its own area (inward: +1 to the right, -1 to
// the left) across `stitches` stitches' worth (1 or 2), ending clear of the area's far boundary.
// `alone`: the area is one stitch wide in that row (a motif one stitch wide, a diamond's tip); the
// tail then lies higher, behind the stitch's own legs just above the head of the loop below.
// The points run from the foot outwards, `foot` excluded, about `spacing` apart; a starting
// tail takes them in reverse order.
std::vector<glm::dvec3> tailPoints(const glm::dvec3& foot, double rowY, int inward, int stitches, bool alone,
                                   double spacing);

}  // namespace knit::intarsia
