// knit/chart_topology.hpp — from a stitch chart to an initial periodic yarn cell.
//
// One course (yarn) per chart row, running in +x and closing on itself through a periodic edge
// (dx = +1). Each stitch is one loop of that course; the loop (row, column) is pulled through the
// loop (row - 1, chart.sourceColumn(row, column)) of the course below (the row below of the
// previous tile for row 0).
//
// Over/under by construction, seen from the front (+z), for stitch (r, c) and the loop L of row
// r - 1 it is pulled through:
//   * knit (the new loop pulled through from the back to the front): where the legs of (r, c)
//     cross the head of L, course r passes in FRONT; where course r, at the base of (r, c),
//     crosses the legs of L, course r passes BEHIND;
//   * purl: the mirror image (z -> -z) of both.
// Cables: a cable token of row r moves the heads of the loops of row r - 1 to their new columns;
// their legs cross. The left-moving loops' legs pass in front for a front cross (`f`), behind for
// a back cross (`b`).
// Round 2 (docs/charts.md has the details):
//   * decreases: the loops a decrease consumes are stacked, their heads moved to its column, the
//     one on top (Chart::sources order) in front where their legs cross; the new loop's legs pass
//     in front of every head, its feet behind every leg;
//   * yo: a loop pulled through nothing (the loops below it lean into the decreases);
//   * sl / sl-wyif: the course makes no loop there but a float from foot to foot, behind (-z) /
//     in front (+z) of the slipped loop, whose upper part is lifted to the row above (it spans
//     two rows, or more when slipped again);
//   * tuck: the course makes a tuck loop that lies behind the held (lifted) loop without being
//     pulled through it; the next row's stitch is pulled through both, the held loop in front;
//   * ktbl / ptbl: the loop's two halves cross once at its base, above the head below, the strand
//     rising from the left foot (to the right leg) in front;
//   * stranded colourwork: one yarn per colour a row uses; a yarn makes the loops of its colour
//     and floats behind (-z) everywhere else, at the height of the course's lower half.
//   * intarsia: one yarn per colour area, knitted back and forth: a serpentine up the period that
//     turns at the area's boundaries behind the work, each turn hooked through the neighbouring
//     yarn's turns above and below (an odd-height chart is stacked twice, so the cell has an even
//     number of rows, areas that wander round the period until each comes back to itself); where a boundary moves a column between rows the turn is carried a stitch
//     on, hooking at each row's boundary; a motif's yarns are open, with tails (docs/charts.md).
//
// The loop shape in the plane is the plain-knit curve of generateStockinette (K. Crane's model),
// one stitch per 2 pi of the parameter; heights follow the rule above. The result is a starting
// point for relaxYarn (knit/relax.hpp), not a rest shape.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "knit/chart.hpp"
#include "knit/pattern.hpp"

