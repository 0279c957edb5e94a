// .pyp pattern reading/writing, validation, periodic adjacency and pattern statistics.
#include "knit/pattern.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>

#include "knit/error.hpp"
#include "util/checks.hpp"
#include "io/special_file.hpp"

namespace knit {
namespace {

struct Row {
    int line = 0;
    std::vector<std::string> tokens;
};
struct Block {
    std::string name;
    int line = 0;
    std::vector<Row> rows;
};

[[noreturn]] void fail(const std::string& source, int line, const std::string& what) {
    std::ostringstream msg;
    msg << source;
    if (line > 0) msg << ":" << line;
    msg << ": " << what;
    throw Error(msg.str());
}

double parseNumber(const std::string& token, const std::string& source, int line) {
    const char* begin = token.c_str();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || *end != '\0') fail(source, line, "'" + token + "' is not a number");
    if (!std::isfinite(value)) fail(source, line, "'" + token + "' is not a finite number");
    return value;
}

long parseInteger(const std::string& token, const std::string& source, int line) {
    const char* begin = token.c_str();
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(begin, &end, 10);
    if (end == begin || *end != '\0') fail(source, line, "'" + token + "' is not an integer");
    if (errno == ERANGE) fail(source, line, "integer '" + token + "' is out of range");
    return value;
}

// Splits the text into '*'-headed blocks of whitespace-separated rows; '#' starts a comment.
std::vector<Block> readBlocks(std::istream& in, const std::string& source) {
    std::vector<Block> blocks;
    std::string text;
    int lineNo = 0;
    while (std::getline(in, text)) {
        ++lineNo;
        if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
        std::istringstream tokens(text);
        std::vector<std::string> row;
        for (std::string t; tokens >> t;) row.push_back(t);
        if (row.empty()) continue;
        if (row[0][0] == '*') {
            std::string name = row[0].substr(1);
            if (name.empty()) fail(source, lineNo, "block header '*' without a name");
            for (const Block& b : blocks)
                if (b.name == name)
                    fail(source, lineNo,
                         "block *" + name + " appears twice (first at line " + std::to_string(b.line) + ")");
            blocks.push_back({name, lineNo, {}});
            continue;
        }
        if (blocks.empty()) fail(source, lineNo, "data before the first block header (expected '*pattern')");
        blocks.back().rows.push_back({lineNo, std::move(row)});
    }
    if (in.bad()) fail(source, 0, "read error");
    return blocks;
}

const Block* findBlock(const std::vector<Block>& blocks, const std::string& name) {
    for (const Block& b : blocks)
        if (b.name == name) return &b;
    return nullptr;
}

const Block& requireBlock(const std::vector<Block>& blocks, const std::string& name, const std::string& source) {
    const Block* b = findBlock(blocks, name);
    if (!b) fail(source, 0, "missing block *" + name);
    return *b;
}

void requireColumns(const Row& row, size_t n, const std::string& block, const std::string& source) {
    if (row.tokens.size() != n)
        fail(source, row.line,
             "*" + block + " row has " + std::to_string(row.tokens.size()) + " values, expected " + std::to_string(n));
}

// The *RGB block: one row "r g b" (linear, in [0, 1]) per vertex.
std::vector<glm::vec3> readColours(const Block& block, size_t n, const std::string& source) {
    if (block.rows.size() != n)
        fail(source, block.line,
             "*RGB has " + std::to_string(block.rows.size()) + " rows but *pattern declares " + std::to_string(n) +
                 " vertices");
    std::vector<glm::vec3> colour;
    colour.reserve(n);
    for (const Row& r : block.rows) {
        requireColumns(r, 3, "RGB", source);
        glm::vec3 c(0.f);
        for (int k = 0; k < 3; ++k) {
            const double v = parseNumber(r.tokens[size_t(k)], source, r.line);
            if (!(v >= 0.0 && v <= 1.0)) fail(source, r.line, "*RGB colour components must be in [0, 1]");
            c[k] = float(v);
        }
        colour.push_back(c);
    }
    return colour;
}

}  // namespace

