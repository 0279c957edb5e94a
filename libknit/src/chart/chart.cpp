// Stitch chart parsing (text -> Chart) and the built-in charts.
#include "knit/chart.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "knit/error.hpp"
#include "chart_intarsia.hpp"
#include "io/special_file.hpp"

namespace knit {
namespace {

struct Token {
    std::string text;
    int column = 0;  // 1-based character column
};
struct Line {
    int number = 0;  // 1-based
    std::vector<Token> tokens;
};
using Block = std::vector<Line>;

[[noreturn]] void fail(const std::string& source, int line, int column, const std::string& what) {
    throw Error(source + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + what);
}

std::vector<Token> splitTokens(const std::string& text) {
    std::vector<Token> tokens;
    size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        const size_t start = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i > start) tokens.push_back({text.substr(start, i - start), int(start) + 1});
    }
    return tokens;
}

// The text's lines, sorted into data blocks (separated by blank lines) and palette lines
// (tokens containing '='); comment lines are dropped and do not separate blocks.
struct Layout {
    std::vector<Block> blocks;
    std::vector<Line> palette;
    std::vector<Line> colourwork;  // lines holding just `stranded` or `intarsia`
    int lastLine = 0;
};

Layout readLayout(const std::string& text) {
    Layout layout;
    std::istringstream in(text);
    bool blockOpen = false;
    for (std::string raw; std::getline(in, raw);) {
        Line line{++layout.lastLine, splitTokens(raw)};
        if (line.tokens.empty()) {
            blockOpen = false;
            continue;
        }
        if (line.tokens[0].text[0] == '#') continue;
        if (line.tokens[0].text.find('=') != std::string::npos) {
            layout.palette.push_back(std::move(line));
            continue;
        }
        if (line.tokens.size() == 1 && (line.tokens[0].text == "stranded" || line.tokens[0].text == "intarsia")) {
            layout.colourwork.push_back(std::move(line));
            continue;
        }
        if (!blockOpen) layout.blocks.emplace_back();
        blockOpen = true;
        layout.blocks.back().push_back(std::move(line));
    }
    return layout;
}

// One parsed stitch token: `span` columns (a cable when span > 1), each consuming loopsConsumed(op)
// loops of the row below (a cable's N + M stitches one each).
struct Stitch {
    StitchKind kind = StitchKind::Knit;
    StitchOp op = StitchOp::Plain;
    int span = 1, right = 0, left = 0;
    bool front = true;
};

const char* kKnownTokens =
    "expected k, p, yo, k2tog, ssk, k3tog, sssk, cdd, sl, sl-wyif, tuck, ktbl, ptbl or a cable c1/1f c1/1b c2/2f "
    "c2/2b c3/3f c3/3b";

// cN/M[p]{f,b}; returns false for anything else.
bool parseCable(const std::string& t, Stitch& s, bool& overPurl) {
    if (t.size() < 5 || t.size() > 6 || t[0] != 'c' || t[2] != '/') return false;
    if (t[1] < '1' || t[1] > '3' || t[3] < '1' || t[3] > '3') return false;
    overPurl = t.size() == 6;
    if (overPurl && t[4] != 'p') return false;
    const char cross = t.back();
    if (cross != 'f' && cross != 'b') return false;
    s.right = t[1] - '0';
    s.left = t[3] - '0';
    s.span = s.right + s.left;
    s.front = cross == 'f';
    s.op = StitchOp::Cable;
    return true;
}

struct NamedOp {
    const char* token;
    StitchOp op;
    StitchKind kind;
};
const NamedOp kOps[] = {
    {"k", StitchOp::Plain, StitchKind::Knit},          {"p", StitchOp::Plain, StitchKind::Purl},
    {"yo", StitchOp::YarnOver, StitchKind::Knit},      {"k2tog", StitchOp::K2tog, StitchKind::Knit},
    {"ssk", StitchOp::Ssk, StitchKind::Knit},          {"k3tog", StitchOp::K3tog, StitchKind::Knit},
    {"sssk", StitchOp::Sssk, StitchKind::Knit},        {"cdd", StitchOp::Cdd, StitchKind::Knit},
    {"sl", StitchOp::Slip, StitchKind::Knit},          {"sl-wyif", StitchOp::SlipFront, StitchKind::Knit},
    {"tuck", StitchOp::Tuck, StitchKind::Knit},        {"ktbl", StitchOp::ThroughBack, StitchKind::Knit},
    {"ptbl", StitchOp::ThroughBack, StitchKind::Purl},
};