namespace knit {

struct ChartCellOptions {
    double radius = 0.001;      // yarn radius (metres)
    int samplesPerStitch = 24;  // vertices per loop (>= 8)
};

// A loop this loop is pulled through: its row and column (a tuck's held loop lies rows below).
struct LoopRef {
    int row = 0, column = 0;
    bool operator==(const LoopRef& o) const { return row == o.row && column == o.column; }
};

// The vertices of one chart cell on the yarn that works it: course `row`, vertices
// [first, first + count) of the pattern: a loop, or for sl / sl-wyif the float of the course.
struct StitchLoop {
    int row = 0, column = 0;
    uint32_t first = 0, count = 0;
    StitchKind kind = StitchKind::Knit;
    StitchOp op = StitchOp::Plain;
    int yarn = 0;          // the yarn (edge chain) these vertices are on
    int sourceColumn = 0;  // the column of row - 1 this loop is pulled through (-1: a yarn-over)
    int headShift = 0;     // columns the head of this loop moves (to the stitch pulled through it)
    int lift = 0;          // rows its upper part is lifted (slipped or tucked above it)
    int stackIndex = 0;    // place among the loops one stitch is pulled through (0 = top / front)
    int stackSize = 1;
    bool madeLoop = true;   // false for sl / sl-wyif: the course floats past
    bool reversed = false;  // its vertices run right to left (intarsia's odd rows, knitted back)
    // The loops this loop is pulled through, top (front) first: none for yo, tuck and sl.
    std::vector<LoopRef> through;
};

// A float: a yarn passing columns without making a loop (stranded colourwork's other colours,
// and the course past slipped stitches), on the wrong side (-z) or, for sl-wyif, the right side.
struct ChartFloat {
    int row = 0;
    int firstColumn = 0, columns = 0;  // the columns it passes (cyclic over the chart's width)
    int yarn = 0;
    char colour = 0;        // palette letter (0 without a colour layer)
    bool front = false;     // sl-wyif
    bool stranded = false;  // it passes stitches of another yarn (stranded colourwork)
    bool carried = false;   // intarsia: an area's yarn carried up from the row below to where its boundary moved
    std::vector<uint32_t> vertices;  // its vertices, in yarn order
};

// How the cell's rows repeat the chart's: an intarsia chart whose every row continues into the
// next has its rows stacked until each area's yarn closes: twice when it has an odd number of rows
// (a serpentine turns on alternate rows), and, when its areas move round the period and arrive on
// another area of their colour (`B A B A` / `A B A B`, diagonals a column a row), until each area
// comes back to itself (`wandering`; docs/charts.md, "Diagonals").
struct ChartStacking {
    int times = 1;  // the cell's rows are the chart's this many times over
    int rows = 0;   // the cell's rows
    bool wandering = false;
};
ChartStacking chartStacking(const Chart& chart);
// The designer's note for a chart stacked because its areas wander ("" otherwise): the chart's
// repeat became N rows tall, and why.
std::string stackingWarning(const Chart& chart, const ChartStacking& stacking);
// Refuses (knit::Error naming the chart, the stacked rows x stitches, the yarn vertices they make
// at `samplesPerStitch` and `limit`, `why` the limit holds) a chart whose wandering areas stack it
// into a cell of more than `limit` yarn vertices (counting a loop per stitch), before it is built.
void checkStackedSize(const Chart& chart, const ChartStacking& stacking, int samplesPerStitch, uint64_t limit,
                      const std::string& why);

struct ChartCell {
    Pattern pattern;                             // points, twist 0, periodic edges (as in .pyp)
    int width = 0, height = 0;                   // stitches per period (the cell's size: rows stacked)
    ChartStacking stacking;                      // how the cell's rows repeat the chart's
    std::vector<StitchLoop> loops;               // row-major, row 0 first
    std::vector<std::array<uint8_t, 3>> colour;  // per loop sRGB; empty without a colour layer
    std::vector<ChartFloat> floats;              // every float (rows of the chart as written)
    int yarns = 0;  // yarns (one per row, more when stranded, one per area for intarsia, open for motifs)
    // Per vertex, for the edge leaving it: the yarn length it holds over its length here. 1,
    // except on loops lifted by slipped or tucked stitches (built stretched over two or more
    // rows, they hold a plain loop's length) — RelaxOptions::restScale.
    std::vector<double> restScale;
    // The vertices of each open yarn's two tails (an intarsia motif's), woven in behind the
    // work, and of the crossover of each intarsia turn carried two stitches on (a boundary
    // moving two columns), lying on the back of the stitches it passes — RelaxOptions::anchors.
    std::vector<uint32_t> anchors;

    const StitchLoop& loop(int row, int column) const { return loops[size_t(row) * size_t(width) + size_t(column)]; }
};

// A cell holds at most this many yarn vertices (a chart is one period: a few hundred stitches).
constexpr uint64_t kMaxChartVertices = uint64_t(1) << 22;

// Throws knit::Error for a non-positive radius, fewer than 8 samples per stitch or more than
// kMaxChartVertices vertices.
ChartCell chartToCell(const Chart& chart, const ChartCellOptions& options = {});

}  // namespace knit
