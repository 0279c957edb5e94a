// knit/export.hpp — write a built scene to a file; the format follows the output extension.
//
// Formats (by extension of ExportOptions::path):
//   .obj   curves as `l i j` segment records, or tube meshes (v / vn / vt / f)
//   .ply   binary little-endian PLY: curves as vertex + edge elements, or tube meshes
//   .bcc   Cem Yuksel's BCC curves ("C0" uniform Catmull-Rom; closed curves have negative counts)
//   .pbrt  pbrt-v4 `Shape "curve"` (cylinder, cubic Bezier converted from Catmull-Rom), or
//          `Shape "trianglemesh"` for tubes
//   .gltf  glTF 2.0 JSON + external .bin buffers (<name>.bin, <name>_1.bin, ...)
//   .glb   binary glTF; the first buffer is the GLB BIN chunk, further buffers (only when the data
//          exceeds maxBufferBytes) are external <name>_1.bin, ... files next to it
//          Curves (glTF): one non-indexed LINE_STRIP per curve with POSITION and _RADIUS; a
//          closed curve repeats its first point at the end; asset.extras.attributes names _RADIUS
//          Tubes: +meshopt (EXT_meshopt_compression) and/or quantize (KHR_mesh_quantization)
// What is written is chosen by ExportOptions::what: the yarn centrelines, the ply curves, or
// swept tube meshes (of the plies when the scene has plies, else of the yarns; see tubesOf).
//
// Streaming: tube meshes are swept, written and freed chunk by chunk (at most chunkVertices
// tube vertices per chunk), so the peak memory is the scene plus a few chunks' meshes (glTF:
// chunks are swept and encoded in parallel, at most two per thread at a time, and written in
// order, so the file does not depend on the thread count). In glTF each chunk is one node whose
// translation is the chunk's local origin (double precision) and whose float32 positions are
// relative to it.
#pragma once
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

#include "knit/budget.hpp"
#include "knit/output_file.hpp"
#include "knit/scene.hpp"

namespace knit {

struct SurfaceLayer;  // knit/surface_export.hpp

enum class ExportWhat { Yarns, Plies, Tubes };
enum class TubeSource { Auto, Plies, Yarns };  // Auto: plies when the scene has any, else yarns

struct ExportOptions {
    std::string path;  // output file; extension picks the format
    ExportWhat what = ExportWhat::Plies;
    TubeSource tubesOf = TubeSource::Auto;

    // Tube meshes (what = Tubes).
    int sides = 8;     // ring vertices (>= 3; +1 seam duplicate for texturing)
    bool caps = true;  // close open curve ends

    // glTF / GLB.
    bool draco = false;          // KHR_draco_mesh_compression (tubes only)
    int dracoBits = 16;          // position quantization bits (1..30; docs/speed-vs-error.md)
    int dracoNormalBits = 10;    // normal / tangent quantization bits
    int dracoTexcoordBits = 12;  // TEXCOORD_0 quantization bits
    int dracoLevel = 7;          // Draco compression level 0 (fast) .. 10 (small)
    bool quantize = false;       // KHR_mesh_quantization (int16 positions, normals, uint16 UVs)
    bool meshopt = false;        // EXT_meshopt_compression of tube views (needs KNIT_WITH_MESHOPT)
    bool yarnColors = false;     // COLOR_0 per yarn (tubes) from a fixed palette
    bool prettyJson = false;     // indent the glTF JSON