Stitch parseStitch(const Token& token, const std::string& source, int line) {
    Stitch s;
    for (const NamedOp& n : kOps)
        if (token.text == n.token) {
            s.op = n.op;
            s.kind = n.kind;
            return s;
        }
    bool overPurl = false;
    if (!parseCable(token.text, s, overPurl))
        fail(source, line, token.column,
             "unknown stitch '" +
                 (token.text.size() > 40
                      ? token.text.substr(0, 40) + "...' (" + std::to_string(token.text.size()) + " characters; "
                      : token.text + "' (") +
                 kKnownTokens + ")");
    if (overPurl)
        fail(source, line, token.column,
             "cable '" + token.text + "' over purl stitches: the stitches a cable crosses are knit stitches");
    return s;
}

// A row must consume exactly the loops the row below makes (one per column, `width`): the first
// token where the running count goes over, or the last one when it falls short, is named.
void checkBalance(const std::vector<Stitch>& row, const Line& line, const std::string& source, int width) {
    int consumed = 0;
    size_t at = row.size() - 1;
    for (size_t k = 0; k < row.size(); ++k) {
        consumed += row[k].span * loopsConsumed(row[k].op);
        if (consumed > width && at == row.size() - 1) at = k;
    }
    if (consumed == width) return;
    fail(source, line.number, line.tokens[at].column,
         "row consumes " + std::to_string(consumed) + " loops but the row below makes " + std::to_string(width) +
             " (yo takes none, k2tog and ssk two, k3tog, sssk and cdd three, every other stitch one): pair each "
             "yo with a decrease");
}

// The stitch block: every row's stitches and cables, checked for width and balance. Returns the
// text column of each chart cell (its token's), row by row, bottom row first.
std::vector<std::vector<int>> readStitches(const Block& block, const std::string& source, Chart& chart) {
    std::vector<std::vector<int>> textColumns(block.size());
    chart.height = int(block.size());
    std::vector<std::vector<Stitch>> rows;
    for (const Line& line : block) {
        rows.emplace_back();
        for (const Token& t : line.tokens) rows.back().push_back(parseStitch(t, source, line.number));
    }
    auto count = [](const std::vector<Stitch>& row) {
        int n = 0;
        for (const Stitch& s : row) n += s.span;
        return n;
    };
    chart.width = count(rows[0]);
    const size_t cells = size_t(chart.width) * size_t(chart.height);
    chart.kind.assign(cells, StitchKind::Knit);
    chart.op.assign(cells, StitchOp::Plain);
    chart.firstSource.assign(cells, 0);
    chart.rowLine.assign(size_t(chart.height), 0);
    for (size_t i = 0; i < rows.size(); ++i) {
        const Line& line = block[i];
        const int row = chart.height - 1 - int(i);  // the bottom row is the last line
        chart.rowLine[size_t(row)] = line.number;
        int column = 0, consumed = 0;
        for (size_t k = 0; k < rows[i].size(); ++k) {
            const Stitch& s = rows[i][k];
            if (s.span > chart.width)
                fail(source, line.number, line.tokens[k].column,
                     "cable '" + line.tokens[k].text + "' spans " + std::to_string(s.span) +
                         " stitches but the chart is " + std::to_string(chart.width) + " wide");
            if (s.span > 1) chart.cables.push_back({row, column, s.right, s.left, s.front});
            for (int j = 0; j < s.span && column + j < chart.width; ++j) {
                const size_t cell = size_t(row) * size_t(chart.width) + size_t(column + j);
                chart.kind[cell] = s.kind;
                chart.op[cell] = s.op;
                chart.firstSource[cell] = std::min(consumed, chart.width - 1);
                consumed += loopsConsumed(s.op);
                textColumns[size_t(row)].push_back(line.tokens[k].column);
            }
            column += s.span;
        }
        if (column != chart.width)
            fail(source, line.number, line.tokens.back().column,
                 "row has " + std::to_string(column) + " stitches, expected " + std::to_string(chart.width) +
                     " (as the first row, line " + std::to_string(block[0].number) + ")");
        checkBalance(rows[i], line, source, chart.width);
    }
    return textColumns;
}

