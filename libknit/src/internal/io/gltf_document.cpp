// gltf_document.cpp — glTF 2.0 container, buffers, accessors and node tree (see gltf_document.hpp).
#include "gltf_document.hpp"

#include "knit/error.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace knit::gltf {
namespace {

namespace fs = std::filesystem;

// A number as a message shows it ("1e+39").
std::string numberText(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}
using nlohmann::json;

constexpr uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

std::optional<std::vector<unsigned char>> decodeBase64(const std::string& s, size_t from) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+' || c == '-') return 62;
        if (c == '/' || c == '_') return 63;
        return -1;
    };
    std::vector<unsigned char> out;
    out.reserve((s.size() - from) / 4 * 3);
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = from; i < s.size(); ++i) {
        if (s[i] == '=') break;
        const int v = value(s[i]);
        if (v < 0) return std::nullopt;
        acc = (acc << 6) | uint32_t(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(uint8_t(acc >> bits));
        }
    }
    return out;
}

std::string percentDecode(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(uint8_t(s[i + 1])) && std::isxdigit(uint8_t(s[i + 2]))) {
            out.push_back(char(std::stoi(s.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(s[i]);
        }
    }
    return out;
}

}  // namespace

int componentBytes(int type) {
    switch (type) {
        case kByte:
        case kUnsignedByte: return 1;
        case kShort:
        case kUnsignedShort: return 2;
        case kUnsignedInt:
        case kFloat: return 4;
        default: return 0;
    }
}

int componentsOf(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4" || type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    return 0;
}

double Accessor::get(size_t i, int k) const {
    const unsigned char* p = base + i * stride + size_t(k) * size_t(componentBytes(componentType));
    switch (componentType) {
        case kFloat: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case kUnsignedByte: return normalized ? p[0] / 255.0 : p[0];
        case kByte: {
            const double v = double(int8_t(p[0]));
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case kUnsignedShort: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case kShort: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : double(v);
        }
        case kUnsignedInt: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        default: return 0.0;
    }
}

std::vector<double> Accessor::values() const {
    std::vector<double> out(count * size_t(components));
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < components; ++k) out[i * size_t(components) + size_t(k)] = get(i, k);
    return out;
}

// ---- container ---------------------------------------------------------------------------------

Document::Document(const std::string& bytes, std::string name, std::string baseDir)
    : name_(std::move(name)), baseDir_(std::move(baseDir)) {
    parseContainer(bytes);
}

Document Document::load(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw Error(path + ": no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open for reading");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const fs::path folder = fs::path(path).parent_path();
    return Document(bytes, path, folder.empty() ? std::string(".") : folder.string());
}

void Document::fail(const std::string& what) const { throw Error(name_ + ": " + what); }

void Document::parseContainer(const std::string& bytes) {
    std::string text = bytes;
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
        // GLB: 12-byte header, a JSON chunk, optionally a BIN chunk.
        auto u32 = [&](size_t at) {
            uint32_t v;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        if (bytes.size() < 20) fail("truncated GLB header");
        if (u32(4) != 2) fail("GLB version " + std::to_string(u32(4)) + " (only glTF 2.0 is read)");
        const size_t total = u32(8);
        if (total > bytes.size())
            fail("truncated GLB: the header says " + std::to_string(total) + " bytes, the file has " +
                 std::to_string(bytes.size()));
        const size_t jsonLength = u32(12);
        if (u32(16) != kJsonChunk) fail("the first GLB chunk is not JSON");
        if (jsonLength > total - 20) fail("the GLB JSON chunk runs past the end of the file");
        glb_ = {true, uint32_t(total), uint32_t(jsonLength), false, 0, 0};
        text = bytes.substr(20, jsonLength);
        const size_t next = 20 + (jsonLength + 3) / 4 * 4;
        if (next + 8 <= total) glb_ = {true, uint32_t(total), uint32_t(jsonLength), true, u32(next + 4), u32(next)};
        if (next + 8 <= total && u32(next + 4) == kBinChunk) {
            const size_t binLength = u32(next);
            if (binLength > total - next - 8) fail("the GLB BIN chunk runs past the end of the file");
            glbBin_.emplace(bytes.begin() + std::ptrdiff_t(next + 8),
                            bytes.begin() + std::ptrdiff_t(next + 8 + binLength));
        }
    }
    try {
        doc_ = json::parse(text);
    } catch (const json::exception& e) {
        fail(std::string("not valid glTF JSON: ") + e.what());
    }
    if (!doc_.is_object()) fail("not valid glTF JSON: the document is not an object");
    const json& asset = member(doc_, "asset", json::value_t::object, "the document");
    const json* version = asset.contains("version") ? &asset["version"] : nullptr;
    if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0)
        fail("asset.version must be \"2.x\" (only glTF 2.0 is read)");
}

