// knit/bound_scene.hpp — a bound rest scene saved once and loaded by every process that
// evaluates frames of it (`knit bind`, then `knit animate --bound` on any machine of a farm).
//
// The file holds what evaluation depends on, exactly (doubles bit for bit): the pattern and its
// placement, the yarn radius and UV cell size, the rest mesh (positions, UVs, faces), the binding
// (triangle, barycentrics, height, twist, colour per yarn vertex; yarn offsets and closed flags),
// the bind statistics, the ply settings, the settings the scene was built with (JSON, for
// provenance), where its strain table came from (provenance; empty: none), and (format version 2) what the
// Animator derives at bind time: the ply layout (each yarn's resampling: kept points, pieces per
// segment, resampled points), the rest arc length and twist phase of every resampled point, each
// yarn's rest pitch, length and first ply frame, the resampled points' colours; and (format
// version 3) the scene's deformation (SceneOptions::deform as knit::decideDeform chose it: the
// mode and why) with, for strain, the strain table itself (float32, the whole table: a farm
// worker needs no cache and no path of the machine that bound the scene; covered by the
// checksum) and each yarn vertex's pattern vertex (Binding::source); and (format version 4) the
// Animator's stretch references (the rest length of every yarn segment and of all yarns) and
// what the deformer did on the rest mesh (Scene::deformStats). Loading rebuilds the cheap rest
// with the same code as binding: the rest vertex normals and the UV grid; the rest yarns (the
// binding evaluated on the rest mesh, with strain displaced by the table as buildScene does)
// are evaluated lazily, on the first Scene::yarns call (an Animator never makes it: what it
// derives from them is stored), so a farm task that bakes frames does not hold them. The loaded
// scene carries the stored Animator state (Scene::animatorState), which its Animators adopt
// instead of resampling the rest yarns, and its strain deformer (Scene::deformer), which they
// apply on every frame. So a loaded scene evaluates every frame to the same bytes as the scene
// that was saved. Nothing depends on other frames.
//
// Format version 5 aligns every array (below), so that readBoundScene leaves the largest arrays
// in place in its memory map of the file instead of copying them: the Animator state's rest arc
// lengths, twist phases and segment lengths (two thirds of the file at 350 x 350; values only, never an index
// or a size). The loaded scene holds them as views that share ownership of the map, so the map
// stays open while the scene, any copy of it or an Animator of it lives. Every value is still
// checked on loading (reading the map allocates nothing). A file truncated or rewritten in place
// while it is mapped changes what the views read (a truncation ends the process with SIGBUS on
// the next read of a lost page); `knit bind` replaces files by rename, which a map survives.
//
// Layout (little-endian): a 32-byte header
//   char[8] "KNITBIND", u32 format version, u32 header size (32), u64 payload bytes,
//   u32 CRC-32 of the payload, u32 zero
// then the payload: the fields above in a fixed order, arrays as a u64 count, zero bytes up to
// the next file offset that is a multiple of 64, and the packed elements; strings as a u64 length
// and bytes. A file of another format version (version 1:
// written before the Animator state was stored; version 2: before the deformation and its table
// were; version 3: before the stretch references and deform statistics were; version 4: before
// the arrays were aligned; bind the scene again), a truncated or otherwise damaged file (size
// or checksum wrong, padding that is not zero,
// counts beyond the file, indices out of range, an embedded table that is not finite or does not
// fit the pattern) is refused with a knit::Error saying which.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "knit/budget.hpp"
#include "knit/scene.hpp"

namespace knit {

// The format this library writes and reads (a file of any other version is refused).
constexpr uint32_t kBoundSceneFormatVersion = 5;

struct BoundSceneInfo {
    uint32_t formatVersion = kBoundSceneFormatVersion;
    std::string settings;  // JSON text: the settings the scene was bound with (provenance)
    // Where the scene's strain table came from (its file or cache entry; provenance only: the
    // table itself is in the file and loads with the scene). Written: the table's source when
    // left empty. Empty: no strain table.
    std::string strainTable;
};

struct BoundScene {
    Scene scene;  // pattern, placement, mesh, normals, grid, binding, rest yarns (lazily), ply options
    BoundSceneInfo info;
};

// The bytes of a bound scene file of `rest` (a scene built by buildScene without a view;
// plies are not stored; its deformation, SceneOptions::deform, is: with strain its table). Throws knit::Error for a scene made from parts or with a view.
// The Animator's bind-time state is computed for the file (its ply points estimated against
// `budget` first) unless `rest` was loaded from such a file.
std::string encodeBoundScene(const Scene& rest, const BoundSceneInfo& info, const MemoryBudget& budget = {});
// Writes them to `path` atomically (knit/output_file.hpp).
void writeBoundScene(const std::string& path, const Scene& rest, const BoundSceneInfo& info,
                     const MemoryBudget& budget = {});

// Reads a bound scene from bytes; `name` names them in messages. Sizes are checked against the
// bytes present before anything is allocated, and the loaded scene's estimated memory against
// `budget`. Throws knit::Error "<name>: <what is wrong>".
// Every array is copied out of `bytes`.
BoundScene decodeBoundScene(std::string_view bytes, const std::string& name, const MemoryBudget& budget = {});
// The same, with the Animator state's largest arrays left in place in `bytes` (when aligned for
// their elements), which `owner` keeps valid and unchanged: the scene and its copies share it.
BoundScene decodeBoundScene(std::string_view bytes, std::shared_ptr<const void> owner, const std::string& name,
                            const MemoryBudget& budget = {});
// The same from a file (its size checked against `budget` first): mapped read-only (POSIX mmap;
// read into memory when the file cannot be mapped), its largest arrays used in place.
BoundScene readBoundScene(const std::string& path, const MemoryBudget& budget = {});

}  // namespace knit