// Step 3 of parsing: charts whose yarn would not hold together. A column that is a yarn-over on
// every row hangs on nothing below; a loop slipped or tucked on every row is never worked, and
// one held over more than kMaxHeldRows rows makes a float and an elongated loop that do not hold.
void checkAnchors(const Chart& chart, const Block& block, const std::vector<std::vector<int>>& textColumns,
                  const std::string& source) {
    auto lineOf = [&](int row) { return block[size_t(chart.height - 1 - row)].number; };
    auto where = [&](int row, int column) { return textColumns[size_t(row)][size_t(column)]; };
    for (int c = 0; c < chart.width; ++c) {
        bool allYo = true;
        for (int r = 0; r < chart.height && allYo; ++r) allYo = chart.opAt(r, c) == StitchOp::YarnOver;
        if (allYo)
            fail(source, lineOf(0), where(0, c),
                 "column " + std::to_string(c + 1) +
                     " is a yarn-over on every row: its loops hang on nothing below, so the fabric splits "
                     "into a ladder there (work it as a stitch on at least one row)");
    }
    auto held = [](StitchOp op) { return op == StitchOp::Slip || op == StitchOp::SlipFront || op == StitchOp::Tuck; };
    for (int r = 0; r < chart.height; ++r)
        for (int c = 0; c < chart.width; ++c) {
            // Follow the loop down while it is passed up unworked.
            int rows = 0, rr = r, cc = c;
            while (held(chart.opAt(rr, cc)) && rows <= chart.height) {
                cc = chart.sourceColumn(rr, cc);
                rr = (rr + chart.height - 1) % chart.height;
                ++rows;
            }
            if (rows > chart.height)
                fail(source, lineOf(r), where(r, c),
                     "the loop in column " + std::to_string(c + 1) +
                         " is slipped or tucked on every row: it is never worked, so the rows are not held "
                         "together there");
            if (rows > kMaxHeldRows)
                fail(source, lineOf(r), where(r, c),
                     "the loop in column " + std::to_string(c + 1) + " is slipped or tucked on " +
                         std::to_string(rows) + " rows in a row (at most " + std::to_string(kMaxHeldRows) +
                         "): work it on a row in between");
        }
}

int hexDigit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// Palette lines: `A=#rrggbb` entries.
void readPalette(const std::vector<Line>& lines, const std::string& source, Chart& chart) {
    for (const Line& line : lines)
        for (const Token& t : line.tokens) {
            const std::string& s = t.text;
            bool ok = s.size() == 9 && std::isalpha(static_cast<unsigned char>(s[0])) && s[1] == '=' && s[2] == '#';
            std::array<uint8_t, 3> rgb{};
            for (int c = 0; ok && c < 3; ++c) {
                const int hi = hexDigit(s[3 + 2 * c]), lo = hexDigit(s[4 + 2 * c]);
                ok = hi >= 0 && lo >= 0;
                rgb[size_t(c)] = uint8_t(hi * 16 + lo);
            }
            if (!ok) fail(source, line.number, t.column, "palette entry '" + s + "' is not LETTER=#rrggbb");
            if (chart.palette.count(s[0]))
                fail(source, line.number, t.column, "colour '" + s.substr(0, 1) + "' is defined twice");
            chart.palette[s[0]] = rgb;
        }
}

// The colour block: one palette letter per stitch, the same size as the stitch block.
void readColours(const Block& block, const std::string& source, Chart& chart) {
    if (int(block.size()) != chart.height)
        fail(source, block[0].number, 1,
             "colour block has " + std::to_string(block.size()) + " rows, expected " + std::to_string(chart.height) +
                 " (as the stitch block)");
    chart.colour.assign(chart.kind.size(), 0);
    for (size_t i = 0; i < block.size(); ++i) {
        const Line& line = block[i];
        if (int(line.tokens.size()) != chart.width)
            fail(source, line.number, line.tokens.back().column,
                 "colour row has " + std::to_string(line.tokens.size()) + " letters, expected " +
                     std::to_string(chart.width));
        const int row = chart.height - 1 - int(i);
        for (int c = 0; c < chart.width; ++c) {
            const Token& t = line.tokens[size_t(c)];
            if (t.text.size() != 1 || !std::isalpha(static_cast<unsigned char>(t.text[0])))
                fail(source, line.number, t.column, "colour '" + t.text + "' is not one letter");
            if (!chart.palette.count(t.text[0]))
                fail(source, line.number, t.column, "colour '" + t.text + "' is not in the palette");
            chart.colour[size_t(row) * size_t(chart.width) + size_t(c)] = t.text[0];
        }
    }
}

