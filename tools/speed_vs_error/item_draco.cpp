// item_draco.cpp — item 3: Draco position quantization (ExportOptions::dracoBits). The ply tubes
// of a test scene written once as plain float32 GLB and once per setting with Draco; both files
// are read back (the library's glTF reader, gltf_document.hpp; Draco primitives decoded with the
// Draco library, timed) and every decoded vertex is matched to its original.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "io/gltf_document.hpp"
#include "items.hpp"
#include "knit/export.hpp"

namespace sve {
namespace {

struct GlbVertex {
    dvec3 p;      // world position (node transforms applied, double)
    glm::vec3 n;  // normal
};
struct GlbTubes {
    std::vector<GlbVertex> vertices;
    std::vector<double> chunkExtent;  // per primitive: largest axis extent of its positions
    double decodeSeconds = 0;
    size_t primitives = 0;
};

// Positions and normals of one tube primitive: plain accessors, or the Draco-compressed data
// decoded with the Draco library (the decoding time is added to `decodeSeconds`).
void primitiveData(const knit::gltf::Document& doc, const knit::gltf::Primitive& prim, std::vector<float>& pos,
                   std::vector<float>& nor, double& decodeSeconds) {
    const json& extensions = doc.extensions(prim);
    if (!extensions.contains("KHR_draco_mesh_compression")) {
        auto floats = [&](const char* name, std::vector<float>& dst) {
            const std::optional<size_t> index = doc.attribute(prim, name);
            if (!index) doc.fail(prim.what + " has no " + name);
            const std::vector<double> v = doc.accessor(*index, prim.what + " " + name).values();
            dst.assign(v.begin(), v.end());
        };
        floats("POSITION", pos);
        floats("NORMAL", nor);
        return;
    }
    const json& ext = extensions["KHR_draco_mesh_compression"];
    const std::string where = prim.what + ".extensions.KHR_draco_mesh_compression";
    const std::optional<size_t> view = doc.index(ext, "bufferView", where);
    if (!view) doc.fail(where + " has no bufferView");
    const knit::gltf::Bytes data = doc.bufferView(*view, where);
    const auto t0 = std::chrono::steady_clock::now();
    draco::DecoderBuffer db;
    db.Init(reinterpret_cast<const char*>(data.data), data.size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&db);
    if (!decoded.ok()) doc.fail("Draco decoding failed: " + decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    decodeSeconds += seconds(t0);
    const json& attributes = doc.member(ext, "attributes", json::value_t::object, where);
    const std::optional<size_t> p = doc.index(attributes, "POSITION", where),
                                n = doc.index(attributes, "NORMAL", where);
    const draco::PointAttribute* pa = p ? mesh->GetAttributeByUniqueId(uint32_t(*p)) : nullptr;
    const draco::PointAttribute* na = n ? mesh->GetAttributeByUniqueId(uint32_t(*n)) : nullptr;
    if (!pa || !na) doc.fail(prim.what + ": Draco primitive without POSITION/NORMAL");
    pos.resize(size_t(mesh->num_points()) * 3);
    nor.resize(pos.size());
    for (uint32_t i = 0; i < mesh->num_points(); ++i) {
        pa->GetMappedValue(draco::PointIndex(i), &pos[3 * size_t(i)]);
        na->GetMappedValue(draco::PointIndex(i), &nor[3 * size_t(i)]);
    }
}

// Reads the tube (TRIANGLES) primitives of a GLB written by knit::exportScene with the library's
// glTF reader, plain or KHR_draco_mesh_compression, with the node transforms applied.
GlbTubes readGlbTubes(const std::string& path) {
    const knit::gltf::Document doc = knit::gltf::Document::load(path);
    GlbTubes out;
    for (const knit::gltf::MeshInstance& instance : doc.meshInstances())
        for (const knit::gltf::Primitive& prim : doc.primitives(instance.mesh)) {
            if (prim.mode != knit::gltf::kTriangles) continue;  // tubes only
            std::vector<float> pos, nor;
            primitiveData(doc, prim, pos, nor, out.decodeSeconds);
            glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
            for (size_t i = 0; i < pos.size() / 3; ++i) {
                const glm::vec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
                lo = glm::min(lo, p), hi = glm::max(hi, p);
                const dvec3 world(instance.world * glm::dvec4(dvec3(p), 1.0));
                out.vertices.push_back({world, glm::vec3(nor[3 * i], nor[3 * i + 1], nor[3 * i + 2])});
            }
            out.chunkExtent.push_back(double(std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z})));
            ++out.primitives;
        }
    return out;
}

// Max distance from decoded vertices (every `stride`-th) to their original: the nearest plain
// vertex within `radius` whose normal agrees within 0.05 (neighbouring ring vertices differ by
// far more, so the true original is the one found). Unmatched vertices are counted.
struct DracoError {
    double maxError = 0;
    size_t checked = 0, unmatched = 0;
};
DracoError dracoError(const GlbTubes& plain, const GlbTubes& decoded, double radius, size_t stride) {
    DracoError e;
    const double cell = radius;
    struct Key {
        int64_t x, y, z;
        bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
    };
    struct KeyHash {
        size_t operator()(const Key& k) const {
            return size_t(k.x * 73856093) ^ size_t(k.y * 19349663) ^ size_t(k.z * 83492791);
        }
    };
    auto key = [&](const dvec3& p) {
        return Key{int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)), int64_t(std::floor(p.z / cell))};
    };
    std::unordered_map<Key, std::vector<uint32_t>, KeyHash> grid;
    for (uint32_t i = 0; i < plain.vertices.size(); ++i) grid[key(plain.vertices[i].p)].push_back(i);
    for (size_t i = 0; i < decoded.vertices.size(); i += stride) {
        const GlbVertex& v = decoded.vertices[i];
        const Key k = key(v.p);
        double best = std::numeric_limits<double>::max();
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find({k.x + dx, k.y + dy, k.z + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t j : it->second) {
                        const GlbVertex& w = plain.vertices[j];
                        if (glm::length(v.n - w.n) > 0.05f) continue;
                        best = std::min(best, glm::length(v.p - w.p));
                    }
                }
        ++e.checked;
        if (best > radius) ++e.unmatched;
        else e.maxError = std::max(e.maxError, best);
    }
    return e;
}

}  // namespace

