// mesh_gltf.cpp — glTF 2.0 base meshes (.gltf / .glb): a gltf::Document (gltf_document.hpp,
// the project's one glTF reader: container, buffers, accessors, node tree, all ranges checked)
// turned into a BaseMesh.
//
// Why not tinygltf's loader: Debian's libdraco.so.7 (1.5.5) exports its own copy of an older
// tinygltf, with default visibility. Its TinyGLTF::LoadASCIIFromFile, LoadBinaryFromFile etc.
// have the same mangled names as libtinygltf.so.2d (2.7.0)'s, and the dynamic linker binds each
// call to the first library in the process's lookup order (the executable's DT_NEEDED entries,
// in link order) that defines it. `knit` and knit_export_tests list libtinygltf before libdraco
// (exporters/CMakeLists.txt links TinyGLTF::TinyGLTF before draco::draco), so there the loader
// reaches tinygltf 2.7 and works; that is why the export tests could read their files with it.
// Link libdraco first and the same calls land in Draco's copy, compiled for another class
// layout: every file fails ("one or more FS callback not set"; checked with nm, LD_DEBUG=bindings
// and a small program linked both ways) or, as reported when this reader was written, crashes
// (free() of an invalid pointer). The exporters' writer is not affected: 2.7's
// WriteGltfSceneToStream takes a const Model*, a name only libtinygltf has. Working by link
// order is fragile, and the part of glTF a base mesh needs is small, so the library reads glTF
// itself (and links neither tinygltf nor Draco).
//
// What is read:
//  * The mesh instances of the default scene (gltf::Document::forEachMeshInstance), each with its
//    node's world transform applied to POSITION; a mirroring transform (negative determinant)
//    reverses the triangles' winding, as glTF specifies. Instancing can multiply a small file:
//    more than MeshLoadOptions::maxElements vertices or triangles in total are refused, and the
//    memory of the expanded elements is estimated from the accessor counts before any is
//    expanded and checked against MeshLoadOptions::budget.
//  * TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (strips and fans are unrolled;
//    triangles with a repeated index, e.g. strip restarts, are skipped). POINTS and LINES
//    primitives are not surfaces and are ignored; a file without any triangle is an error.
//  * POSITION (float, or the integer types of KHR_mesh_quantization) and TEXCOORD_0 (float, or
//    normalized unsigned byte / short) are required; indices are optional (u8 / u16 / u32).
//  * UV convention: glTF puts the texture origin at the top-left corner (v down), libknit like
//    OBJ at the bottom-left, so v is flipped: uv = (u, 1 - v). The same asset exported as OBJ
//    and as glTF gets the same knit.
//  * Vertices are welded by exact position like the other formats (glTF duplicates vertices at
//    UV seams), so normals and yarn welding see one 3D topology.
//  * Buffers as gltf::Document reads them: only buffers the mesh needs are read (never images).
//  * Refused with knit::Error naming the element: KHR_draco_mesh_compression primitives, sparse
//    accessors, accessors without data, out-of-range indices, accessor or buffer-view ranges
//    outside their buffer, non-finite values, malformed JSON or GLB.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "io/gltf_document.hpp"
#include "mesh_gltf.hpp"
#include "mesh_weld.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace knit {
namespace {

// The triangle soup of the default scene's surfaces, in world space, ready for welding.
class TriangleCollector {
public:
    TriangleCollector(const gltf::Document& doc, uint64_t maxElements, const impl::GltfPoser* poser)
        : doc_(doc), maxElements_(maxElements), poser_(poser) {}

    // Step 1: every triangle primitive of every mesh instance (other modes are not surfaces).
    void add(const gltf::MeshInstance& instance) {
        doc_.forEachPrimitive(instance.mesh, [&](const gltf::Primitive& p) {
            if (p.mode != gltf::kTriangles && p.mode != gltf::kTriangleStrip && p.mode != gltf::kTriangleFan) return;
            addPrimitive(p, instance);
        });
    }

