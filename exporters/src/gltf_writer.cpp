// gltf_writer.cpp — glTF 2.0 (.gltf + .bin) and GLB through tinygltf, streamed chunk by chunk.
//
// Structure: scene 0 -> root node "libknit" -> one child node per chunk, whose translation is the
// chunk's local origin (double) and whose mesh holds float32 positions relative to it.
//  * Tubes: one TRIANGLES primitive per chunk with POSITION, NORMAL, TANGENT (along the curve,
//    w = -1, see sweep.cpp), TEXCOORD_0 (u around 0..1, v along in radius units) and optional
//    COLOR_0 (RGBA8 normalized, one palette colour per yarn); UNSIGNED_INT indices.
//    --draco: the primitive carries KHR_draco_mesh_compression (required; no fallback data), its
//    accessors describe the decoded data (count, exact POSITION bounds). --quantize:
//    KHR_mesh_quantization (required): POSITION as SHORT scaled by the node's uniform scale,
//    NORMAL / TANGENT as normalized SHORT (stride 8), TEXCOORD_0 float.
//  * Curves: one LINE_STRIP primitive per curve (closed curves repeat their first index), all
//    curves of a chunk sharing its POSITION and `_RADIUS` accessors.
//  * Material "yarn": pbrMetallicRoughness + KHR_materials_sheen; yarn / ply parameters in extras.
//  * Buffers: binary data streams into temporary files as chunks are produced; a new buffer is
//    started before one would exceed maxBufferBytes. GLB: buffer 0 becomes the BIN chunk, later
//    buffers are external "<stem>_<k>.bin"; .gltf: "<stem>.bin", "<stem>_1.bin", ... All files
//    are renamed into place only after everything was written.
//  * Every bufferView / accessor offset is 4-byte aligned; POSITION min / max are the exact
//    float32 (or quantized integer) bounds of the stored data.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <sstream>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>
#include <tbb/concurrent_queue.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <tiny_gltf.h>

#include "atomic_file.hpp"
#include "chunks.hpp"
#include "draco_codec.hpp"
#include "formats.hpp"
#include "knit/error.hpp"
#include "knit/plies.hpp"

namespace knit::detail {

namespace {

namespace fs = std::filesystem;

constexpr int kArrayBuffer = TINYGLTF_TARGET_ARRAY_BUFFER;
constexpr int kElementArrayBuffer = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;

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

tinygltf::Value toValue(const nlohmann::json& j) {
    switch (j.type()) {
        case nlohmann::json::value_t::object: {
            tinygltf::Value::Object o;
            for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = toValue(it.value());
            return tinygltf::Value(std::move(o));
        }
        case nlohmann::json::value_t::array: {
            tinygltf::Value::Array a;
            for (const auto& v : j) a.push_back(toValue(v));
            return tinygltf::Value(std::move(a));
        }
        case nlohmann::json::value_t::string: return tinygltf::Value(j.get<std::string>());
        case nlohmann::json::value_t::boolean: return tinygltf::Value(j.get<bool>());
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned: {
            const int64_t v = j.get<int64_t>();
            if (v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max())
                return tinygltf::Value(int(v));
            return tinygltf::Value(double(v));
        }
        case nlohmann::json::value_t::number_float: return tinygltf::Value(j.get<double>());
        default: return tinygltf::Value();
    }
}

// A palette colour per yarn (golden-ratio hue steps; deterministic), RGBA8.
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
    return glm::u8vec4(uint8_t(std::lround(r * 255)), uint8_t(std::lround(g * 255)), uint8_t(std::lround(b * 255)),
                       255);
}

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
                        "; lower --chunk-vertices");
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
        const fs::path p(output_);
        const std::string stem = p.stem().string();
        return k == 0 ? stem + ".bin" : stem + "_" + std::to_string(k) + ".bin";
    }
    std::string filePath(size_t k) const { return (fs::path(output_).parent_path() / fileName(k)).string(); }
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