json measureDraco(const knit::Scene& scene, const std::string& work) {
    json out;
    const double R = scene.yarnRadius();
    out["scene"] = sceneSummary(scene);
    knit::ExportOptions plain;
    plain.what = knit::ExportWhat::Tubes;
    plain.path = workFile(work, "plain.glb");
    knit::ExportStats ps;
    const Timing tp =
        timeRunsWithSetup([&] { fs::remove(plain.path); }, [&] { ps = knit::exportScene(scene, plain); }, 3, 5, 1.0);
    out["sides"] = plain.sides;
    out["plain_bytes"] = fileBytes(plain.path);
    out["plain_export_seconds"] = tp.best;
    out["tube_vertices"] = ps.vertices;
    const GlbTubes ref = readGlbTubes(plain.path);
    fs::remove(plain.path);
    for (int bits : {8, 9, 10, 11, 12, 13, 14, 15, 16}) {
        knit::ExportOptions d = plain;
        d.path = workFile(work, "draco.glb");
        d.draco = true;
        d.dracoBits = bits;
        knit::ExportStats ds;
        const Timing te =
            timeRunsWithSetup([&] { fs::remove(d.path); }, [&] { ds = knit::exportScene(scene, d); }, 2, 3, 2.0);
        const size_t bytes = fileBytes(d.path);
        double decodeBest = std::numeric_limits<double>::max();
        GlbTubes dec;
        for (int run = 0; run < 2; ++run) {
            dec = readGlbTubes(d.path);
            decodeBest = std::min(decodeBest, dec.decodeSeconds);
        }
        fs::remove(d.path);
        // Theoretical bound per chunk: half a quantization step per axis over the chunk's
        // largest extent; the search radius is 1.5 times the largest bound.
        double maxExtent = 0;
        for (double x : dec.chunkExtent) maxExtent = std::max(maxExtent, x);
        const double stepMax = maxExtent / double((1u << bits) - 1);
        const double bound = 0.5 * std::sqrt(3.0) * stepMax;
        const size_t stride = std::max<size_t>(1, dec.vertices.size() / 200000);
        const DracoError err = dracoError(ref, dec, 1.5 * bound + 1e-9, stride);
        json row;
        row["bits"] = bits;
        row["bytes"] = bytes;
        row["ratio_vs_plain"] = double(out["plain_bytes"].get<size_t>()) / double(bytes);
        row["export_seconds"] = timingJson(te);
        row["decode_seconds"] = decodeBest;
        row["decoded_vertices"] = dec.vertices.size();
        row["chunks"] = dec.primitives;
        row["max_chunk_extent_R"] = maxExtent / R;
        row["max_error_R"] = err.maxError / R;
        row["bound_R"] = bound / R;
        row["step_R"] = stepMax / R;
        row["checked_vertices"] = err.checked;
        row["unmatched_vertices"] = err.unmatched;
        out["rows"].push_back(row);
        std::fprintf(stderr,
                     "  draco %2d bits: max error %.4f R (bound %.4f R), %.1f MB (plain %.1f MB), export %.2f s, "
                     "decode %.2f s%s\n",
                     bits, err.maxError / R, bound / R, double(bytes) / 1e6, out["plain_bytes"].get<size_t>() / 1e6,
                     te.best, decodeBest, err.unmatched ? "  UNMATCHED VERTICES" : "");
    }
    return out;
}

}  // namespace sve
