// mesh_io.cpp — loadMesh: OBJ / PLY / OFF through OpenMesh's readers into a BaseMesh (glTF is
// read by mesh_gltf.cpp).
//
// How the files are read (facts checked against OpenMesh 9.0, the Debian package):
//  * Dispatch is by the file's extension, case-insensitive: .obj, .ply, .off (anything else is
//    an error). The matching OpenMesh reader singleton is called directly.
//  * Every file is pre-scanned here before OpenMesh sees it, because OpenMesh 9.0 accepts
//    garbage silently and, on some malformed files, crashes, loops or allocates without bound
//    (found by tests/mesh/mesh_fuzz_test.cpp); what OpenMesh returns is checked again after.
//  * OpenMesh's readers talk to a BaseImporter. We give them a *recording* importer instead of a
//    halfedge mesh: it keeps the file's vertices, polygons and texture coordinates exactly as
//    read. A halfedge mesh would silently split "non-manifold" faces (inconsistently oriented
//    neighbours, fans) into duplicated vertices, and OpenMesh then attaches an OBJ face's
//    texcoords starting at the wrong corner. Topology is rebuilt here by welding instead.
//  * OBJ: per face-corner texcoords (`f v/vt`) arrive through add_face_texcoords (OpenMesh's
//    "halfedge texcoords", Options::FaceTexCoord), in face order starting at the first corner.
//    A 3D vertex with several UVs is a seam: the position stays one vertex, UVs differ per
//    corner. OpenMesh's OBJ reader silently *skips* `v` lines it cannot parse (nan, inf,
//    1e400) — shifting every later index — and drops faces with out-of-range or repeated
//    vertices, so an OBJ is first scanned here line by line: every `v`/`vt` must hold finite
//    numbers and every `f` must reference existing v/vt entries with >= 3 distinct vertices.
//    The scan also keeps the `v` coordinates in double (OpenMesh's OBJ reader narrows them to
//    float32); they replace OpenMesh's values one for one (counts are checked to agree).
//  * PLY (ascii, binary little/big endian): per-vertex u,v or s,t are read by OpenMesh as
//    Options::VertexTexCoord. texture_u,texture_v / texture_s,texture_t are *not* known to
//    OpenMesh 9.0; they are read as custom properties (Options::Custom) into a property-only
//    ArrayKernel owned by the importer. OpenMesh's PLY reader turns a non-numeric ASCII token
//    (e.g. "nan") into zeros and empty faces without reporting failure, crashes on some
//    malformed headers and trusts list counts, so the file is walked first (see scanPly).
//    Positions come through OpenMesh as float32.
//  * OFF: texture coordinates need the "ST" header prefix (STOFF: x y z u v per vertex).
//    OpenMesh reads the header options in can_u_read(), so that is called before read(). Its
//    ASCII reader knows no '#' comments, trusts counts and corner counts, and returns success
//    on garbage, so the text is checked line by line first (see scanOff) and OpenMesh parses a
//    cleaned copy from a string stream. Binary OFF is rejected.
//  * OpenMesh keeps texture coordinates as float32 for every format.
//  * Faces are triangulated inside their outline (polygon_triangulation.hpp: convex ones as the
//    fan (v0, vi, vi+1), concave ones by a constrained Delaunay triangulation in their best-fit
//    plane; a polygon without area or crossing itself is refused naming it). Positions that are exactly equal (-0 == +0) are
//    welded when MeshLoadOptions::weldEqualPositions is set, so PLY/OFF files that duplicate
//    vertices along UV seams get the same 3D topology as the OBJ. Vertices no face references
//    are dropped. A UV vertex is one distinct (position, uv) pair, numbered in first-use order.
//  * OpenMesh prints its own warnings to std::cerr (omerr); libknit's knit::Error is the
//    authoritative result. The reader singletons hold state (OFF options), so calls into them
//    are serialized by a mutex here.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "mesh_weld.hpp"
#include "util/platform.hpp"
#include "io/special_file.hpp"

#include <OpenMesh/Core/IO/Options.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/IO/reader/OBJReader.hh>
#include <OpenMesh/Core/IO/reader/OFFReader.hh>
#include <OpenMesh/Core/IO/reader/PLYReader.hh>
#include <OpenMesh/Core/Mesh/ArrayKernel.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <unordered_map>