// "column 3" / "columns 3-5" (from 1 at the left).
std::string columnSpan(int lo, int count) {
    return count == 1 ? "column " + std::to_string(lo + 1)
                      : "columns " + std::to_string(lo + 1) + "-" + std::to_string(lo + count);
}

// Two rows whose areas would continue but for a boundary that could move either way round the
// period, refused at the upper row's line, where the boundary lies in the row below.
[[noreturn]] void refuseTie(const std::string& source, const Chart& chart, const Block& colours,
                            const intarsia::Tie& tie) {
    const int w = chart.width, column = ((tie.column % w) + w) % w, below = (tie.row + chart.height - 1) % chart.height;
    const Line& line = colours[size_t(chart.height - 1 - tie.row)];
    const std::string n = std::to_string(tie.columns);
    fail(source, line.number, line.tokens[size_t(column)].column,
         "intarsia: the colour boundary left of column " + std::to_string(column + 1) + " in row " +
             std::to_string(below + 1) + " moves " + n + " columns into row " + std::to_string(tie.row + 1) +
             ", and on this " + std::to_string(w) + "-stitch repeat " + n +
             " columns to the right and to the left land on the same place: which way the area's yarn is carried "
             "behind the work is not drawn. Move the boundary by fewer than " +
             n + " columns between the two rows (draw the steps between), widen the repeat, or knit it `stranded`");
}

// A block of rows with several colour areas that lasts one row only (an area that starts and
// ends in the same row: a motif one row tall, or a boundary whose move is a tie), refused naming
// the tie or its smallest area where the colour block draws it (rows from 1 at the bottom,
// columns from 1 at the left).
[[noreturn]] void refuseOneRowBlock(const std::string& source, const Chart& chart, const Block& colours,
                                    const intarsia::RowBlock& block) {
    for (const int row : {block.first + 1, block.first})
        if (const std::optional<intarsia::Tie> tie = intarsia::tiedMove(chart, row))
            refuseTie(source, chart, colours, *tie);
    const intarsia::Area* small = &block.areas.front();
    for (const intarsia::Area& a : block.areas)
        if (a.count < small->count) small = &a;
    const Line& line = colours[size_t(chart.height - 1 - block.first)];
    fail(source, line.number, line.tokens[size_t(small->first)].column,
         "intarsia: the colour " + std::string(1, small->colour) + " area in row " + std::to_string(block.first + 1) +
             ", " + columnSpan(small->first, small->count) +
             " lasts one row: the areas of the rows below and above do not continue into it (an area one row "
             "tall: it starts and ends in this row), so its yarn would knit one row with "
             "no row above or below to turn into round its neighbours' yarns and would hang by its two "
             "tails. Make the area at least two rows tall, or knit it `stranded`");
}

// Intarsia in a periodic cell (chart_intarsia.hpp): at least one row with two colour areas; the
// rows whose areas continue (the same areas, boundaries moving the shorter way round) form blocks,
// each of several areas at least two rows tall (the areas' yarns turn round each other), unless
// every row continues into the next (closed yarns; areas that wander round the period onto another
// of their colour are stacked by chartToCell until each comes back to itself); the stitches either
// side of a boundary are knit-face loops the turns and tails can leave from behind.
void checkIntarsia(const std::string& source, const Chart& chart, const Block& colours) {
    const int w = chart.width;
    const std::vector<intarsia::RowBlock> blocks = intarsia::rowBlocks(chart);
    bool several = false;
    for (const intarsia::RowBlock& b : blocks) several = several || b.areas.size() > 1;
    if (!several)
        fail(source, chart.rowLine[0], 1,
             "intarsia needs at least two colour areas along a row (this chart has one colour in every row)");
    if (!blocks.front().closed)
        for (const intarsia::RowBlock& b : blocks)
            if (b.areas.size() > 1 && b.rows < 2) refuseOneRowBlock(source, chart, colours, b);
    for (int r = 0; r < chart.height; ++r)
        for (int c = 0; c < w; ++c) {
            const bool edge = chart.colourAt(r, c) != chart.colourAt(r, (c + 1) % w) ||
                              chart.colourAt(r, c) != chart.colourAt(r, (c + w - 1) % w);
            const StitchOp op = chart.opAt(r, c);
            if (edge && (chart.at(r, c) != StitchKind::Knit || op == StitchOp::Slip || op == StitchOp::SlipFront ||
                         op == StitchOp::Tuck))
                fail(source, chart.rowLine[size_t(r)], 1,
                     "intarsia: the stitch in column " + std::to_string(c + 1) +
                         " lies beside a colour boundary and must be a knit-face loop (k, ktbl, a decrease, yo or a "
                         "cable), not purl, slipped or tucked: the yarns turn there behind the work");
        }
}