Pattern parsePyp(std::istream& in, const std::string& source) {
    // A UTF-8 byte-order mark (editors on Windows add one) is skipped.
    char bom[3] = {};
    const std::streampos start = in.tellg();
    if (!(in.read(bom, 3) && bom[0] == '\xEF' && bom[1] == '\xBB' && bom[2] == '\xBF')) {
        in.clear();
        in.seekg(start);
    }
    const std::vector<Block> blocks = readBlocks(in, source);
    Pattern p;
    p.name = source;

    // *pattern: px py radius n
    const Block& header = requireBlock(blocks, "pattern", source);
    if (header.rows.size() != 1) fail(source, header.line, "*pattern must have exactly one row 'px py radius n'");
    const Row& h = header.rows[0];
    requireColumns(h, 4, "pattern", source);
    p.px = parseNumber(h.tokens[0], source, h.line);
    p.py = parseNumber(h.tokens[1], source, h.line);
    p.radius = parseNumber(h.tokens[2], source, h.line);
    const long n = parseInteger(h.tokens[3], source, h.line);
    if (!(p.px > 0) || !(p.py > 0)) fail(source, h.line, "period px, py must be positive");
    if (!(p.radius > 0)) fail(source, h.line, "yarn radius must be positive");
    if (n <= 0 || n > (1L << 26))
        fail(source, h.line, "vertex count " + std::to_string(n) + " is out of range (1 .. 2^26)");

    // *Q: n rows x y z t
    const Block& q = requireBlock(blocks, "Q", source);
    if (q.rows.size() != size_t(n))
        fail(source, q.line,
             "*Q has " + std::to_string(q.rows.size()) + " rows but *pattern declares " + std::to_string(n) +
                 " vertices");
    p.points.reserve(n);
    p.twist.reserve(n);
    for (const Row& r : q.rows) {
        requireColumns(r, 4, "Q", source);
        p.points.emplace_back(parseNumber(r.tokens[0], source, r.line), parseNumber(r.tokens[1], source, r.line),
                              parseNumber(r.tokens[2], source, r.line));
        p.twist.push_back(parseNumber(r.tokens[3], source, r.line));
    }

    // *E: v0 v1 dx dy
    const Block& e = requireBlock(blocks, "E", source);
    std::vector<int> edgeLines;
    for (const Row& r : e.rows) {
        requireColumns(r, 4, "E", source);
        const long v0 = parseInteger(r.tokens[0], source, r.line), v1 = parseInteger(r.tokens[1], source, r.line);
        const long dx = parseInteger(r.tokens[2], source, r.line), dy = parseInteger(r.tokens[3], source, r.line);
        if (v0 < 0 || v0 >= n || v1 < 0 || v1 >= n)
            fail(source, r.line,
                 "edge " + std::to_string(v0) + " -> " + std::to_string(v1) +
                     " references a missing vertex (the pattern has " + std::to_string(n) + ")");
        if (dx < -1 || dx > 1 || dy < -1 || dy > 1 || (dx != 0 && dy != 0))  // |dx|+|dy| > 1, overflow-free
            fail(source, r.line,
                 "edge offset (" + std::to_string(dx) + ", " + std::to_string(dy) + ") has |dx|+|dy| > 1");
        p.edges.push_back({uint32_t(v0), uint32_t(v1), int32_t(dx), int32_t(dy)});
        edgeLines.push_back(r.line);
    }

    // *GAUGE (optional): stitch columns and rows per period.
    if (const Block* g = findBlock(blocks, "GAUGE")) {
        if (g->rows.size() != 1) fail(source, g->line, "*GAUGE must have exactly one row 'stitches rows'");
        requireColumns(g->rows[0], 2, "GAUGE", source);
        const long stitches = parseInteger(g->rows[0].tokens[0], source, g->rows[0].line);
        const long rows = parseInteger(g->rows[0].tokens[1], source, g->rows[0].line);
        if (stitches < 1 || rows < 1 || stitches > 1000000 || rows > 1000000)
            fail(source, g->rows[0].line, "*GAUGE stitches and rows per period must be in 1 .. 1000000");
        p.stitchesPerPeriod = int(stitches);
        p.rowsPerPeriod = int(rows);
    }

    // *RGB (optional): linear yarn colour per vertex.
    if (const Block* c = findBlock(blocks, "RGB")) p.colour = readColours(*c, size_t(n), source);

    // Everything else: kept verbatim (numbers only).
    for (const Block& b : blocks) {
        if (b.name == "pattern" || b.name == "Q" || b.name == "E" || b.name == "GAUGE" || b.name == "RGB") continue;
        auto& rows = p.extraBlocks[b.name];
        for (const Row& r : b.rows) {
            std::vector<double> values;
            for (const std::string& t : r.tokens) values.push_back(parseNumber(t, source, r.line));
            rows.push_back(std::move(values));
        }
    }

    // Topology checks with line numbers (validatePattern repeats them without lines).
    std::vector<int> degree(n, 0);
    for (size_t i = 0; i < p.edges.size(); ++i) {
        const PeriodicEdge& ed = p.edges[i];
        if (ed.v0 == ed.v1 && ed.dx == 0 && ed.dy == 0)
            fail(source, edgeLines[i], "edge joins vertex " + std::to_string(ed.v0) + " to itself");
        for (const uint32_t v : {ed.v0, ed.v1})
            if (++degree[v] > 2)
                fail(source, edgeLines[i],
                     "vertex " + std::to_string(v) + " gets a third edge (yarn vertices have degree <= 2)");
    }
    validatePattern(p, source);
    return p;
}