// One chunk of curves on its way to the file: float32 points relative to the chunk's origin,
// each curve a run of them (a closed curve repeats its first point at the end of its run).
struct CurveChunk {
    struct Run {
        uint32_t first = 0, count = 0;  // in `pos`
        glm::vec3 lo{0.0f}, hi{0.0f};   // exact float bounds of the run
    };
    size_t index = 0;
    glm::dvec3 origin{0.0};
    std::vector<glm::vec3> pos;
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
    CurveChunkSource(const ExportInput& input, size_t maxPoints) : input_(input) {
        if (input.curves) {
            chunks_ = planCurveChunks(*input.curves, maxPoints);
            return;
        }
        const PlyGenerator& g = *input.plies;
        size_t acc = 0;
        yarnStart_.push_back(0);
        for (size_t y = 0; y < g.yarnCount(); ++y) {
            const size_t e = g.estimatePoints(y);
            if (acc > 0 && acc + e > maxPoints) {
                yarnStart_.push_back(y);
                acc = 0;
            }
            acc += e;
        }
        if (g.yarnCount() > 0) yarnStart_.push_back(g.yarnCount());
    }
    size_t count() const { return input_.curves ? chunks_.size() : yarnStart_.size() - 1; }
    size_t curveCountBound() const {
        return input_.curves ? input_.curves->curveCount()
                             : input_.plies->yarnCount() * size_t(input_.plies->options().count);
    }
    const std::vector<Chunk>& chunks() const { return chunks_; }

    // Produces chunk `chunk.index` and converts it: origin = centre of its points' bounding box.
    void fill(CurveChunk& chunk) const {
        const Polylines* curves = input_.curves;
        size_t first = 0, last = 0;
        if (curves) {
            first = chunks_[chunk.index].firstCurve;
            last = chunks_[chunk.index].lastCurve;
        } else {
            input_.plies->generate(yarnStart_[chunk.index], yarnStart_[chunk.index + 1], chunk.generated, chunk.scratch,
                                   false);  // curves only: no radial directions
            curves = &chunk.generated.curves;
            last = curves->curveCount();
        }
        const Chunk range{first, last, 0, 0};
        chunk.origin = last > first ? chunkOrigin(*curves, range) : glm::dvec3(0.0);
        chunk.pos.clear();
        chunk.runs.clear();
        chunk.points = 0;
        for (size_t c = first; c < last; ++c) {
            const uint32_t n = curves->size(c);
            if (n < 2) continue;
            CurveChunk::Run run;
            run.first = uint32_t(chunk.pos.size());
            const glm::dvec3* p = curves->points.data() + curves->begin(c);
            glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
            for (uint32_t i = 0; i < n; ++i) {
                const glm::vec3 q(p[i] - chunk.origin);
                lo = glm::min(lo, q);
                hi = glm::max(hi, q);
                chunk.pos.push_back(q);
            }
            if (curves->isClosed(c)) chunk.pos.push_back(chunk.pos[run.first]);
            run.count = uint32_t(chunk.pos.size() - run.first);
            run.lo = lo;
            run.hi = hi;
            chunk.runs.push_back(run);
            chunk.points += n;
        }
    }

private:
    const ExportInput& input_;
    std::vector<Chunk> chunks_;       // materialized curves
    std::vector<size_t> yarnStart_;   // generated plies: chunk k = yarns [yarnStart_[k], yarnStart_[k + 1])
};

// Bytes reserved in front of a GLB's BIN data for the header and JSON chunk: generous per-chunk
// (and per-curve) estimates of the JSON size; finish() pads the JSON with spaces to fill it.
uint64_t jsonReservation(const FormatJob& job, const CurveChunkSource* curves) {
    if (job.options.glbJsonReserve > 0) return std::max<uint64_t>(32, (job.options.glbJsonReserve + 3) / 4 * 4);
    uint64_t chunks = 0, curveCount = 0;
    if (curves) {
        chunks = curves->count();
        curveCount = curves->curveCountBound();
    } else if (job.input.curves) {
        chunks = planTubeChunks(*job.input.curves, job.tube, job.options.chunkVertices).size();
    } else {
        return 4096;
    }
    const uint64_t extras = job.input.materialExtras ? job.input.materialExtras->dump().size() : 0;
    // A curve: a primitive and two accessors (POSITION with min / max, _RADIUS), ~400 bytes.
    uint64_t bytes = 4096 + 2 * extras + chunks * 2048 + curveCount * 512;
    if (job.options.prettyJson) bytes *= 3;
    return (bytes + 3) / 4 * 4;
}