// ---- JSON access -------------------------------------------------------------------------------

const json& Document::member(const json& obj, const char* key, json::value_t type, const std::string& where) const {
    static const json emptyArray = json::array(), emptyObject = json::object();
    if (obj.is_object() && obj.contains(key)) {
        const json& v = obj[key];
        if (v.type() != type) fail(where + "." + key + " has the wrong JSON type");
        return v;
    }
    return type == json::value_t::array ? emptyArray : emptyObject;
}

size_t Document::asIndex(const json& v, const std::string& where) const {
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
        fail(where + " must be a non-negative integer");
    return v.get<size_t>();
}

std::optional<size_t> Document::index(const json& obj, const char* key, const std::string& where) const {
    if (!obj.is_object() || !obj.contains(key)) return std::nullopt;
    return asIndex(obj[key], where + "." + key);
}

const json& Document::element(const char* array, size_t i, const std::string& what) const {
    const json& a = member(doc_, array, json::value_t::array, "the document");
    if (i >= a.size() || !a[i].is_object()) fail(what + ": " + array + "[" + std::to_string(i) + "] does not exist");
    return a[i];
}

std::vector<double> Document::numbers(const json& obj, const char* key, size_t n, const std::string& where) const {
    if (!obj.contains(key)) return {};
    const json& v = obj[key];
    if (!v.is_array() || v.size() != n)
        fail(where + "." + key + " must be an array of " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const json& x : v) {
        if (!x.is_number()) fail(where + "." + key + " must be an array of " + std::to_string(n) + " numbers");
        out.push_back(x.get<double>());
        if (!std::isfinite(out.back())) fail(where + "." + key + " is not finite");
        if (std::abs(out.back()) > double(std::numeric_limits<float>::max()))
            fail(where + "." + key + " holds " + numberText(out.back()) +
                 ", beyond the float32 range (3.4e38) of glTF numbers");
    }
    return out;
}

std::vector<std::string> Document::names(const char* key) const {
    std::vector<std::string> out;
    for (const json& v : member(doc_, key, json::value_t::array, "the document")) {
        if (!v.is_string()) fail(std::string("the document.") + key + " must hold strings");
        out.push_back(v.get<std::string>());
    }
    return out;
}

std::vector<std::string> Document::extensionsUsed() const { return names("extensionsUsed"); }
std::vector<std::string> Document::extensionsRequired() const { return names("extensionsRequired"); }

// ---- buffers, views, accessors -----------------------------------------------------------------

size_t Document::bufferCount() const { return member(doc_, "buffers", json::value_t::array, "the document").size(); }

const std::vector<unsigned char>& Document::buffer(size_t i, const std::string& what) const {
    if (auto it = buffers_.find(i); it != buffers_.end()) return it->second;
    const json& b = element("buffers", i, what);
    const std::string where = "buffers[" + std::to_string(i) + "]";
    const size_t length = index(b, "byteLength", where).value_or(0);
    std::vector<unsigned char> data;
    if (!b.contains("uri")) {
        if (i != 0 || !glbBin_) fail(where + " has no uri and there is no GLB BIN chunk");
        if (glbBin_->size() >= length) data = std::move(*glbBin_);  // only buffer 0 uses it: no copy
        else data = *glbBin_;
    } else {
        if (!b["uri"].is_string()) fail(where + ".uri must be a string");
        const std::string uri = b["uri"].get<std::string>();
        if (uri.rfind("data:", 0) == 0) {
            const size_t comma = uri.find(',');
            if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
                fail(where + ": only base64 data URIs are read");
            auto decoded = decodeBase64(uri, comma + 1);
            if (!decoded) fail(where + ": malformed base64 data URI");
            data = std::move(*decoded);
        } else {
            data = externalFile(percentDecode(uri), where, length);
        }
    }
    if (data.size() < length)
        fail(where + " has " + std::to_string(data.size()) + " bytes, less than its byteLength " +
             std::to_string(length));
    data.resize(length);
    return buffers_.emplace(i, std::move(data)).first->second;
}

// The first `length` bytes of an external file (its size is checked first).
std::vector<unsigned char> Document::externalFile(const std::string& uri, const std::string& where,
                                                  size_t length) const {
    if (baseDir_.empty()) fail(where + ": external file '" + uri + "' not allowed here (parsed from memory)");
    if (uri.empty() || uri.find(':') != std::string::npos || fs::path(uri).is_absolute())
        fail(where + ": uri '" + uri + "' is not a relative file path");
    const fs::path path = fs::path(baseDir_) / uri;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) fail(where + ": '" + path.string() + "' is not a readable file");
    const uintmax_t size = fs::file_size(path, ec);
    if (ec || size < length)
        fail(where + ": '" + path.string() + "' has " + std::to_string(ec ? 0 : size) +
             " bytes, less than the buffer's byteLength " + std::to_string(length));
    std::vector<unsigned char> data(length);
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(data.data()), std::streamsize(length)))
        fail(where + ": cannot read '" + path.string() + "'");
    return data;
}