    // Chunking: at most this many tube vertices (tubes) or curve points (curves) per chunk;
    // 0 = auto: 1M (2^20), or 256k (2^18) with Draco, whose encoder needs ~0.5 KB per vertex, or
    // 65535 with quantize / meshopt (every chunk then fits UNSIGNED_SHORT indices).
    // Streamed plies are planned per yarn from a lower bound of their point count (resampling
    // adds a few percent on curved yarns), so their chunks may exceed it slightly; a curve or
    // yarn longer than the limit gets a chunk of its own.
    size_t chunkVertices = 0;
    // Largest glTF buffer (and GLB BIN chunk); data beyond it goes to further buffers.
    uint64_t maxBufferBytes = 0xE0000000ull;  // 3.5 GiB: leaves room for the GLB JSON chunk
    // GLB: bytes reserved before the BIN data for the JSON chunk (0 = estimate from the chunk
    // count). The BIN data streams into the GLB after this gap; if the JSON turns out larger,
    // the file is rewritten once with a copy of the BIN data.
    uint64_t glbJsonReserve = 0;
    // Tube meshes: the chunks in memory at once (swept, encoded, Draco-compressed) are estimated
    // before the first is swept and refused over this budget (the CLI passes --max-memory).
    MemoryBudget budget;
};

struct ExportStats {
    std::string format;    // "obj", "ply", "bcc", "pbrt", "gltf", "glb"
    size_t curves = 0;     // curves exported (or swept)
    size_t vertices = 0;   // curve points, or tube vertices
    size_t triangles = 0;  // tube triangles (0 for curves)
    size_t chunks = 0;     // chunks written (glTF nodes; streaming steps for other formats)
    size_t maxChunkVertices = 0;
    size_t buffers = 0;                // glTF buffers written
    size_t bytes = 0;                  // total bytes of all files written
    size_t uncompressedMeshBytes = 0;  // tube attribute + index bytes before Draco/quantization
    size_t compressedMeshBytes = 0;    // the same data as written (Draco / quantized)
    size_t peakMemoryBytes = 0;        // process peak resident set (VmHWM) after export
    // A view's surface level written beside the curves (ExportInput::surface): its triangle
    // mesh's vertices and triangles and the PNG bytes of its two textures.
    size_t surfaceVertices = 0, surfaceTriangles = 0, imageBytes = 0;
    double seconds = 0;
};

// Writes atomically (temporary file in the same folder, then rename): on error no output file
// exists. Throws knit::Error for unknown extensions, unwritable paths, conflicting options, and
// what checkSceneExport() refuses (an empty result, values beyond float32), before any file is
// written.
//
// Plies of a scene built without them (SceneOptions::buildPlies = false): `what = Plies` (and
// tubes of plies) generates them from scene.yarns with scene.plyOptions during the export, the
// same curves, bit for bit, that buildPlies would have made. For .glb / .gltf the plies are
// streamed: generated, converted and written chunk by chunk on all cores, never held all at
// once (the fast path for garments; docs/speed-vs-error.md). Other formats and tubes generate
// all plies first (makePlies) and then write them.
//
// `surface` (optional): a view's surface level (the base-mesh triangles of its surface-level
// cells with the baked knit material) written into the same .glb / .gltf as one more mesh under
// the root node, with its own material and textures; other formats refuse it (knit::Error).
ExportStats exportScene(const Scene& scene, const ExportOptions& options, const SurfaceLayer* surface = nullptr);

// What no file should hold, refused (knit::Error naming the output, the value and what drives it)
// before anything is written; exportScene() calls it, and a front end may call it earlier to fail
// before other work (`knit animate` does for the point caches it writes with PointCacheWriter):
//   - a value beyond the float32 range: the yarn radius; the ply pitch and radii when plies are
//     written; the curves' coordinates in a float32 format (.bcc .pbrt .gltf .glb .pc2 .mdd);
//   - an export without a curve ("nothing to export: <why>; no file written"): a pattern without
//     edges, no yarn on the mesh, every yarn shorter than one ply sample. Not refused when
//     `surface` (a view's surface level, written beside the curves) is given.
void checkSceneExport(const Scene& scene, const ExportOptions& options, const SurfaceLayer* surface = nullptr);

// Lower-level entry: exports the given curves (yarn centrelines or plies) with constant `radius`.
// `yarnOfCurve` (optional, one entry per curve) selects the COLOR_0 palette entry and is stored;
// `materialExtrasJson` (optional: the text of a JSON object) goes into the glTF material's extras.
struct ExportInput {
    const Polylines* curves = nullptr;
    // Instead of `curves`: plies generated while writing (streamed for .glb / .gltf curves;
    // generated in full first for other formats and tubes). Exactly one of the two is set.
    const PlyGenerator* plies = nullptr;
    double radius = 0;
    const std::vector<uint32_t>* yarnOfCurve = nullptr;
    const std::vector<glm::dvec3>* seedNormals = nullptr;  // per point, tube frame seed (optional)
    // Per point, the linear yarn colour (optional; a pattern with colours): COLOR_0 in glTF (tubes
    // and curves, unless yarnColors), vertex colours in PLY, per-curve colours in pbrt.
    const std::vector<glm::vec3>* colours = nullptr;
    // glTF material extras as JSON object text, e.g. {"generator":"libknit"} (empty: none; the
    // exporter adds radius and tube fields). Anything but a JSON object is a knit::Error.
    std::string materialExtrasJson;
    // A view's surface level written beside the curves (.glb / .gltf only; see exportScene).
    const SurfaceLayer* surface = nullptr;
};
ExportStats exportCurves(const ExportInput& input, const ExportOptions& options);

// True when these options stream generated plies (ply curves into .glb / .gltf): the scene can
// then be built with SceneOptions::buildPlies = false, which costs far less time and memory.
bool streamsPlies(const ExportOptions& options);

// Checks the options against each other and the extension; throws knit::Error naming the
// conflict (e.g. Draco compression of curves, Draco compression with mesh quantization, Draco for a
// non-glTF format) and the settings in words (knit/setting_spelling.hpp).
void validateExportOptions(const ExportOptions& options);

}  // namespace knit