class GltfBuilder {
public:
    GltfBuilder(const FormatJob& job, bool glb)
        : job_(job),
          glb_(glb),
          curves_(job.tubes ? nullptr : std::make_unique<CurveChunkSource>(job.input, job.options.chunkVertices)),
          sink_(job.options.path, glb, job.options.maxBufferBytes, jsonReservation(job, curves_.get())) {
        model_.asset.version = "2.0";
        model_.asset.generator = "libknit";
        model_.defaultScene = 0;
        tinygltf::Scene scene;
        scene.name = "knit";
        scene.nodes.push_back(0);
        model_.scenes.push_back(scene);
        tinygltf::Node root;
        root.name = "libknit";
        model_.nodes.push_back(root);
        addMaterial();
        if (job.tubes && job.options.draco) {
            model_.extensionsUsed.push_back("KHR_draco_mesh_compression");
            model_.extensionsRequired.push_back("KHR_draco_mesh_compression");
        }
        if (job.tubes && job.options.quantize) {
            model_.extensionsUsed.push_back("KHR_mesh_quantization");
            model_.extensionsRequired.push_back("KHR_mesh_quantization");
        }
    }

    void writeTubes() {
        const Polylines& curves = *job_.input.curves;
        const std::vector<Chunk> chunks = planTubeChunks(curves, job_.tube, job_.options.chunkVertices);
        // Before anything is written: every chunk must fit in one buffer (plain size is the
        // upper bound; quantized and Draco data are smaller).
        for (const Chunk& c : chunks) checkChunkFits(c.vertices * 56 + c.triangles * 12 + 64);
        forEachTubeChunk(curves, job_.input.radius, job_.tube, chunks, [&](size_t k, const TubeMesh& mesh) {
            if (mesh.vertexCount() == 0) return;
            std::vector<glm::u8vec4> colours;
            if (job_.options.yarnColors) colours = vertexColours(mesh);
            const std::vector<glm::u8vec4>* col = job_.options.yarnColors ? &colours : nullptr;
            tinygltf::Primitive prim;
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            prim.material = 0;
            std::vector<double> scale;
            const size_t plain = mesh.vertexCount() * (12 + 12 + 16 + 8 + (col ? 4 : 0)) + mesh.triangles.size() * 12;
            job_.stats.uncompressedMeshBytes += plain;
            if (job_.options.draco) {
                tubeDraco(mesh, col, prim);
            } else if (job_.options.quantize) {
                tubeQuantized(mesh, col, prim, scale);
            } else {
                tubePlain(mesh, col, prim);
                job_.stats.compressedMeshBytes += plain;
            }
            addChunkNode(k, mesh.origin, prim, scale);
            job_.stats.vertices += mesh.vertexCount();
            job_.stats.triangles += mesh.triangles.size();
            job_.stats.maxChunkVertices = std::max(job_.stats.maxChunkVertices, mesh.vertexCount());
        });
        job_.stats.curves = curves.curveCount();
    }

    // Curves: chunks are produced (sliced from the input, or generated plies) and converted to
    // float32 in parallel, and appended to the buffers in chunk order (a TBB pipeline), so the
    // writing overlaps the work of the next chunks and at most `tokens` chunks are in memory.
    void writeCurves() {
        const CurveChunkSource& source = *curves_;
        if (job_.input.curves)  // known sizes: fail before anything is written
            for (const Chunk& c : source.chunks())
                checkChunkFits((c.vertices + (c.lastCurve - c.firstCurve)) * 16 + 64);
        const size_t tokens = size_t(2 * std::max(1, tbb::this_task_arena::max_concurrency()));
        std::vector<std::unique_ptr<CurveChunk>> pool;
        tbb::concurrent_queue<CurveChunk*> free;
        for (size_t t = 0; t < tokens; ++t) {
            pool.push_back(std::make_unique<CurveChunk>());
            free.push(pool.back().get());
        }
        size_t next = 0;
        tbb::parallel_pipeline(
            tokens,
            tbb::make_filter<void, CurveChunk*>(tbb::filter_mode::serial_in_order,
                                                [&](tbb::flow_control& fc) -> CurveChunk* {
                                                    CurveChunk* chunk = nullptr;
                                                    if (next == source.count() || !free.try_pop(chunk)) {
                                                        fc.stop();
                                                        return nullptr;
                                                    }
                                                    chunk->index = next++;
                                                    return chunk;
                                                }) &
                tbb::make_filter<CurveChunk*, CurveChunk*>(tbb::filter_mode::parallel,
                                                           [&](CurveChunk* chunk) {
                                                               source.fill(*chunk);
                                                               return chunk;
                                                           }) &
                tbb::make_filter<CurveChunk*, void>(tbb::filter_mode::serial_in_order, [&](CurveChunk* chunk) {
                    writeCurveChunk(*chunk);
                    free.push(chunk);
                }));
    }