Bytes Document::bufferView(size_t i, const std::string& what) const {
    const json& v = element("bufferViews", i, what);
    const std::string where = "bufferViews[" + std::to_string(i) + "]";
    const std::optional<size_t> bufferIndex = index(v, "buffer", where);
    if (!bufferIndex) fail(what + ": " + where + " has no buffer");
    const std::vector<unsigned char>& data = buffer(*bufferIndex, what);
    const size_t offset = index(v, "byteOffset", where).value_or(0);
    const size_t length = index(v, "byteLength", where).value_or(0);
    if (offset > data.size() || length > data.size() - offset) fail(what + ": " + where + " lies outside its buffer");
    return {data.data() + offset, length};
}

Accessor Document::accessor(size_t i, const std::string& what) const {
    const json& a = element("accessors", i, what);
    const std::string where = "accessors[" + std::to_string(i) + "]";
    if (a.contains("sparse")) fail(what + ": sparse accessors are not supported");
    const std::optional<size_t> viewIndex = index(a, "bufferView", where);
    if (!viewIndex) fail(what + ": " + where + " has no data (no bufferView)");
    const json& v = element("bufferViews", *viewIndex, what);
    const std::string vWhere = "bufferViews[" + std::to_string(*viewIndex) + "]";
    const std::optional<size_t> bufferIndex = index(v, "buffer", vWhere);
    if (!bufferIndex) fail(what + ": " + vWhere + " has no buffer");
    const std::vector<unsigned char>& data = buffer(*bufferIndex, what);
    Accessor d;
    d.componentType = int(index(a, "componentType", where).value_or(0));
    if (!a.contains("type") || !a["type"].is_string()) fail(what + ": " + where + " has no type");
    d.components = componentsOf(a["type"].get<std::string>());
    d.normalized = a.contains("normalized") && a["normalized"].is_boolean() && a["normalized"].get<bool>();
    d.count = index(a, "count", where).value_or(0);
    const int cb = componentBytes(d.componentType);
    if (cb == 0 || d.components == 0) fail(what + ": " + where + " has an unknown component type or type");
    const size_t elementSize = size_t(cb) * size_t(d.components);
    const size_t viewOffset = index(v, "byteOffset", vWhere).value_or(0);
    const size_t viewLength = index(v, "byteLength", vWhere).value_or(0);
    d.stride = index(v, "byteStride", vWhere).value_or(0);
    if (d.stride == 0) d.stride = elementSize;
    if (d.stride < elementSize) fail(what + ": " + vWhere + " has a byteStride below the element size");
    if (viewOffset > data.size() || viewLength > data.size() - viewOffset)
        fail(what + ": " + vWhere + " lies outside its buffer");
    const size_t offset = index(a, "byteOffset", where).value_or(0);
    if (d.count > 0 && (offset > viewLength || elementSize > viewLength - offset ||
                        (d.count - 1) > (viewLength - offset - elementSize) / d.stride))
        fail(what + ": " + where + " (" + std::to_string(d.count) + " elements) reaches past the end of " + vWhere);
    d.base = data.data() + viewOffset + offset;
    return d;
}

// ---- scene graph and primitives ----------------------------------------------------------------

void Document::forEachMeshInstance(const std::function<void(const MeshInstance&)>& visit) const {
    const json& scenes = member(doc_, "scenes", json::value_t::array, "the document");
    if (scenes.empty()) {
        const size_t meshes = member(doc_, "meshes", json::value_t::array, "the document").size();
        for (size_t k = 0; k < meshes; ++k) visit(MeshInstance{k, MeshInstance::kNoNode, glm::dmat4(1.0)});
        return;
    }
    const size_t s = index(doc_, "scene", "the document").value_or(0);
    if (s >= scenes.size()) fail("scene " + std::to_string(s) + " does not exist");
    const json& roots = member(scenes[s], "nodes", json::value_t::array, "scenes[" + std::to_string(s) + "]");
    std::vector<char> reached(member(doc_, "nodes", json::value_t::array, "the document").size(), 0);
    for (const json& root : roots) visitTree(asIndex(root, "scenes[" + std::to_string(s) + "].nodes"), reached, visit);
}

std::vector<MeshInstance> Document::meshInstances() const {
    std::vector<MeshInstance> out;
    forEachMeshInstance([&](const MeshInstance& m) { out.push_back(m); });
    return out;
}

