// mesh_ply.cpp — the PLY reader (ascii, binary little/big endian).
//
// OpenMesh 9.0's PLY reader crashes on some malformed headers, trusts list counts and turns a
// non-numeric ASCII token (e.g. "nan") into zeros and empty faces without reporting failure, so
// the file is walked here first (scanPly); only a file that passes is parsed by OpenMesh.
// OpenMesh's reader talks to a BaseImporter; it gets a *recording* importer instead of a
// halfedge mesh, which keeps the file's vertices and polygons exactly as read (a halfedge mesh
// would silently split "non-manifold" faces into duplicated vertices); topology is rebuilt by
// welding (buildPolygonMesh). OpenMesh prints its own warnings to std::cerr (omerr); the
// knit::Error thrown here is the authoritative result. Per-vertex u,v or s,t are read by OpenMesh as Options::VertexTexCoord;
// texture_u,texture_v / texture_s,texture_t are *not* known to OpenMesh 9.0 and are read as
// custom properties (Options::Custom) into the importer's property-only ArrayKernel. Positions
// and u,v come through OpenMesh as float32.
#include "mesh_reader.hpp"

#include <OpenMesh/Core/IO/Options.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/IO/reader/PLYReader.hh>
#include <OpenMesh/Core/Mesh/ArrayKernel.hh>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>

namespace knit::impl {
namespace {

// Recording importer: what OpenMesh's reader saw, without building halfedge topology.
class RecordingImporter final : public OpenMesh::IO::BaseImporter {
public:
    std::vector<OpenMesh::Vec3d> points;
    std::vector<OpenMesh::Vec2f> vertexUv;
    std::vector<char> vertexHasUv;
    Polygons polys;                     // faces as read (PLY texture coordinates are per vertex)
    OpenMesh::ArrayKernel customProps;  // PLY custom properties (texture_u, ...) land here

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
        for (const auto& vh : indices) polys.faceVerts.push_back(vh.idx());
        polys.faceStart.push_back(uint32_t(polys.faceVerts.size()));
        customProps.new_face();
        return OpenMesh::FaceHandle(int(polys.count() - 1));
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
    size_t n_faces() const override { return polys.count(); }
    size_t n_edges() const override { return 0; }

