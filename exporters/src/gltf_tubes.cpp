// gltf_tubes.cpp — tube chunks (gltf_builder.hpp): TRIANGLES primitives with POSITION, NORMAL,
// TANGENT, TEXCOORD_0 and COLOR_0, swept in parallel and written in order.
#include "gltf_builder.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "util/math.hpp"

namespace knit::impl {

namespace {

// A palette colour per yarn (golden-ratio hue steps in sRGB; deterministic) as linear RGBA8:
// glTF's COLOR_0 is linear, so the sRGB palette colour is converted before it is stored.
glm::u8vec4 yarnColour(uint32_t yarn) {
    const double h = std::fmod(0.13 + 0.6180339887498949 * double(yarn), 1.0) * 6.0;
    const double s = 0.55, v = 0.9;
    const int i = int(h);
    const double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (i % 6) {
        case 0: r = v, g = t, b = p; break;
        case 1: r = q, g = v, b = p; break;
        case 2: r = p, g = v, b = t; break;
        case 3: r = p, g = q, b = v; break;
        case 4: r = t, g = p, b = v; break;
        default: r = v, g = p, b = q; break;
    }
    auto linear8 = [](double c) { return uint8_t(std::lround(util::srgbToLinear(c) * 255)); };
    return glm::u8vec4(linear8(r), linear8(g), linear8(b), 255);
}

template <class V>
void setBounds(tinygltf::Accessor& a, const std::vector<V>& values) {
    V lo = values.front(), hi = values.front();
    for (const V& v : values) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], v[k]);
            hi[k] = std::max(hi[k], v[k]);
        }
    }
    a.minValues = {double(lo[0]), double(lo[1]), double(lo[2])};
    a.maxValues = {double(hi[0]), double(hi[1]), double(hi[2])};
}

}  // namespace

// The views of a plain or quantized (not Draco) tube chunk, in file order: POSITION, NORMAL,
// TANGENT, TEXCOORD_0, COLOR_0 (colours), indices (UNSIGNED_SHORT when indices16 is filled).
std::vector<TubeView> tubeViews(const TubeChunk& t, bool colours, bool quantized) {
    const TubeMesh& m = t.mesh;
    const QuantizedTubes& q = t.quantized;
    const size_t n = m.vertexCount();
    const int f = TINYGLTF_COMPONENT_TYPE_FLOAT, s = TINYGLTF_COMPONENT_TYPE_SHORT, b = TINYGLTF_COMPONENT_TYPE_BYTE;
    const int v2 = TINYGLTF_TYPE_VEC2, v3 = TINYGLTF_TYPE_VEC3, v4 = TINYGLTF_TYPE_VEC4;
    std::vector<TubeView> v;
    if (!quantized) {
        v.push_back({"POSITION", m.positions.data(), n, 12, 0, kArrayBuffer, f, v3, false});
        v.push_back({"NORMAL", m.normals.data(), n, 12, 0, kArrayBuffer, f, v3, false});
        v.push_back({"TANGENT", m.tangents.data(), n, 16, 0, kArrayBuffer, f, v4, false});
        v.push_back({"TEXCOORD_0", m.uvs.data(), n, 8, 0, kArrayBuffer, f, v2, false});
    } else {
        v.push_back({"POSITION", q.position.data(), n, 8, 8, kArrayBuffer, s, v3, false});
        if (q.normal8.empty()) {
            v.push_back({"NORMAL", q.normal.data(), n, 8, 8, kArrayBuffer, s, v3, true});
            v.push_back({"TANGENT", q.tangent.data(), n, 8, 0, kArrayBuffer, s, v4, true});
        } else {
            v.push_back({"NORMAL", q.normal8.data(), n, 4, 4, kArrayBuffer, b, v3, true});
            v.push_back({"TANGENT", q.tangent8.data(), n, 4, 0, kArrayBuffer, b, v4, true});
        }
        v.push_back(
            {"TEXCOORD_0", q.uv.data(), n, 4, 0, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, v2, true});
    }
    if (colours)
        v.push_back(
            {"COLOR_0", t.colours.data(), n, 4, 0, kArrayBuffer, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, v4, true});
    const bool shortIndices = !t.indices16.empty();
    v.push_back({nullptr, shortIndices ? static_cast<const void*>(t.indices16.data()) : m.triangles.data(),
                 m.triangles.size() * 3, shortIndices ? size_t(2) : size_t(4), 0, kElementArrayBuffer,
                 shortIndices ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                 TINYGLTF_TYPE_SCALAR, false});
    return v;
}

// Tubes: chunks are swept (and quantized or Draco-encoded) in parallel and written in chunk
// order (orderedChunks), so the file does not depend on the thread count.
void GltfBuilder::writeTubes() {
    const Polylines& curves = *job_.input.curves;
    const std::vector<Chunk> chunks = planTubeChunks(curves, job_.tube, job_.options.chunkVertices);
    // Before anything is written: every chunk must fit in one buffer (plain size is the
    // upper bound; quantized and Draco data are smaller).
    for (const Chunk& c : chunks) checkChunkFits(c.vertices * 56 + c.triangles * 12 + 64);
    orderedChunks<TubeChunk>(
        chunks.size(), [&](size_t k, TubeChunk& t) { prepareTubeChunk(curves, chunks[k], t); },
        [&](size_t k, const TubeChunk& t) { writeTubeChunk(k, t); });
    job_.stats.curves = curves.curveCount();
}