namespace knit {
namespace {

namespace OMIO = OpenMesh::IO;

[[noreturn]] void fail(const std::string& file, const std::string& what) { throw Error(file + ": " + what); }
[[noreturn]] void failLine(const std::string& file, size_t line, const std::string& what) {
    throw Error(file + ":" + std::to_string(line) + ": " + what);
}

// A token that is a whole, finite number ("1.5e-3"; not "nan", "inf", "1e400", "1.0abc").
bool parseFinite(const std::string& token, double& value) {
    if (token.empty()) return false;
    errno = 0;
    char* end = nullptr;
    value = std::strtod(token.c_str(), &end);
    return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(value);
}

// A parsed number the mesh reader (OpenMesh, float32) can store: beyond +-3.4e38 it would read
// garbage and report only a vertex count, so the line and the value are named here.
void requireFloatRange(const std::string& path, size_t lineNo, const std::string& token, double value) {
    if (std::abs(value) > double(std::numeric_limits<float>::max()))
        failLine(path, lineNo, "'" + token + "' is beyond the float32 range (3.4e38) of mesh coordinates");
}

// Files saved with a UTF-8 byte-order mark: named instead of blamed on the first element.
void refuseByteOrderMark(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char head[3] = {};
    if (in.read(head, 3) && head[0] == '\xEF' && head[1] == '\xBB' && head[2] == '\xBF')
        fail(path, "starts with a UTF-8 byte-order mark (BOM), which mesh files may not have; save it without the BOM");
}

bool parseIndex(const std::string& token, long& value) {
    if (token.empty()) return false;
    errno = 0;
    char* end = nullptr;
    value = std::strtol(token.c_str(), &end, 10);
    return end == token.c_str() + token.size() && errno != ERANGE && value != 0;
}

std::string trimmed(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    size_t b = 0;
    while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
    return s.substr(b);
}

// ---------------------------------------------------------------------------------------------
// Recording importer: what OpenMesh's reader saw, without building halfedge topology.
class RecordingImporter final : public OMIO::BaseImporter {
public:
    std::vector<OpenMesh::Vec3d> points;
    std::vector<OpenMesh::Vec2f> vertexUv;
    std::vector<char> vertexHasUv;
    std::vector<uint32_t> faceStart{0};  // polygon k = faceVerts[faceStart[k] .. faceStart[k+1])
    std::vector<int> faceVerts;
    std::vector<OpenMesh::Vec2f> cornerUv;  // same layout as faceVerts
    std::vector<char> faceHasCornerUv;
    std::vector<char> faceCornerUvMismatch;  // texcoord count != corner count
    OpenMesh::ArrayKernel customProps;       // PLY custom properties (texture_u, ...) land here

    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
        return add_vertex(OpenMesh::Vec3d(p[0], p[1], p[2]));
    }
    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
        points.push_back(p);
        vertexUv.emplace_back(0.f, 0.f);
        vertexHasUv.push_back(0);
        customProps.new_vertex();
        return OpenMesh::VertexHandle(int(points.size() - 1));
    }
    OpenMesh::VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
    OpenMesh::FaceHandle add_face(const VHandles& indices) override {
        for (const auto& vh : indices) faceVerts.push_back(vh.idx());
        faceStart.push_back(uint32_t(faceVerts.size()));
        cornerUv.resize(faceVerts.size(), OpenMesh::Vec2f(0.f, 0.f));
        faceHasCornerUv.push_back(0);
        faceCornerUvMismatch.push_back(0);
        customProps.new_face();
        return OpenMesh::FaceHandle(int(faceStart.size() - 2));
    }
    // Texcoords of face `fh`, listed from the corner at vertex `vh` on, in face order.
    void add_face_texcoords(OpenMesh::FaceHandle fh, OpenMesh::VertexHandle vh,
                            const std::vector<OpenMesh::Vec2f>& tcs) override {
        if (!fh.is_valid() || size_t(fh.idx()) + 1 >= faceStart.size()) return;
        const uint32_t b = faceStart[fh.idx()], n = faceStart[fh.idx() + 1] - b;
        if (tcs.empty()) return;
        if (tcs.size() != n) {
            faceCornerUvMismatch[fh.idx()] = 1;
            return;
        }
        uint32_t first = 0;
        while (first < n && faceVerts[b + first] != vh.idx()) ++first;
        if (first == n) first = 0;
        for (uint32_t i = 0; i < n; ++i) cornerUv[b + (first + i) % n] = tcs[i];
        faceHasCornerUv[fh.idx()] = 1;
    }
    void set_texcoord(OpenMesh::VertexHandle vh, const OpenMesh::Vec2f& t) override {
        if (vh.is_valid() && size_t(vh.idx()) < vertexUv.size()) {
            vertexUv[vh.idx()] = t;
            vertexHasUv[vh.idx()] = 1;
        }
    }
    void set_point(OpenMesh::VertexHandle vh, const OpenMesh::Vec3f& p) override {
        if (vh.is_valid() && size_t(vh.idx()) < points.size()) points[vh.idx()] = OpenMesh::Vec3d(p[0], p[1], p[2]);
    }
    OpenMesh::BaseKernel* kernel() override { return &customProps; }
    size_t n_vertices() const override { return points.size(); }
    size_t n_faces() const override { return faceStart.size() - 1; }
    size_t n_edges() const override { return 0; }

