// knit/chart.hpp — stitch charts: the knitter's text form of one periodic cell of fabric.
//
// Format (docs/charts.md has the full description):
//   * one chart row per line, the bottom row LAST (as knitting charts are read); the chart is one
//     period of the fabric and repeats in both directions;
//   * stitches separated by spaces: `k` knit, `p` purl, cables `cN/Mf` and `cN/Mb` (N, M in 1..3,
//     e.g. c1/1f c2/2b c3/3f): one token spanning its N + M stitches, all of them knit;
//   * a line whose first non-blank character is `#` is a comment; blank lines separate blocks;
//   * an optional second block of the same size gives a colour letter per stitch (`A`..`Z`,
//     `a`..`z`), with a palette line `A=#f2e8d5 B=#1d3557` (anywhere in the file).
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
    std::vector<ChartCable> cables;
    // Optional colour layer: one palette letter per stitch (same layout as `kind`); empty = none.
    std::vector<char> colour;
    std::map<char, std::array<uint8_t, 3>> palette;  // letter -> sRGB

    StitchKind at(int row, int column) const { return kind[size_t(row) * size_t(width) + size_t(column)]; }
    // The column of row - 1 whose loop the loop (row, column) is pulled through: the column
    // itself, or its source column when a cable of `row` reorders the stitches.
    int sourceColumn(int row, int column) const;
};

// Parses chart text. Errors are knit::Error "SOURCE:LINE:COLUMN: what" (1-based), for ragged rows,
// an unknown token, a cable over purl stitches (`cN/Mpf`, `cN/Mpb`), a cable wider than the chart,
// an empty chart, and a bad colour block or palette.
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