Pattern loadPyp(const std::string& path) {
    impl::requireInputFile(path, "pattern file", ".pyp pattern file");
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open pattern file");
    return parsePyp(in, path);
}

void writePyp(std::ostream& out, const Pattern& p) {
    out << std::setprecision(17);
    out << "*pattern # px py radius num_vertedges\n"
        << p.px << ' ' << p.py << ' ' << p.radius << ' ' << p.points.size() << "\n\n";
    out << "*Q # dofs: x y z t\n";
    for (size_t i = 0; i < p.points.size(); ++i)
        out << p.points[i].x << ' ' << p.points[i].y << ' ' << p.points[i].z << ' '
            << (i < p.twist.size() ? p.twist[i] : 0.0) << '\n';
    out << "\n*E # edges: v0 v1 dx dy\n";
    for (const PeriodicEdge& e : p.edges) out << e.v0 << ' ' << e.v1 << ' ' << e.dx << ' ' << e.dy << '\n';
    if (p.stitchesPerPeriod != 1 || p.rowsPerPeriod != 1)
        out << "\n*GAUGE # stitches rows per period\n" << p.stitchesPerPeriod << ' ' << p.rowsPerPeriod << '\n';
    if (!p.colour.empty()) {
        out << "\n*RGB # linear yarn colour per vertex: r g b\n";
        for (const glm::vec3& c : p.colour) out << c.r << ' ' << c.g << ' ' << c.b << '\n';
    }
    for (const auto& [name, rows] : p.extraBlocks) {
        out << "\n*" << name << '\n';
        for (const auto& row : rows) {
            for (size_t i = 0; i < row.size(); ++i) out << (i ? " " : "") << row[i];
            out << '\n';
        }
    }
}

void validatePattern(const Pattern& p, const std::string& source) {
    auto bad = [&](const std::string& what) { throw Error(source + ": " + what); };
    if (!(util::positiveFinite(p.px) && util::positiveFinite(p.py))) bad("period must be positive and finite");
    if (!util::positiveFinite(p.radius)) bad("yarn radius must be positive and finite");
    if (p.points.empty()) bad("pattern has no vertices");
    if (p.twist.size() != p.points.size()) bad("twist count differs from vertex count");
    if (p.stitchesPerPeriod < 1 || p.rowsPerPeriod < 1) bad("stitches and rows per period must be at least 1");
    if (!p.colour.empty() && p.colour.size() != p.points.size()) bad("colour count differs from vertex count");
    for (const glm::vec3& c : p.colour)
        if (!(glm::all(glm::greaterThanEqual(c, glm::vec3(0.f))) && glm::all(glm::lessThanEqual(c, glm::vec3(1.f)))))
            bad("a vertex colour is outside [0, 1]");
    for (size_t i = 0; i < p.points.size(); ++i)
        if (!util::finite(p.points[i]) || !util::finite(p.twist[i]))
            bad("vertex " + std::to_string(i) + " has a non-finite coordinate");
    // Sizes far outside any knit (a yarn thicker than its stitch, a loop 1e17 m off the surface)
    // are refused here, naming the value: downstream they only showed as a memory estimate or a
    // search radius blamed on an option.
    const double period = std::max(p.px, p.py);
    if (p.radius > period) {
        std::ostringstream m;
        m << "the yarn radius " << p.radius << " m is larger than the period (" << p.px << " x " << p.py
          << " m): a yarn thicker than its stitches; check the units of the radius";
        bad(m.str());
    }
    constexpr double kMaxHeightPeriods = 16;
    for (size_t i = 0; i < p.points.size(); ++i)
        if (std::abs(p.points[i].z) > kMaxHeightPeriods * period) {
            std::ostringstream m;
            m << "vertex " << i << " lies " << p.points[i].z << " m off the mid-surface, "
              << std::abs(p.points[i].z) / period << " periods (a knit lies on its surface: at most "
              << kMaxHeightPeriods << " periods)";
            bad(m.str());
        }
    for (size_t i = 0; i < p.edges.size(); ++i) {
        const PeriodicEdge& e = p.edges[i];
        if (e.v0 >= p.points.size() || e.v1 >= p.points.size())
            bad("edge " + std::to_string(i) + " references a missing vertex");
        if (e.dx < -1 || e.dx > 1 || e.dy < -1 || e.dy > 1 || (e.dx != 0 && e.dy != 0))
            bad("edge " + std::to_string(i) + " has |dx|+|dy| > 1");
        if (e.v0 == e.v1 && e.dx == 0 && e.dy == 0)
            bad("edge " + std::to_string(i) + " joins vertex " + std::to_string(e.v0) + " to itself");
    }
    const PatternAdjacency adj = buildAdjacency(p);  // throws on degree > 2
    // The same undirected periodic edge twice would make a zero-length double edge.
    for (size_t v = 0; v < adj.slots.size(); ++v) {
        const auto& s = adj.slots[v];
        if (s[0].v >= 0 && s[0].v == s[1].v && s[0].dx == s[1].dx && s[0].dy == s[1].dy)
            bad("vertex " + std::to_string(v) + " is joined twice to vertex " + std::to_string(s[0].v) +
                " in the same tile");
    }
}

