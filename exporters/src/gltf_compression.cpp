// gltf_compression.cpp — the compressed tube data (gltf_builder.hpp): KHR_mesh_quantization,
// EXT_meshopt_compression, KHR_draco_mesh_compression.
#include "gltf_builder.hpp"

#include <algorithm>
#include <cmath>

namespace knit::impl {

namespace {

// TEXCOORD_0 as normalized uint16: u in [0, 1] directly, v (radius units, >= 0) over the chunk's
// largest v, recorded as the primitive's texcoordScale.
void quantizeTexcoords(const TubeMesh& m, QuantizedTubes& q) {
    float vMax = 0.0f;
    for (const glm::vec2& uv : m.uvs) vMax = std::max(vMax, uv.y);
    q.vScale = vMax > 0.0f ? double(vMax) : 1.0;
    q.uv.resize(m.uvs.size());
    auto qu = [](double x) { return uint16_t(std::lround(std::clamp(x, 0.0, 1.0) * 65535.0)); };
    for (size_t i = 0; i < m.uvs.size(); ++i) q.uv[i] = glm::u16vec2(qu(m.uvs[i].x), qu(m.uvs[i].y / q.vScale));
}

// --quantize --meshopt: NORMAL / TANGENT as normalized BYTE (stride 4, like gltfpack's default
// 8-bit normals; ~0.5 degree), which halves them before the vertex codec.
void quantizeDirectionsToBytes(const TubeMesh& m, QuantizedTubes& q) {
    auto qb = [](double x) { return int8_t(std::lround(std::clamp(x, -1.0, 1.0) * 127.0)); };
    q.normal8.resize(m.vertexCount());
    q.tangent8.resize(m.vertexCount());
    for (size_t i = 0; i < m.vertexCount(); ++i) {
        const glm::vec3& n = m.normals[i];
        const glm::vec4& t = m.tangents[i];
        q.normal8[i] = glm::i8vec4(qb(n.x), qb(n.y), qb(n.z), 0);
        q.tangent8[i] = glm::i8vec4(qb(t.x), qb(t.y), qb(t.z), t.w < 0 ? int8_t(-127) : int8_t(127));
    }
    q.normal.clear();
    q.tangent.clear();
}

}  // namespace

void quantizeTubes(const TubeMesh& m, QuantizedTubes& q, bool byteDirections) {
    const size_t n = m.vertexCount();
    float maxAbs = 0.0f;
    for (const glm::vec3& p : m.positions) maxAbs = std::max({maxAbs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    q.step = maxAbs > 0 ? double(maxAbs) / 32767.0 : 1.0;
    q.position.resize(n);
    q.normal.resize(n);
    q.tangent.resize(n);
    q.lo = glm::ivec3(32767);
    q.hi = glm::ivec3(-32767);
    auto qs = [](double x) { return int16_t(std::lround(std::clamp(x, -32767.0, 32767.0))); };
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) {
            q.position[i].v[k] = qs(double(m.positions[i][k]) / q.step);
            q.lo[k] = std::min<int>(q.lo[k], q.position[i].v[k]);
            q.hi[k] = std::max<int>(q.hi[k], q.position[i].v[k]);
            q.normal[i].v[k] = qs(double(m.normals[i][k]) * 32767.0);
            q.tangent[i].v[k] = qs(double(m.tangents[i][k]) * 32767.0);
        }
        q.position[i].v[3] = q.normal[i].v[3] = 0;
        q.tangent[i].v[3] = m.tangents[i].w < 0 ? int16_t(-32767) : int16_t(32767);
    }
    quantizeTexcoords(m, q);
    if (byteDirections) quantizeDirectionsToBytes(m, q);
    else q.normal8.clear(), q.tangent8.clear();
}

// --meshopt: every view of the chunk through meshoptimizer's codecs (index codec for indices).
void encodeTubeViews(TubeChunk& t, bool colours, bool quantized) {
    t.meshopt.clear();
    for (const TubeView& v : tubeViews(t, colours, quantized))
        t.meshopt.push_back(v.target == kElementArrayBuffer ? encodeMeshoptTriangles(v.data, v.count, v.size)
                                                            : encodeMeshoptAttributes(v.data, v.count, v.size));
}

// An EXT_meshopt_compression view: the encoded bytes go into the current buffer, the view
// itself into the fallback buffer (its index and the extension object are set in finish()).
int GltfBuilder::addMeshoptView(const TubeView& source, const MeshoptView& mv) {
    tinygltf::BufferView v;
    v.buffer = 0;
    fallbackBytes_ = (fallbackBytes_ + 3) / 4 * 4;
    v.byteOffset = size_t(fallbackBytes_);
    v.byteLength = source.count * source.size;
    v.byteStride = source.target == kElementArrayBuffer ? 0 : source.size;
    v.target = source.target;
    fallbackBytes_ += v.byteLength;
    // tinygltf 2.7 drops bufferView extensions: the object is added to the JSON in finish().
    const uint64_t at = sink_.append(mv.bytes.data(), mv.bytes.size());
    model_.bufferViews.push_back(v);
    meshoptViews_.push_back({int(model_.bufferViews.size()) - 1,
                             {{"buffer", sink_.buffer()},
                              {"byteOffset", at},
                              {"byteLength", mv.bytes.size()},
                              {"byteStride", mv.stride},
                              {"count", mv.count},
                              {"mode", mv.mode}}});
    return meshoptViews_.back().first;
}

// EXT_meshopt_compression: the fallback buffer (last; no uri, never written) that the
// compressed views point to.
void GltfBuilder::addMeshoptFallback(nlohmann::json& doc, nlohmann::json& buffers) const {
    if (meshoptViews_.empty()) return;
    const size_t fallback = buffers.size();
    buffers.push_back({{"byteLength", std::max<uint64_t>(fallbackBytes_, 4)},
                       {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    for (const auto& [v, ext] : meshoptViews_) {
        nlohmann::json& view = doc["bufferViews"][size_t(v)];
        view["buffer"] = fallback;
        view["extensions"]["EXT_meshopt_compression"] = ext;
    }
}

void GltfBuilder::tubeDraco(const DracoChunk& d, bool colours, tinygltf::Primitive& prim) {
    sink_.reserve(d.bytes.size() + 8);
    const int view = addView(d.bytes.data(), d.bytes.size(), 0, 0);
    job_.stats.compressedMeshBytes += d.bytes.size();
    // Accessors without bufferView: they describe the decoded data.
    const int f = TINYGLTF_COMPONENT_TYPE_FLOAT;
    prim.attributes["POSITION"] = addAccessor(-1, 0, f, TINYGLTF_TYPE_VEC3, d.points, false);
    tinygltf::Accessor& pa = model_.accessors[prim.attributes["POSITION"]];
    pa.minValues = {d.minPosition.x, d.minPosition.y, d.minPosition.z};
    pa.maxValues = {d.maxPosition.x, d.maxPosition.y, d.maxPosition.z};
    prim.attributes["NORMAL"] = addAccessor(-1, 0, f, TINYGLTF_TYPE_VEC3, d.points, false);
    prim.attributes["TANGENT"] = addAccessor(-1, 0, f, TINYGLTF_TYPE_VEC4, d.points, false);
    prim.attributes["TEXCOORD_0"] = addAccessor(-1, 0, f, TINYGLTF_TYPE_VEC2, d.points, false);
    if (colours)
        prim.attributes["COLOR_0"] =
            addAccessor(-1, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, d.points, true);
    prim.indices = addAccessor(-1, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, d.faces * 3, false);
    tinygltf::Value::Object attrs;
    for (const auto& [name, id] : d.attributeIds) attrs[name] = tinygltf::Value(id);
    tinygltf::Value::Object ext;
    ext["bufferView"] = tinygltf::Value(view);
    ext["attributes"] = tinygltf::Value(std::move(attrs));
    prim.extensions["KHR_draco_mesh_compression"] = tinygltf::Value(std::move(ext));
}

}  // namespace knit::impl