    // Everything below is information libknit does not use.
    OpenMesh::HalfedgeHandle add_edge(OpenMesh::VertexHandle, OpenMesh::VertexHandle) override {
        return OpenMesh::HalfedgeHandle();
    }
    OpenMesh::FaceHandle add_face(OpenMesh::HalfedgeHandle) override { return OpenMesh::FaceHandle(); }
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle,
                            const std::vector<OpenMesh::Vec3f>&) override {}
    void set_face_texindex(OpenMesh::FaceHandle, int) override {}
    void set_halfedge(OpenMesh::VertexHandle, OpenMesh::HalfedgeHandle) override {}
    void set_normal(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(OpenMesh::VertexHandle, const OpenMesh::Vec3d&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_next(OpenMesh::HalfedgeHandle, OpenMesh::HalfedgeHandle) override {}
    void set_face(OpenMesh::HalfedgeHandle, OpenMesh::FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec2f&) override {}
    void set_texcoord(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec3f&) override {}
    void set_status(OpenMesh::HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_normal(OpenMesh::FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(OpenMesh::FaceHandle, const OpenMesh::Vec3d&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}
};

// ---------------------------------------------------------------------------------------------
// OBJ pre-scan (see file comment): finite v/vt, valid f references; v kept in double.
struct ObjScan {
    std::vector<glm::dvec3> positions;
    size_t uvCount = 0;
    std::vector<size_t> faceLines;  // line number of each `f`
};

ObjScan scanObj(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open for reading");
    ObjScan scan;
    struct FaceRef {
        size_t line;
        long maxV, maxVt;
    };
    std::vector<FaceRef> refs;
    bool anyVtInFaces = false, anyFaceWithoutVt = false;
    size_t firstFaceWithoutVt = 0;
    std::string line, key, tok;
    for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
        line = trimmed(line);
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        ls >> key;
        if (key == "v" || key == "vt") {
            const int need = key == "v" ? 3 : 2;
            double c[3] = {0, 0, 0};
            for (int i = 0; i < need; ++i) {
                if (!(ls >> tok) || !parseFinite(tok, c[i]))
                    failLine(path, lineNo,
                             key == "v" ? "vertex position is not three finite numbers"
                                        : "texture coordinate (vt) is not two finite numbers");
                requireFloatRange(path, lineNo, tok, c[i]);
            }
            if (key == "v") scan.positions.emplace_back(c[0], c[1], c[2]);
            else ++scan.uvCount;
        } else if (key == "mtllib") {
            // OpenMesh reads the material library itself: never let it open a device or FIFO.
            const std::string name = trimmed(line.substr(6));
            const std::string lib = (std::filesystem::path(path).parent_path() / name).string();
            if (impl::isSpecialFile(lib)) failLine(path, lineNo, "mtllib '" + name + "' " + impl::notRegularFile());
        } else if (key == "f") {
            FaceRef ref{lineNo, 0, 0};
            std::vector<long> verts;
            size_t withVt = 0;
            while (ls >> tok) {
                const size_t s1 = tok.find('/');
                long v = 0, vt = 0;
                if (!parseIndex(tok.substr(0, s1), v))
                    failLine(path, lineNo, "face corner '" + tok + "' has no valid vertex index");
                if (v < 0) v = long(scan.positions.size()) + v + 1;  // relative index
                if (v < 1) failLine(path, lineNo, "face corner '" + tok + "' references a vertex before the first one");
                if (s1 != std::string::npos) {
                    const size_t s2 = tok.find('/', s1 + 1);
                    const std::string t = tok.substr(s1 + 1, s2 == std::string::npos ? std::string::npos : s2 - s1 - 1);
                    if (!t.empty()) {
                        if (!parseIndex(t, vt))
                            failLine(path, lineNo, "face corner '" + tok + "' has an invalid vt index");
                        if (vt < 0) vt = long(scan.uvCount) + vt + 1;
                        if (vt < 1)
                            failLine(path, lineNo, "face corner '" + tok + "' references a vt before the first one");
                        ++withVt;
                    }
                }
                ref.maxV = std::max(ref.maxV, v);
                ref.maxVt = std::max(ref.maxVt, vt);
                verts.push_back(v);
            }
            if (verts.size() < 3) failLine(path, lineNo, "face has fewer than 3 corners");
            std::vector<long> sorted = verts;
            std::sort(sorted.begin(), sorted.end());
            if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
                failLine(
                    path, lineNo,
                    "face uses vertex " + std::to_string(*std::adjacent_find(sorted.begin(), sorted.end())) + " twice");
            if (withVt != 0 && withVt != verts.size())
                failLine(path, lineNo, "face mixes corners with and without texture coordinates");
            if (withVt) anyVtInFaces = true;
            else if (!anyFaceWithoutVt) {
                anyFaceWithoutVt = true;
                firstFaceWithoutVt = lineNo;
            }
            refs.push_back(ref);
            scan.faceLines.push_back(lineNo);
        }
    }
    if (in.bad()) fail(path, "read error");
    // Positive indices may point forward, so ranges are checked once all v/vt are known.
    for (const FaceRef& r : refs) {
        if (size_t(r.maxV) > scan.positions.size())
            failLine(path, r.line,
                     "face references vertex " + std::to_string(r.maxV) + " but the file has " +
                         std::to_string(scan.positions.size()) + " vertices (v)");
        if (size_t(r.maxVt) > scan.uvCount)
            failLine(path, r.line,
                     "face references texture coordinate " + std::to_string(r.maxVt) + " but the file has " +
                         std::to_string(scan.uvCount) + " (vt)");
    }
    if (refs.empty()) fail(path, "the mesh has no faces");
    if (!anyVtInFaces) fail(path, "no texture coordinates (vt); libknit needs UVs");
    if (anyFaceWithoutVt)
        failLine(path, firstFaceWithoutVt, "face has no texture coordinates (v/vt); libknit needs UVs on every face");
    return scan;
}

// ---------------------------------------------------------------------------------------------
// PLY pre-scan. OpenMesh 9.0 crashes on some malformed headers (a property before any element)
// and sizes buffers from list counts it has not checked (a count of -4 allocated ~20 GB), so the
// whole file is walked here first: the header line by line, then every element against the
// declared properties — ASCII: one element per line, exactly the declared tokens, every token a
// finite number, list counts non-negative integers; binary: list counts in range and every
// element inside the file. Only a file that passes is handed to OpenMesh.
struct PlyProperty {
    bool list = false;
    std::string countType, type, name;
};
struct PlyElement {
    std::string name;
    size_t count = 0;
    std::vector<PlyProperty> props;
};
struct PlyHeader {
    bool ascii = false, bigEndian = false;
    std::vector<PlyElement> elements;
    bool hasTextureUV = false;  // texture_u/texture_v or texture_s/texture_t on the vertex element
    std::string textureU, textureV;
};

int plyTypeSize(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}
bool plyFloatType(const std::string& t) { return t == "float" || t == "float32" || t == "double" || t == "float64"; }
bool plySignedType(const std::string& t) {
    return t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
}

// A binary scalar at `at` as a double (integers exactly up to 2^53).
double plyBinaryValue(const std::string& body, size_t at, const std::string& type, bool bigEndian) {
    const int n = plyTypeSize(type);
    unsigned char b[8];
    for (int i = 0; i < n; ++i) b[i] = static_cast<unsigned char>(body[at + (bigEndian ? n - 1 - i : i)]);
    uint64_t u = 0;
    for (int i = n - 1; i >= 0; --i) u = (u << 8) | b[i];
    if (type == "float" || type == "float32") {
        float f;
        const uint32_t u32 = uint32_t(u);
        std::memcpy(&f, &u32, 4);
        return f;
    }
    if (n == 8) {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
    }
    if (plySignedType(type)) {
        const uint64_t sign = uint64_t(1) << (8 * n - 1);
        return double(int64_t(u ^ sign) - int64_t(sign));
    }
    return double(u);
}

void checkPlyBody(std::istream& in, const std::string& path, const PlyHeader& h, size_t firstLineNo) {
    if (h.ascii) {
        std::string line, tok;
        size_t lineNo = firstLineNo - 1;
        std::vector<double> values;
        for (const PlyElement& e : h.elements)
            for (size_t k = 0; k < e.count; ++k) {
                // One element per line (blank lines skipped), every token a finite number.
                values.clear();
                while (values.empty()) {
                    if (!std::getline(in, line))
                        fail(path, "file ends inside element '" + e.name + "' " + std::to_string(k) + " of " +
                                       std::to_string(e.count) + " (truncated?)");
                    ++lineNo;
                    std::istringstream ls(line);
                    double v;
                    while (ls >> tok) {
                        if (!parseFinite(tok, v)) failLine(path, lineNo, "'" + tok + "' is not a finite number");
                        requireFloatRange(path, lineNo, tok, v);
                        values.push_back(v);
                    }
                }
                // Exactly the declared properties; list counts are non-negative integers.
                size_t at = 0;
                for (const PlyProperty& p : e.props) {
                    if (at >= values.size()) failLine(path, lineNo, "too few values for element '" + e.name + "'");
                    if (p.list) {
                        const double n = values[at++];
                        if (n < 0 || n != std::floor(n) || n > double(values.size() - at))
                            failLine(path, lineNo, "list '" + p.name + "' has a bad count");
                        at += size_t(n);
                    } else {
                        ++at;
                    }
                }
                if (at != values.size()) failLine(path, lineNo, "too many values for element '" + e.name + "'");
            }
        return;
    }
    // Binary: walk the elements through the bytes.
    const std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    size_t at = 0;
    for (const PlyElement& e : h.elements)
        for (size_t k = 0; k < e.count; ++k)
            for (const PlyProperty& p : e.props) {
                auto truncated = [&] {
                    fail(path, "file ends inside element '" + e.name + "' " + std::to_string(k) + " of " +
                                   std::to_string(e.count) + " (truncated?)");
                };
                if (!p.list) {
                    const size_t n = size_t(plyTypeSize(p.type));
                    if (body.size() - at < n) truncated();
                    at += n;
                    continue;
                }
                const size_t cn = size_t(plyTypeSize(p.countType)), n = size_t(plyTypeSize(p.type));
                if (body.size() - at < cn) truncated();
                const double count = plyBinaryValue(body, at, p.countType, h.bigEndian);
                at += cn;
                if (count < 0 || count > double(body.size() - at) / double(n))
                    fail(path, "element '" + e.name + "' " + std::to_string(k) + ": list '" + p.name +
                                   "' has a bad count (" + std::to_string(count) + ")");
                at += size_t(count) * n;
            }
}

// OpenMesh 9.0's binary PLY reader converts only float/double data to its float-valued vertex
// properties (positions, normals, texture coordinates), only integer or float data to colours,
// and only integer data to face indices; a property of any other type is skipped without
// consuming its bytes, which desynchronises the rest of the file (garbage values, or minutes
// spent reading a misread list count: tests/fuzz_corpus/ply/timeout-*). Refused up front.
void checkPlyConvertible(const PlyHeader& h, const std::string& path) {
    static const char* kFloatValued[] = {"x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t"};
    static const char* kColours[] = {"red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"};
    for (const PlyElement& e : h.elements)
        for (const PlyProperty& p : e.props) {
            const bool isDouble = p.type == "double" || p.type == "float64";
            std::string need;
            if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index") && plyFloatType(p.type))
                need = "an integer type";
            else if (!p.list && e.name == "vertex" &&
                     std::any_of(std::begin(kFloatValued), std::end(kFloatValued),
                                 [&](const char* n) { return p.name == n; }) &&
                     !plyFloatType(p.type))
                need = "float or double";
            else if (!p.list && isDouble &&
                     std::any_of(std::begin(kColours), std::end(kColours), [&](const char* n) { return p.name == n; }))
                need = "an integer type or float";
            if (!need.empty())
                fail(path, "binary PLY property '" + p.type + " " + p.name + "' of element '" + e.name +
                               "' is not supported (its type must be " + need + ")");
        }
}

PlyHeader scanPly(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open for reading");
    PlyHeader h;
    std::string line, word;
    size_t lineNo = 0;
    bool ended = false, hasFormat = false;
    while (!ended && std::getline(in, line)) {
        ++lineNo;
        std::istringstream ls(trimmed(line));
        word.clear();
        ls >> word;
        if (lineNo == 1) {
            if (word != "ply") fail(path, "not a PLY file (the first line is not 'ply')");
            continue;
        }
        if (word == "comment" || word == "obj_info" || word.empty()) continue;
        if (word == "format") {
            std::string fmt, version, extra;
            ls >> fmt >> version >> extra;
            double v = 0;
            if (fmt != "ascii" && fmt != "binary_little_endian" && fmt != "binary_big_endian")
                failLine(path, lineNo, "unknown PLY format '" + fmt + "'");
            // PLY has only version 1.0; OpenMesh loops forever on other versions.
            if (!parseFinite(version, v) || v != 1.0 || !extra.empty())
                failLine(path, lineNo, "the format line must be 'format " + fmt + " 1.0'");
            h.ascii = fmt == "ascii";
            h.bigEndian = fmt == "binary_big_endian";
            hasFormat = true;
        } else if (word == "element") {
            PlyElement e;
            std::string count, extra;
            ls >> e.name >> count >> extra;
            long n = 0;
            if (e.name.empty() || !(count == "0" || parseIndex(count, n)) || n < 0 || !extra.empty())
                failLine(path, lineNo, "element line needs a name and a non-negative count");
            e.count = size_t(n);
            h.elements.push_back(e);
        } else if (word == "property") {
            if (h.elements.empty()) failLine(path, lineNo, "property line before any element line");
            PlyProperty p;
            ls >> p.type;
            if (p.type == "list") {
                p.list = true;
                ls >> p.countType >> p.type;
                if (!plyTypeSize(p.countType) || plyFloatType(p.countType) || !plyTypeSize(p.type))
                    failLine(path, lineNo, "bad list property types '" + p.countType + " " + p.type + "'");
            } else if (!plyTypeSize(p.type)) {
                failLine(path, lineNo, "unknown property type '" + p.type + "'");
            }
            std::string extra;
            ls >> p.name >> extra;
            if (p.name.empty() || !extra.empty())
                failLine(path, lineNo, "a property line must be 'property TYPE NAME'");
            h.elements.back().props.push_back(p);
        } else if (word == "end_header" && trimmed(line) == "end_header") {
            ended = true;
        } else {
            failLine(path, lineNo, "unexpected PLY header line '" + trimmed(line) + "'");
        }
    }
    if (!ended) fail(path, "PLY header has no end_header line");
    if (!hasFormat) fail(path, "PLY header has no format line");
    // The vertex element needs x, y, z; the face element a vertex index list.
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    for (const PlyElement& e : h.elements) {
        if (e.name == "vertex") vertex = &e;
        if (e.name == "face") face = &e;
    }
    if (!vertex) fail(path, "the PLY file has no vertex element");
    if (!face || face->count == 0) fail(path, "the mesh has no faces");
    auto has = [&](const char* n) {
        return std::any_of(vertex->props.begin(), vertex->props.end(),
                           [&](const PlyProperty& p) { return !p.list && p.name == n; });
    };
    if (!has("x") || !has("y") || !has("z")) fail(path, "the PLY vertex element needs x, y and z properties");
    if (!std::any_of(face->props.begin(), face->props.end(), [](const PlyProperty& p) {
            return p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
        }))
        fail(path, "the PLY face element has no vertex_indices list");
    const bool known = (has("u") && has("v")) || (has("s") && has("t"));
    if (!known) {
        if (has("texture_u") && has("texture_v")) h.textureU = "texture_u", h.textureV = "texture_v";
        else if (has("texture_s") && has("texture_t")) h.textureU = "texture_s", h.textureV = "texture_t";
        h.hasTextureUV = !h.textureU.empty();
    }
    if (!h.ascii) checkPlyConvertible(h, path);
    checkPlyBody(in, path, h, lineNo + 1);
    return h;
}

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
    if (!in) fail(path, "cannot open for reading");
    std::string line, keyword, tok;
    std::getline(in, line);
    std::istringstream header(line.substr(0, line.find('#')));
    header >> keyword;
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
        failLine(path, 1, "not an OFF file (the first line must start with a header such as OFF or STOFF)");
    std::string rest;
    std::getline(header, rest);
    if (trimmed(rest).rfind("BINARY", 0) == 0) fail(path, "binary OFF is not supported (use ASCII OFF, PLY or OBJ)");
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
            if (!parseFinite(tok, v)) failLine(path, lineNo, "'" + tok + "' is not a finite number");
            requireFloatRange(path, lineNo, tok, v);
            values.push_back(v);
        }
        if (values.empty()) return;
        if (dataLine == 0) {
            if (values.size() != 3 || values[0] < 0 || values[1] < 0 || values[0] != std::floor(values[0]) ||
                values[1] != std::floor(values[1]))
                failLine(path, lineNo, "expected the counts 'vertices faces edges' (3 non-negative integers)");
            nv = values[0], nf = values[1];
        } else if (double(dataLine) <= nv) {
            if (values.size() < 3) failLine(path, lineNo, "a vertex line needs at least 3 numbers");
        } else if (double(dataLine) <= nv + nf) {
            const double k = values[0];
            if (k < 3 || k != std::floor(k) || k > double(values.size() - 1))
                failLine(path, lineNo, "a face line must be 'k i1 .. ik' with k >= 3 vertex indices");
            for (size_t i = 1; i <= size_t(k); ++i)
                if (values[i] < 0 || values[i] >= nv || values[i] != std::floor(values[i]))
                    failLine(path, lineNo,
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
    if (dataLine == 0) fail(path, "OFF header has no 'vertices faces edges' counts");
    if (double(dataLine) < 1 + nv + nf)
        fail(path, "declares " + countText(nv) + " vertices and " + countText(nf) + " faces but holds only " +
                       std::to_string(dataLine - 1) + " data lines (truncated?)");
    if (nf == 0) fail(path, "the mesh has no faces");
    cleaned = out.str();
}

// Reads a float or double custom vertex property written by OpenMesh's PLY reader.
bool customVertexScalar(OpenMesh::ArrayKernel& k, const std::string& name, size_t n, std::vector<double>& out) {
    out.assign(n, 0.0);
    OpenMesh::VPropHandleT<float> pf;
    if (k.get_property_handle(pf, name)) {
        for (size_t i = 0; i < n; ++i) out[i] = k.property(pf, OpenMesh::VertexHandle(int(i)));
        return true;
    }
    OpenMesh::VPropHandleT<double> pd;
    if (k.get_property_handle(pd, name)) {
        for (size_t i = 0; i < n; ++i) out[i] = k.property(pd, OpenMesh::VertexHandle(int(i)));
        return true;
    }
    return false;
}

// Triangulated, welded BaseMesh from what the reader recorded.
BaseMesh buildMesh(const std::string& path, const RecordingImporter& rec, const std::vector<glm::dvec3>& points,
                   const std::vector<glm::dvec2>& vertexUv, bool cornerUvs, const std::vector<size_t>* faceLines,
                   const MeshLoadOptions& options) {
    const size_t nv = points.size(), nf = rec.n_faces();
    auto faceName = [&](size_t f) {
        return faceLines ? "face " + std::to_string(f) + " (line " + std::to_string((*faceLines)[f]) + ")"
                         : "face " + std::to_string(f);
    };
    if (nf == 0) fail(path, "the mesh has no faces");
    // Check positions and UVs are finite.
    for (size_t i = 0; i < nv; ++i)
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z))
            fail(path, "vertex " + std::to_string(i) + " has a non-finite position");
    // Check the polygons: >= 3 corners, indices in range, no repeated vertex, UVs present.
    for (size_t f = 0; f < nf; ++f) {
        const uint32_t b = rec.faceStart[f], e = rec.faceStart[f + 1];
        if (e - b < 3)
            fail(path, faceName(f) + " has " + std::to_string(e - b) +
                           " corners (malformed file, or a non-numeric value such as nan in ASCII data?)");
        for (uint32_t c = b; c < e; ++c) {
            const int v = rec.faceVerts[c];
            if (v < 0 || size_t(v) >= nv)
                fail(path, faceName(f) + " references vertex " + std::to_string(v) + " but the file has " +
                               std::to_string(nv) + " vertices");
            for (uint32_t d = b; d < c; ++d)
                if (rec.faceVerts[d] == v)
                    fail(path,
                         faceName(f) + " uses vertex " + std::to_string(v) + " twice (malformed or truncated file?)");
            const glm::dvec2 uv = cornerUvs ? glm::dvec2(rec.cornerUv[c][0], rec.cornerUv[c][1]) : vertexUv[v];
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
                fail(path, faceName(f) + " has a non-finite texture coordinate at vertex " + std::to_string(v));
        }
        if (cornerUvs && (rec.faceCornerUvMismatch[f] || !rec.faceHasCornerUv[f]))
            fail(path, faceName(f) + ": texture coordinates missing or not one per corner");
    }
    // Weld and triangulate (a polygon that cannot be is named with its line).
    return impl::weldPolygons(
        path, points, rec.faceStart, rec.faceVerts,
        [&](uint32_t c) {
            return cornerUvs ? glm::dvec2(rec.cornerUv[c][0], rec.cornerUv[c][1]) : vertexUv[size_t(rec.faceVerts[c])];
        },
        options, faceName);
}