PatternAdjacency buildAdjacency(const Pattern& p) {
    PatternAdjacency adj;
    adj.slots.assign(p.points.size(), {});
    auto add = [&](uint32_t from, PatternNeighbor nb, size_t edge) {
        auto& s = adj.slots[from];
        if (s[0].v < 0) s[0] = nb;
        else if (s[1].v < 0) s[1] = nb;
        else
            throw Error(p.name + ": vertex " + std::to_string(from) + " has more than two edges (edge " +
                        std::to_string(edge) + "); yarn vertices have degree <= 2");
    };
    for (size_t i = 0; i < p.edges.size(); ++i) {
        const PeriodicEdge& e = p.edges[i];
        add(e.v0, {int32_t(e.v1), e.dx, e.dy}, i);
        add(e.v1, {int32_t(e.v0), -e.dx, -e.dy}, i);
    }
    return adj;
}

PatternInfo describePattern(const Pattern& p) {
    PatternInfo info;
    info.px = p.px;
    info.py = p.py;
    info.radius = p.radius;
    info.vertexCount = p.points.size();
    info.edgeCount = p.edges.size();
    for (const PeriodicEdge& e : p.edges) {
        if (e.dx > 0) ++info.crossings[0];
        if (e.dx < 0) ++info.crossings[1];
        if (e.dy > 0) ++info.crossings[2];
        if (e.dy < 0) ++info.crossings[3];
    }
    if (!p.points.empty()) {
        info.boundsMin = info.boundsMax = p.points[0];
        for (const glm::dvec3& q : p.points) {
            info.boundsMin = glm::min(info.boundsMin, q);
            info.boundsMax = glm::max(info.boundsMax, q);
        }
    }
    // 1x1 periodic tiling = the pattern graph with offsets ignored (the pattern on a torus):
    // a connected component is a closed loop when every vertex has two edges.
    const PatternAdjacency adj = buildAdjacency(p);
    std::vector<uint8_t> seen(p.points.size(), 0);
    std::vector<uint32_t> stack;
    for (uint32_t v = 0; v < p.points.size(); ++v) {
        if (seen[v]) continue;
        bool allDegreeTwo = true;
        stack.assign(1, v);
        seen[v] = 1;
        while (!stack.empty()) {
            const uint32_t c = stack.back();
            stack.pop_back();
            int degree = 0;
            for (const PatternNeighbor& nb : adj.slots[c]) {
                if (nb.v < 0) continue;
                ++degree;
                if (!seen[nb.v]) {
                    seen[nb.v] = 1;
                    stack.push_back(uint32_t(nb.v));
                }
            }
            allDegreeTwo = allDegreeTwo && degree == 2;
        }
        ++(allDegreeTwo ? info.loops1x1 : info.openYarns1x1);
    }
    return info;
}

}  // namespace knit
