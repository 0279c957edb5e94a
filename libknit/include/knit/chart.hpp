// knit/chart.hpp — stitch charts: the knitter's text form of one periodic cell of fabric.
//
// Format (docs/charts.md has the full description):
//   * one chart row per line, the bottom row LAST (as knitting charts are read); the chart is one
//     period of the fabric and repeats in both directions;
//   * stitches separated by spaces: `k` knit, `p` purl, cables `cN/Mf` and `cN/Mb` (N, M in 1..3,
//     e.g. c1/1f c2/2b c3/3f): one token spanning its N + M stitches, all of them knit; `yo`,
//     `k2tog`, `ssk`, `k3tog`, `sssk`, `cdd`, `sl`, `sl-wyif`, `tuck`, `ktbl`, `ptbl`: one column
//     each (the loop it makes), consuming 0 (yo), 2 (k2tog, ssk), 3 (k3tog, sssk, cdd) or 1 loop
//     of the row below; a row consumes exactly the loops the row below makes;
//   * a line whose first non-blank character is `#` is a comment; blank lines separate blocks;
//   * an optional second block of the same size gives a colour letter per stitch (`A`..`Z`,
//     `a`..`z`), with a palette line `A=#f2e8d5 B=#1d3557` (anywhere in the file); a line
//     holding just `stranded` or `intarsia` after the palette line says how the colours are
//     knitted (without it they are painted on one yarn per row).
// Conventions: the chart is seen from the front (right side, +z); column 0 is the leftmost token
// (x grows to the right), row 0 is the bottom row. A cable cN/M moves the N right-hand stitches of
// its span to the left over the M left-hand ones: `f` (front cross, a left cross) takes the
// left-moving stitches in front, `b` (back cross, a right cross) behind.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace knit {

enum class StitchKind : uint8_t { Knit, Purl };

// What a chart cell does besides its face (`StitchKind`): see docs/charts.md for each token.
enum class StitchOp : uint8_t {
    Plain,        // k, p
    Cable,        // one stitch of a cable token
    YarnOver,     // yo: a new loop through nothing (an eyelet)
    K2tog,        // through two loops at once, the left one on top
    Ssk,          // two loops, the right one on top
    K3tog,        // three loops, left on top
    Sssk,         // three loops, right on top
    Cdd,          // three loops, the centre on top, then the left, then the right
    Slip,         // sl: the loop below passed up unworked, the working yarn behind it (-z)
    SlipFront,    // sl-wyif: the same, the working yarn in front (+z)
    Tuck,         // the yarn laid behind the loop below (a tuck loop), the loop held
    ThroughBack,  // ktbl / ptbl: a loop twisted at its base
};

// How a colour layer is knitted.
enum class Colourwork : uint8_t {
    Painted,   // one yarn per row, each stitch painted its colour
    Stranded,  // one yarn per colour a row uses; the others float on the wrong side (-z)
    Intarsia,  // one yarn per colour area (bands, motifs, diagonals), knitted back and forth; neighbouring
               // areas' yarns interlock where they turn (docs/charts.md, "Intarsia")
};

// One cable token: row `row`, columns [column, column + left + right).
struct ChartCable {
    int row = 0, column = 0;
    int right = 0;      // N: the right-hand stitches, they move left by `left` columns
    int left = 0;       // M: the left-hand stitches, they move right by `right` columns
    bool front = true;  // the left-moving stitches pass in front
};

struct Chart {
    std::string name;              // file name or built-in name, for messages
    int width = 0, height = 0;     // stitches per row, rows
    std::vector<StitchKind> kind;  // width * height, row-major, row 0 = bottom row
    std::vector<StitchOp> op;      // the same layout
    std::vector<int> rowLine;      // the source line of each row, row 0 (the last line) first
    // The first loop of row - 1 (its column, 0..width-1) a cell consumes: loops are consumed left
    // to right, so a row's consumption is the running sum of its cells' loopsConsumed.
    std::vector<int> firstSource;
    std::vector<ChartCable> cables;
    // Optional colour layer: one palette letter per stitch (same layout as `kind`); empty = none.
    std::vector<char> colour;
    std::map<char, std::array<uint8_t, 3>> palette;  // letter -> sRGB
    Colourwork colourwork = Colourwork::Painted;     // Stranded / Intarsia need a colour layer

    StitchKind at(int row, int column) const { return kind[size_t(row) * size_t(width) + size_t(column)]; }
    StitchOp opAt(int row, int column) const { return op[size_t(row) * size_t(width) + size_t(column)]; }
    char colourAt(int row, int column) const { return colour[size_t(row) * size_t(width) + size_t(column)]; }
    // The columns of row - 1 whose loops the cell (row, column) consumes, the one on top (in
    // front) first: one for k, p, cables, sl, tuck, tbl; none for yo; two or three for decreases.
    std::vector<int> sources(int row, int column) const;
    // The first of sources(row, column) (the loop the stitch is pulled through; for a cable the
    // loop it moves), or -1 for a yarn-over.
    int sourceColumn(int row, int column) const;
};

// Loops of the row below a stitch token consumes (0 for yo, 2 for k2tog/ssk, 3 for
// k3tog/sssk/cdd, 1 otherwise; a cable's stitches 1 each).
int loopsConsumed(StitchOp op);
// Slipped and tucked stitches hold the loop below for the next row; a loop may be held on at
// most this many rows in a row (docs/charts.md: anchoring).
constexpr int kMaxHeldRows = 3;
// Stranded colourwork carries at most this many yarns along a row (Fair Isle uses two).
constexpr int kMaxStrandedColours = 4;

// Parses chart text. Errors are knit::Error "SOURCE:LINE:COLUMN: what" (1-based), for ragged rows,
// an unknown token, a cable over purl stitches (`cN/Mpf`, `cN/Mpb`), a cable wider than the chart,
// an empty chart, a bad colour block or palette, a row that does not consume the loops the row
// below makes (with both counts), and charts whose yarn would not hold together: a column of
// yarn-overs on every row, a loop slipped or tucked on every row or on more than kMaxHeldRows;
// for intarsia, an area that lasts one row (one row tall, or a boundary that jumps three or more
// columns), a single area, or a stitch beside a colour boundary that is not a knit-face loop
// (stripes that move round the period onto another area of their colour are built stacked:
// chartStacking in knit/chart_topology.hpp).
Chart parseChart(const std::string& text, const std::string& source);
Chart loadChart(const std::string& path);
// The text of a chart file, refused (knit::Error naming the path) when it does not exist, is a
// folder, a device or FIFO, or is larger than kMaxChartFileBytes.
constexpr uint64_t kMaxChartFileBytes = uint64_t(1) << 20;
std::string readChartText(const std::string& path);

// Built-in charts ("chart:stockinette", ...): names with the `chart:` prefix.
std::vector<std::string> builtinChartNames();
// The text of a built-in chart; throws knit::Error for an unknown name.
std::string builtinChartText(const std::string& name);
Chart builtinChart(const std::string& name);

}  // namespace knit
