// mesh_obj.cpp — the OBJ reader: one pass over the text, line by line.
//
// Every `v`/`vt` must hold finite numbers and every `f` must reference existing v/vt entries
// with >= 3 distinct vertices, each corner with a texture coordinate (`f v/vt`); errors name
// the line. Positions are kept in double; texture coordinates are stored as float32, read as
// float (strtof, as OpenMesh's OBJ reader, which libknit used before, read them). Hexadecimal
// numbers ("0x1p3") are refused. A 3D vertex with several UVs is a seam: the position stays one vertex, UVs differ per
// corner. Normals, colours, groups and materials are not read; an `mtllib` that names a device
// or FIFO is still refused.
#include "mesh_reader.hpp"

#include "io/special_file.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace knit::impl {
namespace {

// The whitespace-separated words of a line, as `std::istringstream >> std::string` reads them,
// without a stream per line.
class Words {
public:
    explicit Words(const std::string& line) : line_(line) {}
    bool next(std::string& word) {
        while (at_ < line_.size() && std::isspace(static_cast<unsigned char>(line_[at_]))) ++at_;
        if (at_ == line_.size()) return false;
        const size_t begin = at_;
        while (at_ < line_.size() && !std::isspace(static_cast<unsigned char>(line_[at_]))) ++at_;
        word.assign(line_, begin, at_ - begin);
        return true;
    }

private:
    const std::string& line_;
    size_t at_ = 0;
};

}  // namespace

BaseMesh readObjMesh(const std::string& path, const MeshLoadOptions& options) {
    std::ifstream in(path, std::ios::binary);
    if (!in) failMesh(path, "cannot open for reading");
    std::vector<glm::dvec3> positions;
    std::vector<glm::vec2> uvs;
    std::vector<size_t> faceLines;  // line number of each `f`
    struct FaceRef {
        size_t line;
        long maxV, maxVt;
    };
    std::vector<FaceRef> refs;
    std::vector<long> cornerV, cornerVt;  // 1-based, relative indices resolved; checked at the end
    std::vector<uint32_t> faceStart{0};
    bool anyVtInFaces = false, anyFaceWithoutVt = false;
    size_t firstFaceWithoutVt = 0;
    std::string line, key, tok;
    std::vector<long> verts, sorted;
    for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
        Words ls(line);
        if (!ls.next(key) || key[0] == '#') continue;
        if (key == "v" || key == "vt") {
            const int need = key == "v" ? 3 : 2;
            double c[3] = {0, 0, 0};
            float uv[2] = {0, 0};
            for (int i = 0; i < need; ++i) {
                if (!ls.next(tok) || isHexNumber(tok) || !parseFinite(tok, c[i]))
                    failMeshLine(path, lineNo,
                                 key == "v" ? "vertex position is not three finite numbers"
                                            : "texture coordinate (vt) is not two finite numbers");
                requireFloatRange(path, lineNo, tok, c[i]);
                if (need == 2) uv[i] = std::strtof(tok.c_str(), nullptr);
            }
            if (key == "v") positions.emplace_back(c[0], c[1], c[2]);
            else uvs.emplace_back(uv[0], uv[1]);
        } else if (key == "mtllib") {
            // Materials are not read, but a material library that is a device or FIFO is refused.
            const std::string name = trimmed(trimmed(line).substr(6));
            const std::string lib = (std::filesystem::path(path).parent_path() / name).string();
            if (isSpecialFile(lib)) failMeshLine(path, lineNo, "mtllib '" + name + "' " + notRegularFile());
        } else if (key == "f") {
            FaceRef ref{lineNo, 0, 0};
            verts.clear();
            size_t withVt = 0;
            while (ls.next(tok)) {
                const size_t s1 = tok.find('/');
                long v = 0, vt = 0;
                if (!parseIndex(tok.substr(0, s1), v))
                    failMeshLine(path, lineNo, "face corner '" + tok + "' has no valid vertex index");
                if (v < 0) v = long(positions.size()) + v + 1;  // relative index
                if (v < 1)
                    failMeshLine(path, lineNo, "face corner '" + tok + "' references a vertex before the first one");
                if (s1 != std::string::npos) {
                    const size_t s2 = tok.find('/', s1 + 1);
                    const std::string t = tok.substr(s1 + 1, s2 == std::string::npos ? std::string::npos : s2 - s1 - 1);
                    if (!t.empty()) {
                        if (!parseIndex(t, vt))
                            failMeshLine(path, lineNo, "face corner '" + tok + "' has an invalid vt index");
                        if (vt < 0) vt = long(uvs.size()) + vt + 1;
                        if (vt < 1)
                            failMeshLine(path, lineNo,
                                         "face corner '" + tok + "' references a vt before the first one");
                        ++withVt;
                    }
                }
                ref.maxV = std::max(ref.maxV, v);
                ref.maxVt = std::max(ref.maxVt, vt);
                verts.push_back(v);
                cornerVt.push_back(vt);
            }
            if (verts.size() < 3) failMeshLine(path, lineNo, "face has fewer than 3 corners");
            sorted = verts;
            std::sort(sorted.begin(), sorted.end());
            if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
                failMeshLine(
                    path, lineNo,
                    "face uses vertex " + std::to_string(*std::adjacent_find(sorted.begin(), sorted.end())) + " twice");
            if (withVt != 0 && withVt != verts.size())
                failMeshLine(path, lineNo, "face mixes corners with and without texture coordinates");
            if (withVt) anyVtInFaces = true;
            else if (!anyFaceWithoutVt) {
                anyFaceWithoutVt = true;
                firstFaceWithoutVt = lineNo;
            }
            refs.push_back(ref);
            cornerV.insert(cornerV.end(), verts.begin(), verts.end());
            faceStart.push_back(uint32_t(cornerV.size()));
            faceLines.push_back(lineNo);
        }
    }
    if (in.bad()) failMesh(path, "read error");
    // Positive indices may point forward, so ranges are checked once all v/vt are known.
    for (const FaceRef& r : refs) {
        if (size_t(r.maxV) > positions.size())
            failMeshLine(path, r.line,
                         "face references vertex " + std::to_string(r.maxV) + " but the file has " +
                             std::to_string(positions.size()) + " vertices (v)");
        if (size_t(r.maxVt) > uvs.size())
            failMeshLine(path, r.line,
                         "face references texture coordinate " + std::to_string(r.maxVt) + " but the file has " +
                             std::to_string(uvs.size()) + " (vt)");
    }
    if (refs.empty()) failMesh(path, "the mesh has no faces");
    if (!anyVtInFaces) failMesh(path, "no texture coordinates (vt); libknit needs UVs");
    if (anyFaceWithoutVt)
        failMeshLine(path, firstFaceWithoutVt,
                     "face has no texture coordinates (v/vt); libknit needs UVs on every face");

    // Every index is in range and every corner has its vt: the polygons with their corner UVs.
    Polygons polys;
    polys.faceStart = std::move(faceStart);
    polys.faceVerts.resize(cornerV.size());
    polys.cornerUv.resize(cornerV.size());
    for (size_t c = 0; c < cornerV.size(); ++c) {
        polys.faceVerts[c] = int(cornerV[c] - 1);
        polys.cornerUv[c] = uvs[size_t(cornerVt[c] - 1)];
    }
    polys.faceHasCornerUv.assign(polys.count(), 1);
    polys.faceCornerUvMismatch.assign(polys.count(), 0);
    return buildPolygonMesh(path, polys, positions, {}, true, &faceLines, options);
}

}  // namespace knit::impl