    // Step 2: weld into a BaseMesh.
    BaseMesh weld(const MeshLoadOptions& options) const {
        if (faceStart_.size() == 1)
            doc_.fail("no triangle primitives in the default scene (libknit needs a triangle mesh)");
        BaseMesh mesh = impl::weldPolygons(
            doc_.name(), points_, faceStart_, faceVerts_, [&](uint32_t c) { return uvs_[size_t(faceVerts_[c])]; },
            options);
        validateMesh(mesh);
        return mesh;
    }

private:
    void addPrimitive(const gltf::Primitive& p, const gltf::MeshInstance& instance) {
        const glm::dmat4& world = instance.world;
        if (doc_.extensions(p).contains("KHR_draco_mesh_compression"))
            doc_.fail(p.what + " is Draco-compressed (KHR_draco_mesh_compression), which cannot be read here; "
                               "export the base mesh without Draco");
        const std::optional<size_t> pos = doc_.attribute(p, "POSITION");
        if (!pos) doc_.fail(p.what + " has no POSITION");
        const std::optional<size_t> tex = doc_.attribute(p, "TEXCOORD_0");
        if (!tex) doc_.fail(p.what + " has no TEXCOORD_0 (libknit needs UVs)");
        const gltf::Accessor P = doc_.accessor(*pos, p.what + " POSITION");
        const gltf::Accessor T = doc_.accessor(*tex, p.what + " TEXCOORD_0");
        if (P.components != 3) doc_.fail(p.what + ": POSITION is not VEC3");
        if (T.components != 2) doc_.fail(p.what + ": TEXCOORD_0 is not VEC2");
        if (T.count != P.count)
            doc_.fail(p.what + ": TEXCOORD_0 has " + std::to_string(T.count) + " elements, POSITION " +
                      std::to_string(P.count));
        const size_t first = points_.size();
        addVertices(p, P, T, world, poser_ ? (*poser_)(instance, p, P) : std::vector<glm::dvec3>());
        const std::optional<size_t> indices = doc_.indices(p);
        addTriangles(p, vertexIndices(p, indices, P.count), indices.has_value(), first, world);
    }

    // World positions in double (`posed`, when given, replaces world * POSITION), v flipped
    // (glTF's texture origin is top-left).
    void addVertices(const gltf::Primitive& p, const gltf::Accessor& P, const gltf::Accessor& T,
                     const glm::dmat4& world, const std::vector<glm::dvec3>& posed) {
        if (points_.size() + P.count > std::min<uint64_t>(maxElements_, uint64_t(std::numeric_limits<int>::max())))
            doc_.fail("more than " + std::to_string(maxElements_) +
                      " vertices once its nodes' instances are placed; the file is refused "
                      "before they are generated");
        for (size_t i = 0; i < P.count; ++i) {
            const glm::dvec4 x = posed.empty() ? world * glm::dvec4(P.get(i, 0), P.get(i, 1), P.get(i, 2), 1.0)
                                               : glm::dvec4(posed[i], 1.0);
            const glm::dvec2 uv(T.get(i, 0), 1.0 - T.get(i, 1));
            if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
                doc_.fail(p.what + ": vertex " + std::to_string(i) + " has a non-finite position");
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
                doc_.fail(p.what + ": vertex " + std::to_string(i) + " has a non-finite TEXCOORD_0");
            points_.emplace_back(x);
            uvs_.push_back(uv);
        }
    }

    // The primitive's indices (checked against its vertex count), or 0..vertices-1.
    std::vector<uint32_t> vertexIndices(const gltf::Primitive& p, const std::optional<size_t>& indices,
                                        size_t vertices) const {
        std::vector<uint32_t> idx;
        if (!indices) {
            idx.resize(vertices);
            for (size_t i = 0; i < vertices; ++i) idx[i] = uint32_t(i);
            return idx;
        }
        const gltf::Accessor I = doc_.accessor(*indices, p.what + " indices");
        // glTF 2.0 (3.7.2.1): never normalized; a normalized accessor would read every index as
        // a fraction (0 .. 1) of the type's range, not as a vertex number.
        if (I.components != 1 || I.normalized ||
            (I.componentType != gltf::kUnsignedByte && I.componentType != gltf::kUnsignedShort &&
             I.componentType != gltf::kUnsignedInt))
            doc_.fail(p.what + ": indices must be unsigned byte, short or int scalars, not normalized");
        idx.resize(I.count);
        for (size_t i = 0; i < I.count; ++i) {
            const double v = I.get(i, 0);
            if (v >= double(vertices))
                doc_.fail(p.what + ": index " + std::to_string(i) + " is " + std::to_string(uint64_t(v)) +
                          " but there are " + std::to_string(vertices) + " vertices");
            idx[i] = uint32_t(v);
        }
        return idx;
    }

