// mesh_off.cpp — the OFF reader (ASCII; texture coordinates need the "ST" header prefix:
// STOFF, x y z u v per vertex).
//
// One pass over the text, line by line (scanOff says what is checked); libknit used OpenMesh's
// reader before, which knows no '#' comments, trusts counts and corner counts and returns
// success on garbage, on a copy cleaned by that pass. Positions and UVs are float32, as there.
#include "mesh_reader.hpp"

#include "knit/error.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace knit::impl {
namespace {

// A count read as a double (an OFF header may declare 1e38 vertices), as text: casting it to
// size_t first is undefined beyond 2^64 (UBSan; tests/fuzz_corpus/off/crash-03931b42...).
std::string countText(double count) {
    std::ostringstream s;
    s << std::setprecision(16) << count;  // exact up to 2^53, "1e+38" beyond
    return s.str();
}

// The header options as OpenMesh 9.0's OFF reader (which libknit used before) took them from the
// start of the first line, "[ST][C][N]OFF": texture coordinates, colours, normals per vertex;
// "4OFF" / "nOFF" (other dimensions) and any other start are not OFF to it.
struct OffHeader {
    bool valid = false, texcoords = false, colours = false, normals = false;
};
OffHeader offHeader(const std::string& line) {
    OffHeader h;
    size_t p = 0;
    auto at = [&](const char* s) { return line.compare(p, std::strlen(s), s) == 0; };
    if (at("ST")) h.texcoords = true, p += 2;
    if (at("C")) h.colours = true, ++p;
    if (at("N")) h.normals = true, ++p;
    h.valid = at("OFF");
    return h;
}

// Whitespace-separated words of a line with where each ends (as >> reads them).
void splitWords(const std::string& text, std::vector<std::string>& words, std::vector<size_t>& ends) {
    words.clear();
    ends.clear();
    size_t i = 0;
    while (true) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i == text.size()) return;
        const size_t b = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        words.push_back(text.substr(b, i - b));
        ends.push_back(i);
    }
}

// [+-]digits within [-limit, limit]: what `>> int` / `>> unsigned` reads whole.
bool plainInteger(const std::string& w, double limit) {
    const size_t s = !w.empty() && (w[0] == '+' || w[0] == '-') ? 1 : 0;
    if (w.size() == s || w.find_first_not_of("0123456789", s) != std::string::npos) return false;
    return std::abs(std::strtod(w.c_str(), nullptr)) <= limit;
}

// The colour words before a vertex's texture coordinates in a "C" file, counted as OFF writers
// lay them out (and as OpenMesh counted them: items separated by ' ' after the position, minus
// the two texture coordinates; 3 or 4 are integers unless the first has a '.'): 0 to 4.
size_t colourWords(const std::string& restOfLine, bool& integers) {
    integers = false;
    if (restOfLine.empty()) return 0;
    const std::string t = trimmed(restOfLine);
    int count = t.empty() ? 0 : int(std::count(t.begin(), t.end(), ' ')) + 1;
    count -= 2;
    if (count == 3 || count == 4) {
        integers = t.substr(0, t.find(' ')).find('.') == std::string::npos;
        return size_t(count);
    }
    if (count == 5) return 3;
    if (count == 6) return 4;
    return count == 1 || count == 2 ? size_t(count) : 0;
}

// ASCII OFF, read line-based as OFF writers write it: the counts line holds exactly "vertices
// faces edges", then one vertex per line ("x y z [nx ny nz] [colour] [u v]" as the header says),
// then one face per line ("k i1 .. ik [colour]", 0 <= i < vertices); '#' starts a comment.
// Every number must be finite (and within float32), counts and indices integers, so what other
// readers would accept silently (garbage counts, unchecked corner counts, a truncated file) is
// refused naming the line. Positions and texture coordinates are stored as float32 (read as
// float, as OpenMesh's reader, which libknit used before, read them). Binary OFF is rejected.
struct OffData {
    std::vector<glm::dvec3> points;
    std::vector<glm::dvec2> uvs;
    Polygons polys;
    std::vector<size_t> faceLines;
    OffHeader header;
    // The first problem only the texture coordinates' layout has (a hexadecimal number, a count
    // or colour that is not a plain integer, a vertex line too short for its layout): reported
    // after the checks every OFF file gets, as "path:line: what".
    std::string layoutProblem;
};

