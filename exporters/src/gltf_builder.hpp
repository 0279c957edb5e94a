// gltf_builder.hpp (internal) — the glTF / GLB writer (exportGltf), split by what it writes
// (gltf_writer.cpp says what the files hold):
//   gltf_writer.cpp       the model: asset, scene, root node, material "yarn", the surface level; exportGltf
//   gltf_buffers.cpp      buffers, views, accessors and chunk nodes; the JSON and the final files
//   gltf_curves.cpp       curve chunks: LINE_STRIP primitives with POSITION and _RADIUS
//   gltf_tubes.cpp        tube chunks: TRIANGLES primitives with POSITION, NORMAL, TANGENT, TEXCOORD_0, COLOR_0
//   gltf_compression.cpp  KHR_mesh_quantization, EXT_meshopt_compression, KHR_draco_mesh_compression
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/type_precision.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "chunks.hpp"
#include "draco_codec.hpp"
#include "formats.hpp"
#include "io/atomic_file.hpp"
#include "knit/error.hpp"
#include "knit/plies.hpp"
#include "meshopt_codec.hpp"

namespace knit::impl {

constexpr int kArrayBuffer = TINYGLTF_TARGET_ARRAY_BUFFER;
constexpr int kElementArrayBuffer = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;

// A linear colour in [0, 1] as COLOR_0's normalized RGBA8 (opaque).
glm::u8vec4 linearRgba8(const glm::vec3& c);

// Binary data for the glTF buffers, streamed into temporary files. GLB: buffer 0 is written
// straight into the GLB's own temporary file after a reserved gap of `glbPrefix` bytes, which
// finish() fills with the 12-byte header, the JSON chunk (space padded) and the BIN chunk header,
// so the binary data is written once (no copy) whenever the JSON fits the reservation.
class BufferSink {
public:
    BufferSink(const std::string& outputPath, bool glb, uint64_t maxBytes, uint64_t glbPrefix)
        : output_(outputPath), glb_(glb), maxBytes_(maxBytes), glbPrefix_(glbPrefix) {}

    // Makes sure the next `bytes` (one chunk's data) fit in the current buffer; else opens a new one.
    void reserve(uint64_t bytes) {
        if (bytes + 4 > maxBytes_)
            throw Error("cannot export '" + output_ + "': one chunk needs " + std::to_string(bytes) +
                        " bytes, more than the buffer limit " + std::to_string(maxBytes_) +
                        "; lower the vertices per chunk");
        if (files_.empty() || sizes_.back() + bytes + 4 > maxBytes_) openBuffer();
    }
    int buffer() const { return int(files_.size()) - 1; }
    // Appends at a 4-byte aligned offset of the current buffer; returns that offset.
    uint64_t append(const void* data, uint64_t bytes) {
        pad();
        const uint64_t at = sizes_.back();
        files_.back()->stream().write(static_cast<const char*>(data), std::streamsize(bytes));
        sizes_.back() += bytes;
        return at;
    }
    size_t count() const { return files_.size(); }
    uint64_t size(size_t k) const { return sizes_[k]; }
    AtomicFile& file(size_t k) { return *files_[k]; }
    bool embedsFirst() const { return glb_; }
    uint64_t glbPrefix() const { return glbPrefix_; }
    // The final file name of buffer k (GLB: buffer 0 is embedded and has none).
    std::string fileName(size_t k) const {
        const std::filesystem::path p(output_);
        const std::string stem = p.stem().string();
        return k == 0 ? stem + ".bin" : stem + "_" + std::to_string(k) + ".bin";
    }
    std::string filePath(size_t k) const {
        return (std::filesystem::path(output_).parent_path() / fileName(k)).string();
    }
    void padAll() {
        if (!files_.empty()) pad();
    }

private:
    void pad() {
        static const char zeros[4] = {0, 0, 0, 0};
        const uint64_t r = sizes_.back() % 4;
        if (r) {
            files_.back()->stream().write(zeros, std::streamsize(4 - r));
            sizes_.back() += 4 - r;
        }
    }
    void openBuffer() {
        if (!files_.empty()) pad();
        const size_t k = files_.size();
        const bool inGlb = glb_ && k == 0;
        files_.push_back(std::make_unique<AtomicFile>(inGlb ? output_ : filePath(k), true));
        sizes_.push_back(0);
        if (inGlb) {
            // The gap for header + JSON chunk + BIN chunk header, filled in by finish().
            const std::vector<char> gap(size_t(glbPrefix_ + 8), ' ');
            files_.back()->stream().write(gap.data(), std::streamsize(gap.size()));
        }
    }
    std::string output_;
    bool glb_;
    uint64_t maxBytes_;
    uint64_t glbPrefix_;
    std::vector<std::unique_ptr<AtomicFile>> files_;
    std::vector<uint64_t> sizes_;
};

// One chunk of curves on its way to the file: float32 points relative to the chunk's origin,
// each curve a run of them (a closed curve repeats its first point at the end of its run).
struct CurveChunk {
    struct Run {
        uint32_t first = 0, count = 0;  // in `pos`
        glm::vec3 lo{0.0f}, hi{0.0f};   // exact float bounds of the run
    };
    glm::dvec3 origin{0.0};
    std::vector<glm::vec3> pos;
    std::vector<glm::u8vec4> colour;  // per entry of pos (COLOR_0); empty without colours
    std::vector<Run> runs;
    size_t points = 0;  // curve points (without the repeated first points)
    Plies generated;    // storage of generated plies
    PlyScratch scratch;
};

// The chunks of a curve export: consecutive curves of the input Polylines (planCurveChunks), or
// plies generated for consecutive yarns (yarns grouped until their estimated ply points reach
// maxPoints; a longer yarn gets a chunk of its own).
class CurveChunkSource {
public:
    // Plans the chunks (options.chunkVertices points each, or a longer yarn's own) and refuses
    // generated plies whose chunks in memory at once exceed options.budget.
    CurveChunkSource(const ExportInput& input, const ExportOptions& options);
    size_t count() const { return input_.curves ? chunks_.size() : yarnStart_.size() - 1; }
    size_t curveCountBound() const {
        return input_.curves ? input_.curves->curveCount()
                             : input_.plies->yarnCount() * size_t(input_.plies->options().count);
    }
    const std::vector<Chunk>& chunks() const { return chunks_; }

