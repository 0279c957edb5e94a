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
//
// The loop shape in the plane is the plain-knit curve of generateStockinette (K. Crane's model),
// one stitch per 2 pi of the parameter; heights follow the rule above. The result is a starting
// point for relaxYarn (knit/relax.hpp), not a rest shape.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "knit/chart.hpp"
#include "knit/pattern.hpp"

namespace knit {

struct ChartCellOptions {
    double radius = 0.001;      // yarn radius (metres)
    int samplesPerStitch = 24;  // vertices per loop (>= 8)
};

// The vertices of one loop: course `row`, vertices [first, first + count) of the pattern.
struct StitchLoop {
    int row = 0, column = 0;
    uint32_t first = 0, count = 0;
    StitchKind kind = StitchKind::Knit;
    int sourceColumn = 0;  // the column of row - 1 this loop is pulled through
    int headShift = 0;     // columns the head of this loop moves (a cable of the row above)
};

struct ChartCell {
    Pattern pattern;                             // points, twist 0, periodic edges (as in .pyp)
    int width = 0, height = 0;                   // stitches per period (the chart's size)
    std::vector<StitchLoop> loops;               // row-major, row 0 first
    std::vector<std::array<uint8_t, 3>> colour;  // per loop sRGB; empty without a colour layer

    const StitchLoop& loop(int row, int column) const { return loops[size_t(row) * size_t(width) + size_t(column)]; }
};

// Throws knit::Error for a non-positive radius or fewer than 8 samples per stitch.
ChartCell chartToCell(const Chart& chart, const ChartCellOptions& options = {});

}  // namespace knit