OffData scanOff(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) failMesh(path, "cannot open for reading");
    OffData d;
    std::string line, keyword;
    std::getline(in, line);
    d.header = offHeader(line);
    const bool wantUv = d.header.valid && d.header.texcoords;
    std::istringstream header(line.substr(0, line.find('#')));
    header >> keyword;
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
        failMeshLine(path, 1, "not an OFF file (the first line must start with a header such as OFF or STOFF)");
    std::string rest;
    std::getline(header, rest);
    if (trimmed(rest).rfind("BINARY", 0) == 0)
        failMesh(path, "binary OFF is not supported (use ASCII OFF, PLY or OBJ)");
    size_t dataLine = 0;  // 0: counts, then vertices, then faces
    double nv = 0, nf = 0;
    std::vector<double> values;
    std::vector<std::string> words;
    std::vector<size_t> ends;
    auto layout = [&](size_t lineNo, const std::string& what) {
        if (d.layoutProblem.empty()) d.layoutProblem = path + ":" + std::to_string(lineNo) + ": " + what;
    };
    auto take = [&](const std::string& text, size_t lineNo) {
        values.clear();
        splitWords(text, words, ends);
        double v;
        for (const std::string& w : words) {
            if (!parseFinite(w, v)) failMeshLine(path, lineNo, "'" + w + "' is not a finite number");
            if (isHexNumber(w)) layout(lineNo, "'" + w + "' is not a finite number");
            requireFloatRange(path, lineNo, w, v);
            values.push_back(v);
        }
        if (values.empty()) return;
        if (dataLine == 0) {
            const std::string counts = "expected the counts 'vertices faces edges' (3 non-negative integers)";
            if (values.size() != 3 || values[0] < 0 || values[1] < 0 || values[0] != std::floor(values[0]) ||
                values[1] != std::floor(values[1]))
                failMeshLine(path, lineNo, counts);
            for (const std::string& w : words)
                if (!plainInteger(w, 4294967295.0)) layout(lineNo, counts);
            nv = values[0], nf = values[1];
        } else if (double(dataLine) <= nv) {
            const size_t position = wantUv && d.header.normals ? 6 : 3;  // x y z [nx ny nz]
            if (values.size() < 3) failMeshLine(path, lineNo, "a vertex line needs at least 3 numbers");
            auto f32 = [&](size_t i) {
                return i < words.size() ? double(std::strtof(words[i].c_str(), nullptr)) : 0.0;
            };
            d.points.emplace_back(f32(0), f32(1), f32(2));
            if (wantUv && values.size() < position)
                layout(lineNo, "a vertex line needs at least " + std::to_string(position) + " numbers");
            else if (wantUv) {
                bool integers = false;
                const size_t colour = d.header.colours ? colourWords(text.substr(ends[position - 1]), integers) : 0;
                if (values.size() < position + colour + 2)
                    layout(lineNo,
                           "a vertex line needs at least " + std::to_string(position + colour + 2) + " numbers");
                for (size_t i = position; integers && i < position + colour && i < words.size(); ++i)
                    if (!plainInteger(words[i], 2147483647.0))
                        layout(lineNo, "'" + words[i] + "' is not an integer colour component");
                d.uvs.emplace_back(f32(position + colour), f32(position + colour + 1));
            }
        } else if (double(dataLine) <= nv + nf) {
            const double k = values[0];
            if (k < 3 || k != std::floor(k) || k > double(values.size() - 1))
                failMeshLine(path, lineNo, "a face line must be 'k i1 .. ik' with k >= 3 vertex indices");
            for (size_t i = 1; i <= size_t(k); ++i)
                if (values[i] < 0 || values[i] >= nv || values[i] != std::floor(values[i]))
                    failMeshLine(path, lineNo,
                                 "face references vertex " + std::to_string(values[i]) + " but the file has " +
                                     countText(nv) + " vertices");
            // A face colour after the indices (integer or float RGB[A], valid OFF) is ignored:
            // libknit does not use colours.
            for (size_t i = 1; i <= size_t(k); ++i) d.polys.faceVerts.push_back(int(values[i]));
            d.polys.faceStart.push_back(uint32_t(d.polys.faceVerts.size()));
            d.faceLines.push_back(lineNo);
        }
        ++dataLine;
    };
    take(rest, 1);
    for (size_t lineNo = 2; std::getline(in, line); ++lineNo) take(line.substr(0, line.find('#')), lineNo);
    if (dataLine == 0) failMesh(path, "OFF header has no 'vertices faces edges' counts");
    if (double(dataLine) < 1 + nv + nf)
        failMesh(path, "declares " + countText(nv) + " vertices and " + countText(nf) + " faces but holds only " +
                           std::to_string(dataLine - 1) + " data lines (truncated?)");
    if (nf == 0) failMesh(path, "the mesh has no faces");
    return d;
}

}  // namespace

BaseMesh readOffMesh(const std::string& path, const MeshLoadOptions& options) {
    const OffData d = scanOff(path);
    if (!d.header.valid)
        failMeshLine(path, 1, "not an OFF file (the first line must start with a header such as OFF or STOFF)");
    if (!d.header.texcoords)
        failMesh(path, "no texture coordinates (an STOFF header with x y z u v per vertex); libknit needs UVs");
    if (!d.layoutProblem.empty()) throw Error(d.layoutProblem);
    return buildPolygonMesh(path, d.polys, d.points, d.uvs, false, &d.faceLines, options);
}

}  // namespace knit::impl