    // Produces chunk k and converts it: origin = centre of its points' bounding box.
    void fill(size_t k, CurveChunk& chunk) const;

private:
    const ExportInput& input_;
    std::vector<Chunk> chunks_;      // materialized curves
    std::vector<size_t> yarnStart_;  // generated plies: chunk k = yarns [yarnStart_[k], yarnStart_[k + 1])
};

// KHR_mesh_quantization data of one tube chunk: one uniform step per chunk (the node scale),
// q = round(p / step) with |q| <= 32767; normals and tangents as normalized shorts (stride 8).
struct QuantizedTubes {
    struct S4 {
        int16_t v[4];
    };
    std::vector<S4> position, normal, tangent;
    std::vector<glm::i8vec4> normal8, tangent8;  // instead of normal / tangent with --meshopt
    std::vector<glm::u16vec2> uv;                // normalized (u, v / vScale)
    glm::ivec3 lo{32767}, hi{-32767};            // bounds of the quantized positions
    double step = 1.0;
    double vScale = 1.0;  // largest v of the chunk (v >= 0)
};

void quantizeTubes(const TubeMesh& m, QuantizedTubes& q, bool byteDirections);

// One chunk of tubes on its way to the file (see GltfBuilder::writeTubes).
struct TubeChunk {
    TubeMesh mesh;
    std::vector<glm::u8vec4> colours;  // --yarn-colors
    QuantizedTubes quantized;          // --quantize
    DracoChunk draco;                  // --draco
    std::vector<uint16_t> indices16;   // the triangles as UNSIGNED_SHORT when <= 65535 vertices
    std::vector<MeshoptView> meshopt;  // --meshopt: tubeViews(), encoded in the parallel half
};

// UNSIGNED_SHORT indices fit when every index is below 65535 (the primitive-restart value is
// not allowed as an index).
inline bool fitsShortIndices(const TubeMesh& m) { return m.vertexCount() <= 65535; }

// One bufferView + accessor of a tube chunk: `count` elements of `size` bytes at `data`.
struct TubeView {
    const char* attribute;  // glTF attribute name, or nullptr for the indices
    const void* data;
    size_t count, size;
    int stride, target, componentType, type;
    bool normalized;
};

// The views of a plain or quantized (not Draco) tube chunk, in file order: POSITION, NORMAL,
// TANGENT, TEXCOORD_0, COLOR_0 (colours), indices (UNSIGNED_SHORT when indices16 is filled).
std::vector<TubeView> tubeViews(const TubeChunk& t, bool colours, bool quantized);

// --meshopt: every view of the chunk through meshoptimizer's codecs (index codec for indices).
void encodeTubeViews(TubeChunk& t, bool colours, bool quantized);

class GltfBuilder {
public:
    GltfBuilder(const FormatJob& job, bool glb);
    // The chunks' nodes (tubes or curves), then the surface level, then the files.
    void writeTubes();    // gltf_tubes.cpp
    void writeCurves();   // gltf_curves.cpp
    void writeSurface();  // gltf_writer.cpp
    void finish();        // gltf_buffers.cpp

private:
    // gltf_writer.cpp
    void addMaterial();
    bool hasPointColours() const;

    // gltf_buffers.cpp
    void checkChunkFits(uint64_t bytes) const;
    int addView(const void* data, uint64_t bytes, int stride, int target);
    int addAccessor(int view, size_t offset, int componentType, int type, size_t count, bool normalized);
    void addChunkNode(size_t k, const glm::dvec3& origin, tinygltf::Primitive& prim, const std::vector<double>& scale);
    void addChunkMesh(size_t k, const glm::dvec3& origin, tinygltf::Mesh mesh, const std::vector<double>& scale);

    // gltf_curves.cpp
    void writeCurveChunk(size_t k, const CurveChunk& chunk);

    // gltf_tubes.cpp
    void prepareTubeChunk(const Polylines& curves, const Chunk& chunk, TubeChunk& t) const;
    void writeTubeChunk(size_t k, const TubeChunk& t);
    std::vector<glm::u8vec4> vertexColours(const TubeMesh& mesh) const;
    void tubeAccessors(const TubeChunk& t, bool colours, tinygltf::Primitive& prim, std::vector<double>& scale);

    // gltf_compression.cpp
    int addMeshoptView(const TubeView& source, const MeshoptView& mv);
    void addMeshoptFallback(nlohmann::json& doc, nlohmann::json& buffers) const;
    void tubeDraco(const DracoChunk& d, bool colours, tinygltf::Primitive& prim);

    const FormatJob& job_;
    bool glb_;
    std::unique_ptr<CurveChunkSource> curves_;  // curve exports: where the chunks come from
    BufferSink sink_;
    tinygltf::Model model_;
    std::vector<float> radius_;  // the constant _RADIUS values, as long as the longest curve so far
    // --meshopt: views whose data is in the fallback buffer, with their extension objects.
    std::vector<std::pair<int, nlohmann::json>> meshoptViews_;
    uint64_t fallbackBytes_ = 0;  // --meshopt: size of the fallback buffer
};

}  // namespace knit::impl
