// mesh_off.cpp — the OFF reader (ASCII; texture coordinates need the "ST" header prefix:
// STOFF, x y z u v per vertex).
//
// OpenMesh 9.0's ASCII OFF reader knows no '#' comments, trusts counts and corner counts, and
// returns success on garbage, so the text is checked line by line first (scanOff) and OpenMesh
// (mesh_openmesh.hpp) parses a cleaned copy from a string stream; it reads the header options in
// can_u_read(), so that is called before read(). Binary OFF is rejected. Positions and UVs come
// through OpenMesh as float32.
#include "mesh_openmesh.hpp"

#include <OpenMesh/Core/IO/Options.hh>
#include <OpenMesh/Core/IO/reader/OFFReader.hh>

#include <cmath>
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

// ASCII OFF: OpenMesh's reader knows no '#' comments (it then reads garbage counts and can loop
// over billions of empty faces), wants the counts on the line after the header keyword, sizes
// a face from its unchecked corner count, turns a non-numeric token into garbage indices and
// repeats the last face of a truncated file, all without reporting an error. So the text is
// checked first, line-based as OFF writers write it: the counts line holds exactly
// "vertices faces edges", then one vertex per line (finite numbers, >= 3 of them), then one
// face per line ("k i1 .. ik [colour]", 0 <= i < vertices). OpenMesh parses a cleaned copy
// (comments and blank lines removed, keyword on its own line). Binary OFF is rejected: it
// cannot be checked this way and OpenMesh trusts its counts.
void scanOff(const std::string& path, std::string& cleaned, std::vector<size_t>& faceLines) {
    std::ifstream in(path, std::ios::binary);
    if (!in) failMesh(path, "cannot open for reading");
    std::string line, keyword, tok;
    std::getline(in, line);
    std::istringstream header(line.substr(0, line.find('#')));
    header >> keyword;
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
        failMeshLine(path, 1, "not an OFF file (the first line must start with a header such as OFF or STOFF)");
    std::string rest;
    std::getline(header, rest);
    if (trimmed(rest).rfind("BINARY", 0) == 0)
        failMesh(path, "binary OFF is not supported (use ASCII OFF, PLY or OBJ)");
    std::ostringstream out;
    out << keyword << "\n";
    size_t dataLine = 0;  // 0: counts, then vertices, then faces
    double nv = 0, nf = 0;
    std::vector<double> values;
    auto take = [&](const std::string& text, size_t lineNo) {
        values.clear();
        std::istringstream ls(text);
        double v;
        while (ls >> tok) {
            if (!parseFinite(tok, v)) failMeshLine(path, lineNo, "'" + tok + "' is not a finite number");
            requireFloatRange(path, lineNo, tok, v);
            values.push_back(v);
        }
        if (values.empty()) return;
        if (dataLine == 0) {
            if (values.size() != 3 || values[0] < 0 || values[1] < 0 || values[0] != std::floor(values[0]) ||
                values[1] != std::floor(values[1]))
                failMeshLine(path, lineNo, "expected the counts 'vertices faces edges' (3 non-negative integers)");
            nv = values[0], nf = values[1];
        } else if (double(dataLine) <= nv) {
            if (values.size() < 3) failMeshLine(path, lineNo, "a vertex line needs at least 3 numbers");
        } else if (double(dataLine) <= nv + nf) {
            const double k = values[0];
            if (k < 3 || k != std::floor(k) || k > double(values.size() - 1))
                failMeshLine(path, lineNo, "a face line must be 'k i1 .. ik' with k >= 3 vertex indices");
            for (size_t i = 1; i <= size_t(k); ++i)
                if (values[i] < 0 || values[i] >= nv || values[i] != std::floor(values[i]))
                    failMeshLine(path, lineNo,
                                 "face references vertex " + std::to_string(values[i]) + " but the file has " +
                                     countText(nv) + " vertices");
            // A face colour after the indices (integer or float RGB[A], valid OFF) is not passed
            // on: OpenMesh misreads float colours as more corners. libknit does not use colours.
            std::ostringstream face;
            for (size_t i = 0; i <= size_t(k); ++i) face << (i ? " " : "") << uint64_t(values[i]);
            faceLines.push_back(lineNo);
            ++dataLine;
            out << face.str() << "\n";
            return;
        }
        ++dataLine;
        out << text << "\n";
    };
    take(rest, 1);
    for (size_t lineNo = 2; std::getline(in, line); ++lineNo) take(line.substr(0, line.find('#')), lineNo);
    if (dataLine == 0) failMesh(path, "OFF header has no 'vertices faces edges' counts");
    if (double(dataLine) < 1 + nv + nf)
        failMesh(path, "declares " + countText(nv) + " vertices and " + countText(nf) + " faces but holds only " +
                           std::to_string(dataLine - 1) + " data lines (truncated?)");
    if (nf == 0) failMesh(path, "the mesh has no faces");
    cleaned = out.str();
}

}  // namespace

BaseMesh readOffMesh(const std::string& path, const MeshLoadOptions& options) {
    std::string offText;
    std::vector<size_t> faceLines;
    scanOff(path, offText, faceLines);
    RecordingImporter rec;
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexTexCoord;
    bool ok = false;
    {
        std::lock_guard<std::mutex> lock(openMeshReaderMutex());
        if (!OpenMesh::IO::OFFReader().can_u_read(path)) ok = false;  // parses the header options
        else {
            std::istringstream text(offText);
            ok = OpenMesh::IO::OFFReader().read(text, rec, opt);
        }
    }
    if (!ok) failMesh(path, "OpenMesh could not parse the file (malformed or truncated)");
    const size_t nv = rec.points.size();
    if (!opt.check(OpenMesh::IO::Options::VertexTexCoord))
        failMesh(path, "no texture coordinates (an STOFF header with x y z u v per vertex); libknit needs UVs");
    std::vector<glm::dvec2> vertexUv(nv);
    for (size_t i = 0; i < nv; ++i) vertexUv[i] = {rec.vertexUv[i][0], rec.vertexUv[i][1]};
    const std::vector<size_t>* lines = faceLines.size() == rec.n_faces() ? &faceLines : nullptr;
    return buildPolygonMesh(path, rec.polys, recordedPoints(rec), vertexUv, false, lines, options);
}

}  // namespace knit::impl