    // Serializes the JSON with tinygltf, fixes up the buffers, writes all files, renames them.
    void finish() {
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

private:
    void checkChunkFits(uint64_t bytes) const {
        if (bytes + 4 > job_.options.maxBufferBytes)
            throw Error("cannot export '" + job_.options.path + "': a chunk needs up to " + std::to_string(bytes) +
                        " bytes, more than the buffer limit " + std::to_string(job_.options.maxBufferBytes) +
                        "; lower --chunk-vertices (a single curve longer than the limit cannot be split)");
    }

    // One chunk's node: a POSITION view (stride 12) holding every curve's points and a _RADIUS
    // view (stride 4) as long as the longest curve, shared by the curves' accessors; one
    // non-indexed LINE_STRIP primitive per curve.
    void writeCurveChunk(const CurveChunk& chunk) {
        if (chunk.runs.empty()) return;
        uint32_t longest = 0;
        for (const CurveChunk::Run& r : chunk.runs) longest = std::max(longest, r.count);
        if (radius_.size() < longest) radius_.resize(longest, float(job_.input.radius));
        sink_.reserve(chunk.pos.size() * 12 + uint64_t(longest) * 4 + 16);
        const int posView = addView(chunk.pos.data(), chunk.pos.size() * 12, 12, kArrayBuffer);
        const int radView = addView(radius_.data(), uint64_t(longest) * 4, 4, kArrayBuffer);
        tinygltf::Mesh mesh;
        mesh.name = "curves " + std::to_string(chunk.index);
        for (const CurveChunk::Run& r : chunk.runs) {
            tinygltf::Primitive prim;
            prim.mode = TINYGLTF_MODE_LINE_STRIP;
            prim.material = 0;
            const int pos = addAccessor(posView, size_t(r.first) * 12, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                        TINYGLTF_TYPE_VEC3, r.count, false);
            model_.accessors[size_t(pos)].minValues = {double(r.lo.x), double(r.lo.y), double(r.lo.z)};
            model_.accessors[size_t(pos)].maxValues = {double(r.hi.x), double(r.hi.y), double(r.hi.z)};
            prim.attributes["POSITION"] = pos;
            prim.attributes["_RADIUS"] =
                addAccessor(radView, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, r.count, false);
            mesh.primitives.push_back(std::move(prim));
        }
        addChunkMesh(chunk.index, chunk.origin, std::move(mesh), {});
        job_.stats.curves += chunk.runs.size();
        job_.stats.vertices += chunk.points;
        job_.stats.maxChunkVertices = std::max(job_.stats.maxChunkVertices, chunk.points);
    }

    void addMaterial() {
        tinygltf::Material m;
        m.name = "yarn";
        m.pbrMetallicRoughness.baseColorFactor = job_.options.yarnColors ? std::vector<double>{1.0, 1.0, 1.0, 1.0}
                                                                         : std::vector<double>{0.8, 0.78, 0.74, 1.0};
        m.pbrMetallicRoughness.metallicFactor = 0.0;
        m.pbrMetallicRoughness.roughnessFactor = 0.85;
        tinygltf::Value::Object sheen;
        sheen["sheenColorFactor"] = tinygltf::Value(tinygltf::Value::Array{
            tinygltf::Value(0.8), tinygltf::Value(0.8), tinygltf::Value(0.8)});
        sheen["sheenRoughnessFactor"] = tinygltf::Value(0.6);
        m.extensions["KHR_materials_sheen"] = tinygltf::Value(std::move(sheen));
        nlohmann::json extras = job_.input.materialExtras ? *job_.input.materialExtras : nlohmann::json::object();
        extras["radius"] = job_.input.radius;
        if (job_.tubes) {
            extras["tubeSides"] = job_.options.sides;
            extras["texcoord"] = "u around the tube 0..1 (seam column duplicated), v along in radius units";
            extras["tangent"] = "along the curve, w = -1 (w * cross(normal, tangent) points along +u)";
        }
        m.extras = toValue(extras);
        model_.materials.push_back(std::move(m));
        model_.extensionsUsed.push_back("KHR_materials_sheen");
    }

    std::vector<glm::u8vec4> vertexColours(const TubeMesh& mesh) const {
        std::vector<glm::u8vec4> c(mesh.vertexCount());
        for (size_t i = 0; i < c.size(); ++i) {
            const uint32_t curve = mesh.curveOfVertex[i];
            const uint32_t yarn = job_.input.yarnOfCurve ? (*job_.input.yarnOfCurve)[curve] : curve;
            c[i] = yarnColour(yarn);
        }
        return c;
    }

    int addView(const void* data, uint64_t bytes, int stride, int target) {
        tinygltf::BufferView v;
        v.buffer = sink_.buffer();
        v.byteOffset = size_t(sink_.append(data, bytes));
        v.byteLength = size_t(bytes);
        v.byteStride = size_t(stride);
        v.target = target;
        model_.bufferViews.push_back(v);
        return int(model_.bufferViews.size()) - 1;
    }

    int addAccessor(int view, size_t offset, int componentType, int type, size_t count, bool normalized) {
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

    template <class V>
    static void setBounds(tinygltf::Accessor& a, const std::vector<V>& values) {
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

    void tubePlain(const TubeMesh& m, const std::vector<glm::u8vec4>* col, tinygltf::Primitive& prim) {
        const size_t n = m.vertexCount();
        sink_.reserve(n * (48 + 4) + m.triangles.size() * 12 + 32);
        const int f = TINYGLTF_COMPONENT_TYPE_FLOAT;
        prim.attributes["POSITION"] =
            addAccessor(addView(m.positions.data(), n * 12, 0, kArrayBuffer), 0, f, TINYGLTF_TYPE_VEC3, n, false);
        setBounds(model_.accessors[prim.attributes["POSITION"]], m.positions);
        prim.attributes["NORMAL"] =
            addAccessor(addView(m.normals.data(), n * 12, 0, kArrayBuffer), 0, f, TINYGLTF_TYPE_VEC3, n, false);
        prim.attributes["TANGENT"] =
            addAccessor(addView(m.tangents.data(), n * 16, 0, kArrayBuffer), 0, f, TINYGLTF_TYPE_VEC4, n, false);
        prim.attributes["TEXCOORD_0"] =
            addAccessor(addView(m.uvs.data(), n * 8, 0, kArrayBuffer), 0, f, TINYGLTF_TYPE_VEC2, n, false);
        if (col)
            prim.attributes["COLOR_0"] = addAccessor(addView(col->data(), n * 4, 0, kArrayBuffer), 0,
                                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, n, true);
        prim.indices = addAccessor(addView(m.triangles.data(), m.triangles.size() * 12, 0, kElementArrayBuffer), 0,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                   m.triangles.size() * 3, false);
    }

    void tubeQuantized(const TubeMesh& m, const std::vector<glm::u8vec4>* col, tinygltf::Primitive& prim,
                       std::vector<double>& scale) {
        const size_t n = m.vertexCount();
        // Step: one uniform step per chunk (the node scale): q = round(p / step), |q| <= 32767.
        float maxAbs = 0.0f;
        for (const glm::vec3& p : m.positions) maxAbs = std::max({maxAbs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        const double step = maxAbs > 0 ? double(maxAbs) / 32767.0 : 1.0;
        scale = {step, step, step};
        struct S4 { int16_t v[4]; };
        std::vector<S4> qp(n), qn(n), qt(n);
        auto qs = [](double x) { return int16_t(std::lround(std::clamp(x, -32767.0, 32767.0))); };
        glm::ivec3 lo(32767), hi(-32767);
        for (size_t i = 0; i < n; ++i) {
            for (int k = 0; k < 3; ++k) {
                qp[i].v[k] = qs(double(m.positions[i][k]) / step);
                lo[k] = std::min<int>(lo[k], qp[i].v[k]);
                hi[k] = std::max<int>(hi[k], qp[i].v[k]);
                qn[i].v[k] = qs(double(m.normals[i][k]) * 32767.0);
                qt[i].v[k] = qs(double(m.tangents[i][k]) * 32767.0);
            }
            qp[i].v[3] = qn[i].v[3] = 0;
            qt[i].v[3] = m.tangents[i].w < 0 ? int16_t(-32767) : int16_t(32767);
        }
        sink_.reserve(n * (8 * 3 + 8 + 4) + m.triangles.size() * 12 + 32);
        const int s = TINYGLTF_COMPONENT_TYPE_SHORT;
        prim.attributes["POSITION"] =
            addAccessor(addView(qp.data(), n * 8, 8, kArrayBuffer), 0, s, TINYGLTF_TYPE_VEC3, n, false);
        tinygltf::Accessor& pa = model_.accessors[prim.attributes["POSITION"]];
        pa.minValues = {double(lo.x), double(lo.y), double(lo.z)};
        pa.maxValues = {double(hi.x), double(hi.y), double(hi.z)};
        prim.attributes["NORMAL"] =
            addAccessor(addView(qn.data(), n * 8, 8, kArrayBuffer), 0, s, TINYGLTF_TYPE_VEC3, n, true);
        prim.attributes["TANGENT"] =
            addAccessor(addView(qt.data(), n * 8, 0, kArrayBuffer), 0, s, TINYGLTF_TYPE_VEC4, n, true);
        prim.attributes["TEXCOORD_0"] = addAccessor(addView(m.uvs.data(), n * 8, 0, kArrayBuffer), 0,
                                                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n, false);
        size_t bytes = n * (8 * 3 + 8) + m.triangles.size() * 12;
        if (col) {
            prim.attributes["COLOR_0"] = addAccessor(addView(col->data(), n * 4, 0, kArrayBuffer), 0,
                                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, n, true);
            bytes += n * 4;
        }
        prim.indices = addAccessor(addView(m.triangles.data(), m.triangles.size() * 12, 0, kElementArrayBuffer), 0,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                   m.triangles.size() * 3, false);
        job_.stats.compressedMeshBytes += bytes;
    }

    void tubeDraco(const TubeMesh& m, const std::vector<glm::u8vec4>* col, tinygltf::Primitive& prim) {
        DracoSettings settings;
        settings.positionBits = job_.options.dracoBits;
        settings.normalBits = job_.options.dracoNormalBits;
        settings.texcoordBits = job_.options.dracoTexcoordBits;
        settings.level = job_.options.dracoLevel;
        const DracoChunk d = encodeDracoTubes(m, col, settings);
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
        if (col)
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

    void addChunkNode(size_t k, const glm::dvec3& origin, tinygltf::Primitive& prim, const std::vector<double>& scale) {
        tinygltf::Mesh mesh;
        mesh.name = "tubes " + std::to_string(k);
        mesh.primitives.push_back(std::move(prim));
        addChunkMesh(k, origin, std::move(mesh), scale);
    }

    void addChunkMesh(size_t k, const glm::dvec3& origin, tinygltf::Mesh mesh, const std::vector<double>& scale) {
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

    const FormatJob& job_;
    bool glb_;
    std::unique_ptr<CurveChunkSource> curves_;  // curve exports: where the chunks come from
    BufferSink sink_;
    tinygltf::Model model_;
    std::vector<float> radius_;  // the constant _RADIUS values, as long as the longest curve so far
};

}  // namespace

void exportGltf(const FormatJob& job, bool binary) {
    GltfBuilder builder(job, binary);
    if (job.tubes) builder.writeTubes();
    else builder.writeCurves();
    builder.finish();
}

}  // namespace knit::detail