    // Everything below is information libknit does not use.
    OpenMesh::HalfedgeHandle add_edge(OpenMesh::VertexHandle, OpenMesh::VertexHandle) override {
        return OpenMesh::HalfedgeHandle();
    }
    OpenMesh::FaceHandle add_face(OpenMesh::HalfedgeHandle) override { return OpenMesh::FaceHandle(); }
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle,
                            const std::vector<OpenMesh::Vec2f>&) override {}  // PLY UVs are per vertex
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

// The reader singleton keeps per-file state: calls into it are serialized.
std::mutex& openMeshReaderMutex() {
    static std::mutex m;
    return m;
}

// The recorded positions, float32 as OpenMesh read them, in double.
std::vector<glm::dvec3> recordedPoints(const RecordingImporter& rec) {
    std::vector<glm::dvec3> points(rec.points.size());
    for (size_t i = 0; i < points.size(); ++i) points[i] = {rec.points[i][0], rec.points[i][1], rec.points[i][2]};
    return points;
}

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
                        failMesh(path, "file ends inside element '" + e.name + "' " + std::to_string(k) + " of " +
                                           std::to_string(e.count) + " (truncated?)");
                    ++lineNo;
                    std::istringstream ls(line);
                    double v;
                    while (ls >> tok) {
                        if (!parseFinite(tok, v)) failMeshLine(path, lineNo, "'" + tok + "' is not a finite number");
                        requireFloatRange(path, lineNo, tok, v);
                        values.push_back(v);
                    }
                }
                // Exactly the declared properties; list counts are non-negative integers.
                size_t at = 0;
                for (const PlyProperty& p : e.props) {
                    if (at >= values.size()) failMeshLine(path, lineNo, "too few values for element '" + e.name + "'");
                    if (p.list) {
                        const double n = values[at++];
                        if (n < 0 || n != std::floor(n) || n > double(values.size() - at))
                            failMeshLine(path, lineNo, "list '" + p.name + "' has a bad count");
                        at += size_t(n);
                    } else {
                        ++at;
                    }
                }
                if (at != values.size()) failMeshLine(path, lineNo, "too many values for element '" + e.name + "'");
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
                    failMesh(path, "file ends inside element '" + e.name + "' " + std::to_string(k) + " of " +
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
                    failMesh(path, "element '" + e.name + "' " + std::to_string(k) + ": list '" + p.name +
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
                failMesh(path, "binary PLY property '" + p.type + " " + p.name + "' of element '" + e.name +
                                   "' is not supported (its type must be " + need + ")");
        }
}

PlyHeader scanPly(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) failMesh(path, "cannot open for reading");
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
            if (word != "ply") failMesh(path, "not a PLY file (the first line is not 'ply')");
            continue;
        }
        if (word == "comment" || word == "obj_info" || word.empty()) continue;
        if (word == "format") {
            std::string fmt, version, extra;
            ls >> fmt >> version >> extra;
            double v = 0;
            if (fmt != "ascii" && fmt != "binary_little_endian" && fmt != "binary_big_endian")
                failMeshLine(path, lineNo, "unknown PLY format '" + fmt + "'");
            // PLY has only version 1.0; OpenMesh loops forever on other versions.
            if (!parseFinite(version, v) || v != 1.0 || !extra.empty())
                failMeshLine(path, lineNo, "the format line must be 'format " + fmt + " 1.0'");
            h.ascii = fmt == "ascii";
            h.bigEndian = fmt == "binary_big_endian";
            hasFormat = true;
        } else if (word == "element") {
            PlyElement e;
            std::string count, extra;
            ls >> e.name >> count >> extra;
            long n = 0;
            if (e.name.empty() || !(count == "0" || parseIndex(count, n)) || n < 0 || !extra.empty())
                failMeshLine(path, lineNo, "element line needs a name and a non-negative count");
            e.count = size_t(n);
            h.elements.push_back(e);
        } else if (word == "property") {
            if (h.elements.empty()) failMeshLine(path, lineNo, "property line before any element line");
            PlyProperty p;
            ls >> p.type;
            if (p.type == "list") {
                p.list = true;
                ls >> p.countType >> p.type;
                if (!plyTypeSize(p.countType) || plyFloatType(p.countType) || !plyTypeSize(p.type))
                    failMeshLine(path, lineNo, "bad list property types '" + p.countType + " " + p.type + "'");
            } else if (!plyTypeSize(p.type)) {
                failMeshLine(path, lineNo, "unknown property type '" + p.type + "'");
            }
            std::string extra;
            ls >> p.name >> extra;
            if (p.name.empty() || !extra.empty())
                failMeshLine(path, lineNo, "a property line must be 'property TYPE NAME'");
            h.elements.back().props.push_back(p);
        } else if (word == "end_header" && trimmed(line) == "end_header") {
            ended = true;
        } else {
            failMeshLine(path, lineNo, "unexpected PLY header line '" + trimmed(line) + "'");
        }
    }
    if (!ended) failMesh(path, "PLY header has no end_header line");
    if (!hasFormat) failMesh(path, "PLY header has no format line");
    // The vertex element needs x, y, z; the face element a vertex index list.
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    for (const PlyElement& e : h.elements) {
        if (e.name == "vertex") vertex = &e;
        if (e.name == "face") face = &e;
    }
    if (!vertex) failMesh(path, "the PLY file has no vertex element");
    if (!face || face->count == 0) failMesh(path, "the mesh has no faces");
    auto has = [&](const char* n) {
        return std::any_of(vertex->props.begin(), vertex->props.end(),
                           [&](const PlyProperty& p) { return !p.list && p.name == n; });
    };
    if (!has("x") || !has("y") || !has("z")) failMesh(path, "the PLY vertex element needs x, y and z properties");
    if (!std::any_of(face->props.begin(), face->props.end(), [](const PlyProperty& p) {
            return p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
        }))
        failMesh(path, "the PLY face element has no vertex_indices list");
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

}  // namespace

BaseMesh readPlyMesh(const std::string& path, const MeshLoadOptions& options) {
    const PlyHeader ply = scanPly(path);
    RecordingImporter rec;
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexTexCoord;
    if (ply.hasTextureUV) opt += OpenMesh::IO::Options::Custom;
    bool ok = false;
    {
        std::lock_guard<std::mutex> lock(openMeshReaderMutex());
        ok = OpenMesh::IO::PLYReader().read(path, rec, opt);
    }
    if (!ok) failMesh(path, "OpenMesh could not parse the file (malformed or truncated)");
    const size_t nv = rec.points.size();
    // UVs per vertex: a custom property (texture_u, ...) or OpenMesh's u,v / s,t.
    std::vector<glm::dvec2> vertexUv;
    if (ply.hasTextureUV) {
        std::vector<double> u, v;
        if (!customVertexScalar(rec.customProps, ply.textureU, nv, u) ||
            !customVertexScalar(rec.customProps, ply.textureV, nv, v))
            failMesh(path, "could not read vertex properties " + ply.textureU + "/" + ply.textureV);
        vertexUv.resize(nv);
        for (size_t i = 0; i < nv; ++i) vertexUv[i] = {u[i], v[i]};
    } else if (opt.check(OpenMesh::IO::Options::VertexTexCoord)) {
        vertexUv.resize(nv);
        for (size_t i = 0; i < nv; ++i) vertexUv[i] = {rec.vertexUv[i][0], rec.vertexUv[i][1]};
    } else {
        failMesh(path, "no per-vertex texture coordinates (u,v / s,t / texture_u,texture_v); libknit needs UVs");
    }
    return buildPolygonMesh(path, rec.polys, recordedPoints(rec), vertexUv, false, nullptr, options);
}

}  // namespace knit::impl