// A line holding just `stranded` or `intarsia`, after the palette line, once, with a colour block.
void readColourwork(const Layout& layout, const std::string& source, Chart& chart) {
    if (layout.colourwork.empty()) return;
    const Line& line = layout.colourwork.front();
    const std::string& word = line.tokens[0].text;
    if (layout.colourwork.size() > 1)
        fail(source, layout.colourwork[1].number, 1,
             "a second colourwork line (the first is line " + std::to_string(line.number) + ")");
    if (chart.colour.empty())
        fail(source, line.number, 1,
             "'" + word + "' needs a colour block and a palette: it says how their colours are knitted");
    if (line.number < layout.palette.back().number)
        fail(source, line.number, 1,
             "'" + word + "' goes after the palette line (line " + std::to_string(layout.palette.back().number) + ")");
    chart.colourwork = word == "stranded" ? Colourwork::Stranded : Colourwork::Intarsia;
    // Stranded: each colour of a row is a yarn carried along the whole row.
    if (chart.colourwork == Colourwork::Stranded)
        for (int r = 0; r < chart.height; ++r) {
            std::string used;
            for (int c = 0; c < chart.width; ++c)
                if (used.find(chart.colourAt(r, c)) == std::string::npos) used += chart.colourAt(r, c);
            if (int(used.size()) > kMaxStrandedColours)
                fail(source, chart.rowLine[size_t(r)], 1,
                     "row uses " + std::to_string(used.size()) + " colours (" + used +
                         "); stranded colourwork carries "
                         "at most " +
                         std::to_string(kMaxStrandedColours) + " yarns along a row");
        }
    if (chart.colourwork == Colourwork::Intarsia) checkIntarsia(source, chart, layout.blocks[1]);
}

}  // namespace

int loopsConsumed(StitchOp op) {
    switch (op) {
        case StitchOp::YarnOver: return 0;
        case StitchOp::K2tog:
        case StitchOp::Ssk: return 2;
        case StitchOp::K3tog:
        case StitchOp::Sssk:
        case StitchOp::Cdd: return 3;
        default: return 1;
    }
}

std::vector<int> Chart::sources(int row, int column) const {
    const int s = firstSource[size_t(row) * size_t(width) + size_t(column)];
    switch (opAt(row, column)) {
        case StitchOp::YarnOver: return {};
        case StitchOp::K2tog: return {s, s + 1};
        case StitchOp::Ssk: return {s + 1, s};
        case StitchOp::K3tog: return {s, s + 1, s + 2};
        case StitchOp::Sssk: return {s + 2, s + 1, s};
        case StitchOp::Cdd: return {s + 1, s, s + 2};
        case StitchOp::Cable:
            for (const ChartCable& c : cables) {
                if (c.row != row || column < c.column || column >= c.column + c.left + c.right) continue;
                const int j = column - c.column;
                const int start = firstSource[size_t(row) * size_t(width) + size_t(c.column)];
                // Positions [0, right) receive the right-hand stitches, [right, span) the left-hand ones.
                return {start + (j < c.right ? j + c.left : j - c.right)};
            }
            return {s};
        default: return {s};
    }
}

int Chart::sourceColumn(int row, int column) const {
    const std::vector<int> s = sources(row, column);
    return s.empty() ? -1 : s.front();
}

Chart parseChart(const std::string& text, const std::string& source) {
    const Layout layout = readLayout(text);
    Chart chart;
    chart.name = source;
    // Step 1: the stitch block (required).
    if (layout.blocks.empty())
        fail(source, layout.lastLine > 0 ? layout.lastLine : 1, 1, "empty chart: no stitch rows");
    const std::vector<std::vector<int>> textColumns = readStitches(layout.blocks[0], source, chart);
    checkAnchors(chart, layout.blocks[0], textColumns, source);
    // Step 2: the optional palette and colour block.
    readPalette(layout.palette, source, chart);
    if (layout.blocks.size() > 2)
        fail(source, layout.blocks[2][0].number, 1, "a chart has at most two blocks (stitches, then colours)");
    if (layout.blocks.size() == 2) readColours(layout.blocks[1], source, chart);
    // Step 3: how the colours are knitted.
    readColourwork(layout, source, chart);
    return chart;
}