    // Triangles by mode; strips and fans unrolled, degenerate ones (strip restarts) skipped.
    void addTriangles(const gltf::Primitive& p, const std::vector<uint32_t>& idx, bool indexed, size_t first,
                      const glm::dmat4& world) {
        // A mirroring world transform turns the winding around (glTF: det < 0 reverses it).
        const bool mirrored = glm::determinant(glm::dmat3(world)) < 0;
        auto triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
            if (a == b || b == c || a == c) return;  // degenerate (strip restart)
            if (mirrored) std::swap(b, c);
            for (uint32_t v : {a, b, c}) faceVerts_.push_back(int(first + v));
            faceStart_.push_back(uint32_t(faceVerts_.size()));
        };
        const size_t triangles = p.mode == gltf::kTriangles ? idx.size() / 3 : (idx.size() >= 3 ? idx.size() - 2 : 0);
        if (faceStart_.size() - 1 + triangles > maxElements_)
            doc_.fail("more than " + std::to_string(maxElements_) +
                      " triangles once its nodes' instances are placed; the file is refused "
                      "before they are generated");
        if (p.mode == gltf::kTriangles) {
            if (idx.size() % 3 != 0)
                doc_.fail(p.what + ": " + std::to_string(idx.size()) + (indexed ? " indices" : " vertices") +
                          " do not make whole triangles");
            for (size_t i = 0; i + 3 <= idx.size(); i += 3) triangle(idx[i], idx[i + 1], idx[i + 2]);
        } else if (p.mode == gltf::kTriangleStrip) {
            for (size_t i = 0; i + 2 < idx.size(); ++i)
                i % 2 == 0 ? triangle(idx[i], idx[i + 1], idx[i + 2]) : triangle(idx[i + 1], idx[i], idx[i + 2]);
        } else {
            for (size_t i = 1; i + 1 < idx.size(); ++i) triangle(idx[0], idx[i], idx[i + 1]);
        }
    }

    const gltf::Document& doc_;
    uint64_t maxElements_;
    const impl::GltfPoser* poser_;
    std::vector<glm::dvec3> points_;
    std::vector<glm::dvec2> uvs_;
    std::vector<uint32_t> faceStart_{0};
    std::vector<int> faceVerts_;
};

// Bytes per expanded element while collecting and welding (world positions and UVs, the weld's
// keys; indices, face lists and the welded faces); generous like the scene estimates.
constexpr double kBytesPerExpandedVertex = 96;
constexpr double kBytesPerExpandedIndex = 24;

// The vertices and indices one triangle primitive expands to, or nothing when it cannot be read
// (no POSITION or TEXCOORD_0, Draco, a bad accessor): the collector then reports it in its order.
std::optional<std::pair<double, double>> expandedCounts(const gltf::Document& doc, const gltf::Primitive& p) {
    if (p.mode != gltf::kTriangles && p.mode != gltf::kTriangleStrip && p.mode != gltf::kTriangleFan) return {};
    const std::optional<size_t> pos = doc.attribute(p, "POSITION");
    if (!pos || !doc.attribute(p, "TEXCOORD_0") || doc.extensions(p).contains("KHR_draco_mesh_compression")) return {};
    try {
        const double n = double(doc.accessor(*pos, p.what + " POSITION").count);
        const std::optional<size_t> idx = doc.indices(p);
        return std::make_pair(n, idx ? double(doc.accessor(*idx, p.what + " indices").count) : n);
    } catch (const Error&) {
        return {};
    }
}

// Before anything is expanded: the vertices and indices of every triangle primitive of every
// instance (one big accessor reused by many primitives or nodes counts each time), against the
// budget.
void checkExpansionBudget(const gltf::Document& doc, const MemoryBudget& budget) {
    double vertices = 0, indices = 0, instances = 0;
    doc.forEachMeshInstance([&](const gltf::MeshInstance& instance) {
        doc.forEachPrimitive(instance.mesh, [&](const gltf::Primitive& p) {
            if (const auto counts = expandedCounts(doc, p)) {
                vertices += counts->first;
                indices += counts->second;
                instances += 1;
            }
        });
    });
    std::ostringstream what;
    what.precision(3);
    what << vertices << " vertices and " << indices << " indices of " << instances << " primitive instances in '"
         << doc.name() << "'";
    budget.require(vertices * kBytesPerExpandedVertex + indices * kBytesPerExpandedIndex, what.str(),
                   "the instancing of the mesh file (its nodes and primitives reusing accessors)");
}

}  // namespace

BaseMesh impl::gltfMeshOf(const gltf::Document& doc, const MeshLoadOptions& options, const GltfPoser* poser) {
    // meshopt-compressed buffer views cannot be read: say so, rather than report their
    // fallback buffer (which has no data) as missing.
    for (const std::string& e : doc.extensionsUsed())
        if (e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
            doc.fail(e + " is not supported (compressed buffer views); export the base mesh uncompressed");
    checkExpansionBudget(doc, options.budget);
    TriangleCollector triangles(doc, options.maxElements, poser);
    doc.forEachMeshInstance([&](const gltf::MeshInstance& instance) { triangles.add(instance); });
    return triangles.weld(options);
}

BaseMesh parseGltfMesh(const std::string& bytes, const std::string& name, const std::string& baseDir,
                       const MeshLoadOptions& options) {
    return impl::gltfMeshOf(gltf::Document(bytes, name, baseDir), options);
}

BaseMesh loadGltfMesh(const std::string& path, const MeshLoadOptions& options) {
    return impl::gltfMeshOf(gltf::Document::load(path), options);
}

}  // namespace knit