// Depth-first over the node tree from `root`, with an explicit stack (deep chains are fine).
void Document::visitTree(size_t root, std::vector<char>& reached,
                         const std::function<void(const MeshInstance&)>& visit) const {
    std::vector<std::pair<size_t, glm::dmat4>> stack{{root, glm::dmat4(1.0)}};
    while (!stack.empty()) {
        const auto [i, parent] = stack.back();
        stack.pop_back();
        const json& n = element("nodes", i, "the scene");
        if (reached[i]) fail("node " + std::to_string(i) + " is reached twice (glTF nodes must form a tree)");
        reached[i] = 1;
        const std::string where = "nodes[" + std::to_string(i) + "]";
        const glm::dmat4 world = parent * localTransform(i);
        requireFloatWorld(world, i);
        if (const auto mesh = index(n, "mesh", where)) visit(MeshInstance{*mesh, i, world});
        const json& children = member(n, "children", json::value_t::array, where);
        for (auto it = children.rbegin(); it != children.rend(); ++it)
            stack.emplace_back(asIndex(*it, where + ".children"), world);  // reversed: visited in order
    }
}

// The node's transform composed with its parents' must stay a float32 matrix (what a glTF viewer
// computes): a product of large scales (1e20 x 1e20) or translations overflows it.
void Document::requireFloatWorld(const glm::dmat4& world, size_t i) const {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!(std::abs(world[c][r]) <= double(std::numeric_limits<float>::max())))
                fail(nodeName(i) + ": its transform times its parents' reaches " + numberText(world[c][r]) +
                     ", beyond the float32 range (3.4e38) of glTF; lower the scale or translation of this node or "
                     "its parents");
}

std::string Document::nodeName(size_t i) const {
    const json& n = element("nodes", i, "the scene");
    const std::string name = n.contains("name") && n["name"].is_string() ? n["name"].get<std::string>() : "";
    return "nodes[" + std::to_string(i) + "]" + (name.empty() ? "" : " ('" + name + "')");
}

glm::dmat4 Document::localTransform(size_t i) const {
    const json& n = element("nodes", i, "the scene");
    const std::string where = nodeName(i);
    glm::dmat4 m(1.0);
    if (const std::vector<double> v = numbers(n, "matrix", 16, where); !v.empty()) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = v[size_t(4 * c + r)];  // column-major
        return m;
    }
    if (const std::vector<double> t = numbers(n, "translation", 3, where); !t.empty())
        m = glm::translate(m, glm::dvec3(t[0], t[1], t[2]));
    if (const std::vector<double> r = numbers(n, "rotation", 4, where); !r.empty()) {
        const glm::dquat q(r[3], r[0], r[1], r[2]);  // stored (x, y, z, w)
        const double len = glm::length(q);
        if (!(len > 0)) fail(where + ".rotation is not a rotation (zero quaternion)");
        m = m * glm::mat4_cast(q / len);
    }
    if (const std::vector<double> s = numbers(n, "scale", 3, where); !s.empty())
        m = glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
    return m;
}

void Document::forEachPrimitive(size_t meshIndex, const std::function<void(const Primitive&)>& visit) const {
    const json& mesh = element("meshes", meshIndex, "a node");
    const std::string meshWhere = "meshes[" + std::to_string(meshIndex) + "]";
    const std::string meshName =
        mesh.contains("name") && mesh["name"].is_string() ? mesh["name"].get<std::string>() : "";
    const json& prims = member(mesh, "primitives", json::value_t::array, meshWhere);
    for (size_t p = 0; p < prims.size(); ++p) {
        Primitive prim;
        prim.object = &prims[p];
        prim.index = p;
        prim.what = "mesh " + std::to_string(meshIndex) + (meshName.empty() ? "" : " ('" + meshName + "')") +
                    " primitive " + std::to_string(p);
        if (!prim.object->is_object()) fail(prim.what + " is not an object");
        prim.mode = index(*prim.object, "mode", prim.what).value_or(kTriangles);
        visit(prim);
    }
}

std::vector<Primitive> Document::primitives(size_t mesh) const {
    std::vector<Primitive> out;
    forEachPrimitive(mesh, [&](const Primitive& p) { out.push_back(p); });
    return out;
}

std::optional<size_t> Document::attribute(const Primitive& p, const char* name) const {
    return index(member(*p.object, "attributes", json::value_t::object, p.what), name, p.what + ".attributes");
}

std::optional<size_t> Document::indices(const Primitive& p) const { return index(*p.object, "indices", p.what); }

const json& Document::extensions(const Primitive& p) const {
    return member(*p.object, "extensions", json::value_t::object, p.what);
}

}  // namespace knit::gltf