// The parallel half: sweep the chunk's tubes, and colour / quantize / Draco-encode them.
void GltfBuilder::prepareTubeChunk(const Polylines& curves, const Chunk& chunk, TubeChunk& t) const {
    sweepTubes(curves, job_.input.radius, job_.tube, chunk.firstCurve, chunk.lastCurve, chunkOrigin(curves, chunk),
               t.mesh);
    t.colours.clear();
    t.indices16.clear();
    if (t.mesh.vertexCount() == 0) return;
    if (job_.options.yarnColors) t.colours = vertexColours(t.mesh);
    else std::transform(t.mesh.colours.begin(), t.mesh.colours.end(), std::back_inserter(t.colours), linearRgba8);
    const std::vector<glm::u8vec4>* col = t.colours.empty() ? nullptr : &t.colours;
    if (job_.options.draco) {
        DracoSettings settings;
        settings.positionBits = job_.options.dracoBits;
        settings.normalBits = job_.options.dracoNormalBits;
        settings.texcoordBits = job_.options.dracoTexcoordBits;
        settings.level = job_.options.dracoLevel;
        t.draco = encodeDracoTubes(t.mesh, col, settings);
        return;
    }
    if (job_.options.quantize) quantizeTubes(t.mesh, t.quantized, job_.options.meshopt);
    if (fitsShortIndices(t.mesh)) {
        t.indices16.resize(t.mesh.triangles.size() * 3);
        for (size_t i = 0; i < t.mesh.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) t.indices16[i * 3 + size_t(k)] = uint16_t(t.mesh.triangles[i][k]);
    }
    if (job_.options.meshopt) encodeTubeViews(t, col != nullptr, job_.options.quantize);
}

// The serial half: views, accessors and the chunk's node.
void GltfBuilder::writeTubeChunk(size_t k, const TubeChunk& t) {
    const TubeMesh& mesh = t.mesh;
    if (mesh.vertexCount() == 0) return;
    const std::vector<glm::u8vec4>* col = t.colours.empty() ? nullptr : &t.colours;
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = 0;
    std::vector<double> scale;
    const size_t plain = mesh.vertexCount() * (12 + 12 + 16 + 8 + (col ? 4 : 0)) + mesh.triangles.size() * 12;
    job_.stats.uncompressedMeshBytes += plain;
    if (job_.options.draco) {
        tubeDraco(t.draco, col != nullptr, prim);
    } else {
        // The chunk's data is at most its plain size; meshopt's worst case adds a little.
        sink_.reserve(plain + plain / 8 + 1024);
        const uint64_t before = sink_.size(size_t(sink_.buffer()));
        tubeAccessors(t, col != nullptr, prim, scale);
        job_.stats.compressedMeshBytes += sink_.size(size_t(sink_.buffer())) - before;
    }
    addChunkNode(k, mesh.origin, prim, scale);
    job_.stats.vertices += mesh.vertexCount();
    job_.stats.triangles += mesh.triangles.size();
    job_.stats.maxChunkVertices = std::max(job_.stats.maxChunkVertices, mesh.vertexCount());
}

std::vector<glm::u8vec4> GltfBuilder::vertexColours(const TubeMesh& mesh) const {
    std::vector<glm::u8vec4> c(mesh.vertexCount());
    for (size_t i = 0; i < c.size(); ++i) {
        const uint32_t curve = mesh.curveOfVertex[i];
        const uint32_t yarn = job_.input.yarnOfCurve ? (*job_.input.yarnOfCurve)[curve] : curve;
        c[i] = yarnColour(yarn);
    }
    return c;
}

// The views and accessors of a plain or quantized chunk (the caller reserved the space), with
// the exact POSITION bounds, and for quantized data the node scale and texcoordScale extras.
void GltfBuilder::tubeAccessors(const TubeChunk& t, bool colours, tinygltf::Primitive& prim,
                                std::vector<double>& scale) {
    const bool quantized = job_.options.quantize;
    const std::vector<TubeView> views = tubeViews(t, colours, quantized);
    for (size_t i = 0; i < views.size(); ++i) {
        const TubeView& v = views[i];
        const int view = job_.options.meshopt ? addMeshoptView(v, t.meshopt[i])
                                              : addView(v.data, uint64_t(v.count) * v.size, v.stride, v.target);
        const int accessor = addAccessor(view, 0, v.componentType, v.type, v.count, v.normalized);
        if (v.attribute) prim.attributes[v.attribute] = accessor;
        else prim.indices = accessor;
    }
    tinygltf::Accessor& position = model_.accessors[size_t(prim.attributes["POSITION"])];
    if (!quantized) {
        setBounds(position, t.mesh.positions);
        return;
    }
    const QuantizedTubes& q = t.quantized;
    position.minValues = {double(q.lo.x), double(q.lo.y), double(q.lo.z)};
    position.maxValues = {double(q.hi.x), double(q.hi.y), double(q.hi.z)};
    scale = {q.step, q.step, q.step};
    tinygltf::Value::Object extras;
    extras["texcoordScale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(1.0), tinygltf::Value(q.vScale)});
    prim.extras = tinygltf::Value(std::move(extras));
}

}  // namespace knit::impl