std::string readChartText(const std::string& path) {
    // Step 1: what the path names (a FIFO or a device would block or never end), and its size
    // before reading it whole (a chart is one period: a few hundred stitches).
    const uint64_t bytes = impl::requireInputFile(path, "chart file", "chart file");
    if (bytes > kMaxChartFileBytes)
        throw Error(path + ": a chart file holds at most " + std::to_string(kMaxChartFileBytes >> 20) +
                    " MiB of text; this one has " + std::to_string(bytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open chart file");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

Chart loadChart(const std::string& path) { return parseChart(readChartText(path), path); }

namespace {

struct BuiltinChart {
    const char* name;
    const char* text;
};

// Each one period of the fabric, the bottom row last.
const BuiltinChart kBuiltinCharts[] = {
    {"chart:stockinette", "k k\nk k\n"},
    {"chart:reverse-stockinette", "p p\np p\n"},
    {"chart:garter", "# two-row period: a knit row, then a purl row\np p\nk k\n"},
    {"chart:rib1x1", "k p\nk p\n"},
    {"chart:rib2x2", "k k p p\nk k p p\n"},
    {"chart:seed", "p k\nk p\n"},
    {"chart:moss", "p k\np k\nk p\nk p\n"},
    {"chart:basketweave", "p p k k\np p k k\nk k p p\nk k p p\n"},
    {"chart:cable4", "# a 2/2 front cable between purl ridges\np k k k k p\np k k k k p\np k k k k p\np c2/2f p\n"},
    {"chart:eyelet-mesh",
     "# lace: an eyelet every other row, offset by half the repeat\nk k k k\nk k k2tog yo\nk k k k\n"
     "k2tog yo k k\n"},
    {"chart:honeycomb", "# slip-stitch honeycomb: each slipped stitch held for two rows\nsl k\nsl k\nk sl\nk sl\n"},
    {"chart:fishermans-rib", "# fisherman's rib: knit and purl columns tucked on alternate rows\nk tuck\ntuck p\n"},
    {"chart:fair-isle",
     "# a two-colour stranded band: checks between plain rows\nk k k k\nk k k k\nk k k k\nk k k k\n\n"
     "A A A A\nA B A B\nB A B A\nA A A A\nA=#f2e8d5 B=#1d3557\nstranded\n"},
    {"chart:intarsia-blocks",
     "# intarsia: two colour blocks side by side, each knitted back and forth with its own yarn,\n"
     "# the two yarns interlocked where the blocks meet\nk k k k\nk k k k\n\n"
     "A A B B\nA A B B\nA=#f2e8d5 B=#c1121f\nintarsia\n"},
    {"chart:intarsia-motif",
     "# intarsia: a motif one stitch wide and three rows tall on a plain background; the motif and the\n"
     "# background beside it each knitted back and forth with their own yarn (tails woven in behind),\n"
     "# interlocked where they meet; the rows above and below in the background's yarn\n"
     "k k k\nk k k\nk k k\nk k k\nk k k\n\nA A A\nA B A\nA B A\nA B A\nA A A\nA=#f2e8d5 B=#c1121f\nintarsia\n"},
    {"chart:intarsia-diamond",
     "# intarsia: a diamond on a plain background; each boundary moves a column every row, the\n"
     "# diamond's and the background's yarns carried one stitch on at each step and interlocked\n"
     "k k k k k\nk k k k k\nk k k k k\nk k k k k\nk k k k k\n\n"
     "A A A A A\nA A B A A\nA B B B A\nA A B A A\nA A A A A\nA=#f2e8d5 B=#c1121f\nintarsia\n"},
};

}  // namespace

std::vector<std::string> builtinChartNames() {
    std::vector<std::string> names;
    for (const BuiltinChart& c : kBuiltinCharts) names.push_back(c.name);
    return names;
}

std::string builtinChartText(const std::string& name) {
    std::string known;
    for (const BuiltinChart& c : kBuiltinCharts) {
        if (name == c.name) return c.text;
        known += (known.empty() ? "" : ", ") + std::string(c.name);
    }
    throw Error("unknown chart '" + name + "' (built-in charts: " + known + ")");
}

Chart builtinChart(const std::string& name) { return parseChart(builtinChartText(name), name); }

}  // namespace knit
