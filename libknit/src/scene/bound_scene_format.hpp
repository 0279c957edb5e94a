// bound_scene_format.hpp (internal) — the payload layout of a bound scene file
// (knit/bound_scene.hpp), described once (boundSceneLayout) and walked by the writer and the
// reader, so the two cannot disagree on the order or the width of a field.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <isa-l/crc.h>

#include "animation/animator_bind_state.hpp"
#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/pattern.hpp"
#include "knit/plies.hpp"
#include "knit/strain.hpp"
#include "knit/tiling.hpp"

namespace knit::impl {

// Packed arrays are copied as bytes: the file is little-endian.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "bound scene files are written on little-endian hosts");
static_assert(sizeof(size_t) == 8, "counts are stored as 64-bit values");

constexpr char kBoundSceneMagic[8] = {'K', 'N', 'I', 'T', 'B', 'I', 'N', 'D'};
constexpr size_t kBoundSceneHeaderBytes = 32;

// Format version 5: every array's elements start at a file offset that is a multiple of 64
// (zero bytes between its count and its first element), so that a reader can use them in place
// in a memory map of the file (aligned for any element type, and to cache lines).
constexpr size_t kBoundSceneArrayAlignment = 64;
// The zero bytes in front of an array whose elements would otherwise start at `fileOffset`.
inline size_t arrayPadding(size_t fileOffset) {
    return (kBoundSceneArrayAlignment - fileOffset % kBoundSceneArrayAlignment) % kBoundSceneArrayAlignment;
}

// The CRC-32 (zlib's: the polynomial of gzip and PNG) of a payload, by ISA-L (the same value as
// zlib's crc32, ~3x faster: it was a third of a load).
inline uint32_t payloadCrc32(const char* data, size_t size) {
    return crc32_gzip_refl(0, reinterpret_cast<const unsigned char*>(data), size);
}

// What the file stores (the rest is rebuilt on loading).
struct BoundSceneParts {
    std::string settings, strainTable;
    Pattern pattern;
    PatternPlacement placement;
    BaseMesh mesh;
    Binding binding;
    BindStats stats;
    PlyOptions plies;
    AnimatorBindState animator;  // format version 2
    // Format version 3: the deformation the scene was bound with (knit::decideDeform), and with
    // strain its table, embedded whole, and each yarn vertex's pattern vertex (Binding::source,
    // which the deformer looks the table up by; empty with none).
    uint32_t deformMode = 0;    // DeformMode
    uint32_t deformReason = 0;  // DeformReason
    double tableSeconds = 0;    // DeformOptions::tableSeconds
    StrainTable table;          // empty (no samples, no data) with none
    // Format version 4: what the deformer did on the rest mesh (Scene::deformStats), stored so
    // that loading need not evaluate the rest yarns (Scene::yarns evaluates them when asked).
    DeformStats deformStats;
};

// The fields in file order; `io` has value(x, what), array(v, what) (a std::vector or a
// util::SharedArray: the Animator state's rest arc lengths, twist phases and segment lengths,
// which a reader may leave in place in the file), text(s, what) and blocks(map, what), for
// `P` = const BoundSceneParts (writing) or BoundSceneParts (reading). Arrays: a u64 count, zero
// bytes up to the next multiple of 64 of the file offset (arrayPadding), the packed elements.
template <class IO, class P>
void boundSceneLayout(IO& io, P& p) {
    io.text(p.settings, "the settings");
    io.text(p.strainTable, "the strain table reference");
    // The pattern.
    io.text(p.pattern.name, "the pattern name");
    io.value(p.pattern.px, "the pattern period");
    io.value(p.pattern.py, "the pattern period");
    io.value(p.pattern.radius, "the pattern yarn radius");
    io.array(p.pattern.points, "the pattern points");
    io.array(p.pattern.twist, "the pattern twists");
    io.array(p.pattern.edges, "the pattern edges");
    io.value(p.pattern.stitchesPerPeriod, "the pattern stitches per period");
    io.value(p.pattern.rowsPerPeriod, "the pattern rows per period");
    io.array(p.pattern.colour, "the pattern colours");
    io.blocks(p.pattern.extraBlocks, "the pattern's extra blocks");
    // Its placement on the mesh.
    io.value(p.placement.repeats, "the repeats");
    io.value(p.placement.scale, "the placement scale");
    io.value(p.placement.periodMetres, "the period in metres");
    // The rest mesh.
    io.text(p.mesh.name, "the mesh name");
    io.array(p.mesh.positions, "the mesh positions");
    io.array(p.mesh.uvs, "the mesh UVs");
    io.array(p.mesh.faces, "the mesh faces");
    io.array(p.mesh.faceUvs, "the mesh face UVs");
    // The binding and its statistics.
    io.array(p.binding.face, "the binding triangles");
    io.array(p.binding.bary, "the binding barycentrics");
    io.array(p.binding.height, "the binding heights");
    io.array(p.binding.twist, "the binding twists");
    io.array(p.binding.colour, "the binding colours");
    io.array(p.binding.offsets, "the yarn offsets");
    io.array(p.binding.closed, "the yarn closed flags");
    io.value(p.stats, "the bind statistics");
    // The ply settings (as the scene holds them: resolved by the evaluation).
    io.value(p.plies.count, "the number of plies");
    io.value(p.plies.yarnRadius, "the ply yarn radius");
    io.value(p.plies.centerRadius, "the ply centre radius");
    io.value(p.plies.plyRadius, "the ply radius");
    io.value(p.plies.pitch, "the ply pitch");
    io.value(p.plies.twist, "the twist direction");
    io.value(p.plies.samplesPerTurn, "the samples per turn");
    // The Animator's bind-time state (format version 2): what evaluation derives from the rest
    // yarns and ply settings, stored so that loading does not resample the rest yarns again.
    auto& a = p.animator;  // const for the writer
    io.array(a.keptOffsets, "the resampling layout's kept point offsets");
    io.array(a.kept, "the resampling layout's kept points");
    io.array(a.pieceOffsets, "the resampling layout's piece offsets");
    io.array(a.pieces, "the resampling layout's pieces");
    io.array(a.centreOffsets, "the resampled point offsets");
    io.array(a.restArc, "the rest arc lengths");
    io.array(a.restPhase, "the rest twist phases");
    io.array(a.restPitch, "the rest pitches");
    io.array(a.restLength, "the rest yarn lengths");
    io.array(a.seeds, "the frame seeds");
    io.array(a.centreColour, "the resampled points' colours");
    // The deformation (format version 3): the mode and why it was chosen, the binding's pattern
    // vertices, and the strain table the frames are deformed with (the whole table: a farm worker
    // needs no cache and no path of the machine that bound the scene).
    io.value(p.deformMode, "the deform mode");
    io.value(p.deformReason, "the deform reason");
    io.value(p.tableSeconds, "the strain table's seconds");
    io.array(p.binding.source, "the binding's pattern vertices");
    auto& t = p.table;  // const for the writer
    io.text(t.source, "the strain table's source");
    io.text(t.pattern, "the strain table's pattern");
    io.value(t.px, "the strain table's period");
    io.value(t.py, "the strain table's period");
    io.value(t.radius, "the strain table's yarn radius");
    io.value(t.vertexCount, "the strain table's vertex count");
    io.array(t.axes[0], "the strain table's sx samples");
    io.array(t.axes[1], "the strain table's sa samples");
    io.array(t.axes[2], "the strain table's sy samples");
    io.array(t.data, "the strain table's data");
    // Format version 4: the Animator's stretch references (each rest yarn segment's length, all
    // of them together) and the deformer's statistics on the rest mesh: with them, a loaded scene
    // and its Animators need nothing of the rest yarns, which Scene::yarns evaluates lazily.
    io.array(a.restSegment, "the rest segment lengths");
    io.value(a.restTotalLength, "the rest yarns' total length");
    io.value(p.deformStats, "the deform statistics");
}

}  // namespace knit::impl
