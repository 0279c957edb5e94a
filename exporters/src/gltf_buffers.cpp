// gltf_buffers.cpp — buffers, views, accessors and chunk nodes; the JSON and the final files (gltf_builder.hpp).
#include "gltf_builder.hpp"

#include <cctype>
#include <filesystem>
#include <sstream>

namespace knit::impl {

namespace {

// Percent-encodes a file name for a relative glTF URI.
std::string uriEncode(const std::string& name) {
    static const char* hex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : name) {
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
            out.push_back(char(c));
        } else {
            out.push_back('%');
            out.push_back(hex[c >> 4]);
            out.push_back(hex[c & 15]);
        }
    }
    return out;
}

// GLB header + JSON chunk (padded with spaces to `jsonChunk` bytes) + BIN chunk header.
void writeGlbHead(std::ostream& out, const std::string& json, uint64_t jsonChunk, uint64_t bin, uint64_t total) {
    auto u32 = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    out.write("glTF", 4);
    u32(2);
    u32(uint32_t(total));
    u32(uint32_t(jsonChunk));
    u32(0x4E4F534A);  // "JSON"
    out.write(json.data(), std::streamsize(json.size()));
    for (uint64_t i = json.size(); i < jsonChunk; ++i) out.put(' ');
    if (bin > 0) {
        u32(uint32_t(bin));
        u32(0x004E4942);  // "BIN\0"
    }
}

}  // namespace

// Serializes the JSON with tinygltf, fixes up the buffers, writes all files, renames them.
void GltfBuilder::finish() {
    std::ostringstream jsonText;
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&model_, jsonText, job_.options.prettyJson, false))
        throw Error("cannot export '" + job_.options.path + "': tinygltf failed to serialize the model");
    nlohmann::json doc = nlohmann::json::parse(jsonText.str());
    // The buffers (tinygltf only knows in-memory buffers): sizes and URIs of the streamed files.
    sink_.padAll();
    nlohmann::json buffers = nlohmann::json::array();
    for (size_t k = 0; k < sink_.count(); ++k) {
        nlohmann::json b = {{"byteLength", sink_.size(k)}};
        if (!(glb_ && k == 0)) b["uri"] = uriEncode(sink_.fileName(k));
        buffers.push_back(b);
    }
    addMeshoptFallback(doc, buffers);
    if (buffers.empty()) doc.erase("buffers");
    else doc["buffers"] = buffers;
    const std::string json = job_.options.prettyJson ? doc.dump(2) : doc.dump();

    std::unique_ptr<AtomicFile> rewritten;  // GLB whose JSON did not fit the reservation
    AtomicFile* main = nullptr;
    uint64_t mainBytes = 0;
    if (glb_ && sink_.count() > 0) {
        // GLB with data: the BIN chunk already follows the reserved gap in the GLB's file.
        const uint64_t bin = sink_.size(0), prefix = sink_.glbPrefix();
        const uint64_t jsonPadded = (json.size() + 3) / 4 * 4;
        const bool fits = 20 + jsonPadded <= prefix;
        const uint64_t jsonChunk = fits ? prefix - 20 : jsonPadded;
        const uint64_t total = 20 + jsonChunk + 8 + bin;
        if (total > 0xFFFFFFFFull)
            throw Error("cannot export '" + job_.options.path + "': the GLB would be " + std::to_string(total) +
                        " bytes, over the 4 GiB GLB limit; lower the buffer size or write .gltf");
        AtomicFile& file0 = sink_.file(0);
        if (fits) {
            std::ostream& out = file0.stream();
            out.seekp(0);
            writeGlbHead(out, json, jsonChunk, bin, total);
            main = &file0;
        } else {
            // Rare: the JSON outgrew the reservation; write a new file and copy the BIN data.
            file0.close();
            rewritten = std::make_unique<AtomicFile>(job_.options.path, true);
            writeGlbHead(rewritten->stream(), json, jsonChunk, bin, total);
            appendFile(rewritten->stream(), file0.tempPath(), prefix + 8, bin);
            main = rewritten.get();
        }
        mainBytes = total;
    } else {
        rewritten = std::make_unique<AtomicFile>(job_.options.path, true);
        if (glb_) {
            const uint64_t jsonPadded = (json.size() + 3) / 4 * 4;
            writeGlbHead(rewritten->stream(), json, jsonPadded, 0, 20 + jsonPadded);
            mainBytes = 20 + jsonPadded;
        } else {
            rewritten->stream().write(json.data(), std::streamsize(json.size()));
            mainBytes = json.size();
        }
        main = rewritten.get();
    }
    for (size_t k = 0; k < sink_.count(); ++k) sink_.file(k).close();
    main->close();
    // Rename: external buffers first, the main file last; undo on failure.
    try {
        for (size_t k = (glb_ ? 1 : 0); k < sink_.count(); ++k) sink_.file(k).commit();
        main->commit();
    } catch (...) {
        for (size_t k = 0; k < sink_.count(); ++k) sink_.file(k).undoCommit();
        throw;
    }
    uint64_t bytes = mainBytes;
    for (size_t k = (glb_ ? 1 : 0); k < sink_.count(); ++k) bytes += sink_.size(k);
    job_.stats.bytes = bytes;
    job_.stats.buffers = sink_.count();
}

void GltfBuilder::checkChunkFits(uint64_t bytes) const {
    if (bytes + 4 > job_.options.maxBufferBytes)
        throw Error("cannot export '" + job_.options.path + "': a chunk needs up to " + std::to_string(bytes) +
                    " bytes, more than the buffer limit " + std::to_string(job_.options.maxBufferBytes) +
                    "; lower the vertices per chunk (a single curve longer than the limit cannot be split)");
}

int GltfBuilder::addView(const void* data, uint64_t bytes, int stride, int target) {
    tinygltf::BufferView v;
    v.buffer = sink_.buffer();
    v.byteOffset = size_t(sink_.append(data, bytes));
    v.byteLength = size_t(bytes);
    v.byteStride = size_t(stride);
    v.target = target;
    model_.bufferViews.push_back(v);
    return int(model_.bufferViews.size()) - 1;
}

int GltfBuilder::addAccessor(int view, size_t offset, int componentType, int type, size_t count, bool normalized) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = offset;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.normalized = normalized;
    model_.accessors.push_back(a);
    return int(model_.accessors.size()) - 1;
}

void GltfBuilder::addChunkNode(size_t k, const glm::dvec3& origin, tinygltf::Primitive& prim,
                               const std::vector<double>& scale) {
    tinygltf::Mesh mesh;
    mesh.name = "tubes " + std::to_string(k);
    mesh.primitives.push_back(std::move(prim));
    addChunkMesh(k, origin, std::move(mesh), scale);
}

void GltfBuilder::addChunkMesh(size_t k, const glm::dvec3& origin, tinygltf::Mesh mesh,
                               const std::vector<double>& scale) {
    model_.meshes.push_back(std::move(mesh));
    tinygltf::Node node;
    node.name = "chunk " + std::to_string(k);
    node.mesh = int(model_.meshes.size()) - 1;
    node.translation = {origin.x, origin.y, origin.z};
    node.scale = scale;
    model_.nodes.push_back(std::move(node));
    model_.nodes[0].children.push_back(int(model_.nodes.size()) - 1);
    ++job_.stats.chunks;
}

}  // namespace knit::impl
