// gltf_document.hpp — the one glTF 2.0 reader of the project (internal, not installed): parses a
// .gltf / .glb container and decodes what its accessors point at, checking every range first.
//
// Used by the base-mesh reader (mesh_gltf.cpp), by the tests that read exports back and by the
// speed-vs-error tool. It reads the structure glTF has, not a model of it: the JSON document
// stays available as it is (root()), and the reader adds what JSON alone cannot give safely:
//  * Container: GLB (12-byte header, a JSON chunk, optionally a BIN chunk; sizes checked against
//    the file) or plain JSON; asset.version must be "2.x".
//  * Buffers, read on first use: the GLB BIN chunk, base64 `data:` URIs, or files given by
//    relative URIs (percent-decoded) read as regular files relative to `baseDir` (their first
//    byteLength bytes; absolute paths and other schemes are refused, and any file when parsed
//    from memory). Buffer views are checked to lie inside their buffer.
//  * Accessors: every component type (normalized integers mapped as the glTF spec says), byte
//    stride, byte offsets and counts checked against the view without overflow; sparse
//    accessors and accessors without a bufferView (e.g. the ones Draco replaces) are refused.
//  * The node tree of the default scene (scene 0 when none is set; every mesh once, untransformed,
//    when the file has no scenes), walked without recursion, so deep chains are fine: a node
//    reached twice (a cycle, or two parents) is an error. World transforms are composed in
//    double from matrix or translation * rotation * scale.
//  * Primitives in file order, with their mode, attributes, indices and extensions.
// Every error is a knit::Error "<name>: <what>", naming the element (e.g. "accessors[3]").
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

namespace knit::gltf {

// glTF 2.0 component types and primitive modes.
constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kPoints = 0, kLines = 1, kLineLoop = 2, kLineStrip = 3, kTriangles = 4, kTriangleStrip = 5,
              kTriangleFan = 6;

// Bytes of one component (0 for an unknown type) and components of an accessor type ("VEC3": 3).
int componentBytes(int componentType);
int componentsOf(const std::string& type);

// A checked view of one accessor's elements (valid while its Document lives).
struct Accessor {
    const unsigned char* base = nullptr;
    size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;

    // Component k of element i as a double (normalized integers mapped as the glTF spec says).
    double get(size_t i, int k) const;
    // All count x components values, element by element.
    std::vector<double> values() const;
};

// A checked byte range inside a buffer (valid while its Document lives).
struct Bytes {
    const unsigned char* data = nullptr;
    size_t size = 0;
};

// What the GLB header and chunk headers say (all zero for a plain JSON file).
struct GlbLayout {
    bool glb = false;
    uint32_t length = 0, jsonLength = 0;  // header's total length, JSON chunk length
    bool secondChunk = false;             // a chunk header follows the JSON chunk
    uint32_t secondType = 0, secondLength = 0;
};

// One mesh of the default scene with the world transform of the node that holds it.
struct MeshInstance {
    size_t mesh = 0;
    size_t node = kNoNode;  // kNoNode when the file has no scenes
    glm::dmat4 world{1.0};
    static constexpr size_t kNoNode = size_t(-1);
};

// One primitive of a mesh. `what` names it in messages ("mesh 2 ('sleeve') primitive 0").
struct Primitive {
    const nlohmann::json* object = nullptr;
    std::string what;
    size_t index = 0;
    size_t mode = kTriangles;
};

class Document {
public:
    // `name` prefixes every message; external buffers are read relative to `baseDir` (none when
    // it is empty: parsed from memory). Throws knit::Error on a malformed container or JSON.
    Document(const std::string& bytes, std::string name, std::string baseDir);
    // Reads the file at `path` (its folder is the base folder).
    static Document load(const std::string& path);

    const std::string& name() const { return name_; }
    const nlohmann::json& root() const { return doc_; }
    const GlbLayout& glbLayout() const { return glb_; }
    [[noreturn]] void fail(const std::string& what) const;

    // ---- JSON access with messages naming the element ----
    // obj[key] when present (it must have `type`), else an empty value of that type.
    const nlohmann::json& member(const nlohmann::json& obj, const char* key, nlohmann::json::value_t type,
                                 const std::string& where) const;
    size_t asIndex(const nlohmann::json& v, const std::string& where) const;
    std::optional<size_t> index(const nlohmann::json& obj, const char* key, const std::string& where) const;
    // The object root()[array][i]; `what` names its use in the message when it does not exist.
    const nlohmann::json& element(const char* array, size_t i, const std::string& what) const;
    // obj[key] as exactly n finite numbers within the float32 range (empty when absent).
    std::vector<double> numbers(const nlohmann::json& obj, const char* key, size_t n, const std::string& where) const;
    // The names listed in extensionsUsed / extensionsRequired.
    std::vector<std::string> extensionsUsed() const;
    std::vector<std::string> extensionsRequired() const;

    // ---- data (`what` names the use in messages) ----
    size_t bufferCount() const;
    const std::vector<unsigned char>& buffer(size_t i, const std::string& what) const;
    Bytes bufferView(size_t i, const std::string& what) const;
    Accessor accessor(size_t i, const std::string& what) const;

    // ---- scene ----
    // The mesh instances of the default scene, depth-first in file order (see the file comment).
    void forEachMeshInstance(const std::function<void(const MeshInstance&)>& visit) const;
    std::vector<MeshInstance> meshInstances() const;
    glm::dmat4 localTransform(size_t node) const;
    void requireFloatWorld(const glm::dmat4& world, size_t node) const;
    std::string nodeName(size_t node) const;  // "nodes[3] ('sleeve')" for messages
    // The primitives of mesh `mesh`, in order.
    void forEachPrimitive(size_t mesh, const std::function<void(const Primitive&)>& visit) const;
    std::vector<Primitive> primitives(size_t mesh) const;
    std::optional<size_t> attribute(const Primitive& p, const char* name) const;
    std::optional<size_t> indices(const Primitive& p) const;
    const nlohmann::json& extensions(const Primitive& p) const;

private:
    void parseContainer(const std::string& bytes);
    std::vector<unsigned char> externalFile(const std::string& uri, const std::string& where, size_t length) const;
    std::vector<std::string> names(const char* key) const;
    void visitTree(size_t root, std::vector<char>& reached,
                   const std::function<void(const MeshInstance&)>& visit) const;

    std::string name_, baseDir_;
    nlohmann::json doc_;
    GlbLayout glb_;
    mutable std::optional<std::vector<unsigned char>> glbBin_;      // until buffer 0 takes it
    mutable std::map<size_t, std::vector<unsigned char>> buffers_;  // read on first use
};

}  // namespace knit::gltf