std::mutex& openMeshReaderMutex() {
    static std::mutex m;
    return m;
}

}  // namespace

BaseMesh loadMesh(const std::string& path, const MeshLoadOptions& options) {
    // Check the file exists, is a regular file and has a known extension.
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) fail(path, "no such file");
    if (std::filesystem::is_directory(status)) fail(path, "is a directory, not a mesh file");
    if (impl::isSpecialFile(path)) fail(path, impl::notRegularFile());
    const std::string ext = util::lowerExtension(path);  // without the dot
    if (ext == "gltf" || ext == "glb") return loadGltfMesh(path, options);
    if (ext != "obj" && ext != "ply" && ext != "off") {
        const std::string dot = std::filesystem::path(path).has_extension() ? "." : "";  // "name." shows '.'
        fail(path, "unknown mesh file extension '" + dot + ext + "' (supported: .obj, .ply, .off, .gltf, .glb)");
    }
    if (!std::ifstream(path, std::ios::binary)) fail(path, "cannot open for reading");
    refuseByteOrderMark(path);

    // Pre-scan what OpenMesh would accept silently.
    ObjScan obj;
    PlyHeader ply;
    std::string offText;
    std::vector<size_t> offFaceLines;
    if (ext == "obj") obj = scanObj(path);
    else if (ext == "ply") ply = scanPly(path);
    else scanOff(path, offText, offFaceLines);

    // Parse with OpenMesh into the recording importer.
    RecordingImporter rec;
    OMIO::Options opt;
    opt += OMIO::Options::VertexTexCoord;
    if (ext == "obj") opt += OMIO::Options::FaceTexCoord;
    if (ext == "ply" && ply.hasTextureUV) opt += OMIO::Options::Custom;
    bool ok = false;
    {
        std::lock_guard<std::mutex> lock(openMeshReaderMutex());
        if (ext == "obj") ok = OMIO::OBJReader().read(path, rec, opt);
        else if (ext == "ply") ok = OMIO::PLYReader().read(path, rec, opt);
        else if (!OMIO::OFFReader().can_u_read(path)) ok = false;  // parses the header options
        else {
            std::istringstream text(offText);
            ok = OMIO::OFFReader().read(text, rec, opt);
        }
    }
    if (!ok) fail(path, "OpenMesh could not parse the file (malformed or truncated)");
    const size_t nv = rec.points.size();

    // Positions: OBJ from the double-precision scan (same count and order as OpenMesh's).
    std::vector<glm::dvec3> points(nv);
    if (ext == "obj") {
        if (nv != obj.positions.size() || rec.n_faces() != obj.faceLines.size())
            fail(path, "OpenMesh read " + std::to_string(nv) + " vertices and " + std::to_string(rec.n_faces()) +
                           " faces, but the file has " + std::to_string(obj.positions.size()) + " and " +
                           std::to_string(obj.faceLines.size()));
        points = obj.positions;
    } else {
        for (size_t i = 0; i < nv; ++i) points[i] = {rec.points[i][0], rec.points[i][1], rec.points[i][2]};
    }

    // UVs: per corner (OBJ) or per vertex (PLY/OFF, native or custom property).
    std::vector<glm::dvec2> vertexUv;
    bool cornerUvs = false;
    if (ext == "obj") {
        cornerUvs = true;
    } else if (ply.hasTextureUV) {
        std::vector<double> u, v;
        if (!customVertexScalar(rec.customProps, ply.textureU, nv, u) ||
            !customVertexScalar(rec.customProps, ply.textureV, nv, v))
            fail(path, "could not read vertex properties " + ply.textureU + "/" + ply.textureV);
        vertexUv.resize(nv);
        for (size_t i = 0; i < nv; ++i) vertexUv[i] = {u[i], v[i]};
    } else if (opt.check(OMIO::Options::VertexTexCoord)) {
        vertexUv.resize(nv);
        for (size_t i = 0; i < nv; ++i) vertexUv[i] = {rec.vertexUv[i][0], rec.vertexUv[i][1]};
    } else if (ext == "ply") {
        fail(path, "no per-vertex texture coordinates (u,v / s,t / texture_u,texture_v); libknit needs UVs");
    } else {
        fail(path, "no texture coordinates (an STOFF header with x y z u v per vertex); libknit needs UVs");
    }
    const std::vector<size_t>* faceLines = ext == "obj" ? &obj.faceLines : ext == "off" ? &offFaceLines : nullptr;
    if (faceLines && faceLines->size() != rec.n_faces()) faceLines = nullptr;
    BaseMesh mesh = buildMesh(path, rec, points, vertexUv, cornerUvs, faceLines, options);
    validateMesh(mesh);
    return mesh;
}

}  // namespace knit
