// knit/strain.hpp — strain-aware deformation of the yarns (Sperl, Narain, Wojtan, "Mechanics-Aware
// Deformation of Yarn Pattern Geometry", SIGGRAPH 2021): where the cloth is stretched, sheared or
// compressed against the pattern's rest layout, the yarns slide and bend as the pattern's own
// relaxation says instead of stretching with the surface.
//
// Strain convention (the published one): F maps pattern space (x along courses, y along wales, at
// the pattern's period times the placement's scale) to 3D, C = F^T F, and
//   sx = sqrt(C00) - 1,  sy = sqrt(C11) - 1,  sa = C01 / ((1 + sx)(1 + sy))
// (sa: the cosine of the angle between the deformed axes). A strain table holds, per cell vertex
// and strain sample, the displacement D = (dx, dy, dz, dtwist) in the pattern's reference space
// and units: the vertex goes to F (X + D) plus its height (z + dz) along the normal.
//
// Table files (documented in docs/deformation.md):
//  * the project's own: `T.npy`, NumPy format 1.0, float32 little-endian, shape (Nv Nx Na Ny, 4),
//    row isx + Nx isa + Nx Na isy + Nx Na Ny vertex, columns dx dy dz dtwist (metres of the
//    pattern file), and beside it `T.axes.txt`: three lines of sample values (sx, sa, sy) after
//    `#` lines naming the pattern, its vertex count, period and radius;
//  * MADYPG's published tables, a folder `sxsasy/` holding `axes.txt` (the three lines) and
//    `data.npy` in the same layout.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec4.hpp>

#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/pattern.hpp"
#include "knit/tiling.hpp"

namespace knit {

struct Strain {
    double sx = 0, sa = 0, sy = 0;
};
// The strain of a first fundamental form C (symmetric 2 x 2).
Strain strainOf(const glm::dmat2& C);
// A lattice map with that strain: F = [(1+sx, 0), (1+sy)(sa, sqrt(1 - sa^2))] (columns).
glm::dmat2 latticeMap(const Strain& s);

struct StrainTable {
    std::string source;                       // file or folder, for messages
    std::array<std::vector<double>, 3> axes;  // sample values of sx, sa, sy (strictly increasing)
    size_t vertexCount = 0;
    std::vector<float> data;  // 4 per row, rows as in the file comment
    // The project's own tables: the pattern they were made for (empty / 0 for MADYPG's tables).
    std::string pattern;
    double px = 0, py = 0, radius = 0;

    size_t samples() const { return axes[0].size() * axes[1].size() * axes[2].size(); }
};

// The displacement of `vertex` at strain s, trilinear in the table; strains outside the axes are
// clamped to them (*clamped set), never extrapolated.
glm::dvec4 lookupStrainTable(const StrainTable& table, uint32_t vertex, const Strain& s, bool* clamped = nullptr);

// ---- making tables ---------------------------------------------------------------------------

struct StrainTableOptions {
    std::array<int, 3> samples{9, 9, 9};  // along sx, sa, sy
    std::array<double, 2> sxRange{-0.2, 1.0}, saRange{-0.7, 0.7}, syRange{-0.2, 1.0};
    // The yarn-level solver on the deformed lattice, period fixed (docs/deformation.md): the yarn's
    // stretch weight (ten times chart relaxation's: close to inextensible), bending, the contact
    // penalty below contactDistance radii and the contact barrier below barrierDistance radii.
    double stretch = 2000, bend = 1, contact = 400, barrier = 2000;
    double contactDistance = 2.05, barrierDistance = 1.25;
    int maxIterations = 600;
    // Each sample is relaxed from this many of its relaxed neighbours one step closer to zero
    // strain (1 to 3; the lowest energy kept): 1 is the parent alone.
    int startsPerSample = 1;
    // Called after each sample with the samples done and the total (from worker threads, serialised).
    std::function<void(size_t done, size_t total)> progress;
};

struct StrainTableStats {
    double seconds = 0;          // wall time
    size_t samples = 0;          // relaxations (the rest cell included)
    size_t unconverged = 0;      // stopped at the iteration cap
    size_t iterations = 0;       // Newton iterations over every sample (the rest cell's not counted)
    size_t stages = 0;           // lattice stages relaxed over every sample (strainTableStages)
    double minDistance = 0;      // closest distinct yarns over every sample, in yarn radii
    double restMinDistance = 0;  // of the relaxed rest cell
};

// Throws knit::Error for options out of range (sample counts 1..64 per axis, ranges increasing and
// within sx, sy > -1, |sa| < 1) or a pattern relaxation cannot use (open yarns).
StrainTable makeStrainTable(const Pattern& pattern, const StrainTableOptions& options,
                            StrainTableStats* stats = nullptr);
// Seconds the whole table is expected to take on this machine's idle cores: Newton iterations of
// the cell timed (thread CPU time), times the table's lattice stages (strainTableStages) and the
// work per stage measured on a whole table of the same solver path (dense: the default
// stockinette; sparse, over 64 cell vertices: chart:basketweave), plus the serial rest cell.
double estimateStrainTableSeconds(const Pattern& pattern, const StrainTableOptions& options);
// The lattice stages a table's relaxations go through: per sample, from the lattice of each
// neighbour it starts from to its own (each stage changes the map by at most a tenth of its
// smallest singular value). A table's time grows with this count, not with its samples: a coarse
// grid takes larger steps between samples, in more stages each (3 x 3 x 3: 320 stages for 27
// samples; the default 9 x 9 x 9: 1791 for 729).
size_t strainTableStages(const StrainTableOptions& options);

// One cell relaxed on the lattice of `strain` by the tables' solver (`solver`'s weights and
// iteration cap; from the pattern's own cell through the lattice stages), its rest lengths
// `restLengthScale` times the pattern's edges (below 1 the yarn is under tension and pulls itself
// taut: tools/strain_bound). The cell's yarn length over the pattern's own, its closest
// centrelines in yarn radii.
struct StrainCellResult {
    double lengthRatio = 1, closestRadii = 0;
    int iterations = 0;
    bool converged = false;
};
StrainCellResult relaxStrainCell(const Pattern& pattern, const Strain& strain, const StrainTableOptions& solver,
                                 double restLengthScale = 1);

// ---- files -------------------------------------------------------------------------------------

// `path` (.npy) and its axes file (strainAxesPath), both written atomically (knit/output_file.hpp).
void writeStrainTable(const StrainTable& table, const std::string& path);
std::string strainAxesPath(const std::string& npyPath);  // T.npy -> T.axes.txt
// A table file (with its axes file) or a MADYPG folder (axes.txt + data.npy). Throws knit::Error
// naming the file and what is wrong (header, shape, dtype, non-finite values, axes).
StrainTable loadStrainTable(const std::string& path);
// The parser behind it, on bytes: `npy` the .npy file, `axes` the axes text.
StrainTable parseStrainTable(const std::string& npy, const std::string& axes, const std::string& source);
// Throws knit::Error naming the table unless it fits the pattern: its vertex count, and for the
// project's own tables its period (relative 1e-6).
void checkStrainTable(const StrainTable& table, const Pattern& pattern);

// ---- cached tables -----------------------------------------------------------------------------

// A pattern's table kept in the cache folder (knit/chart_cache.hpp's chartCacheDir: $KNIT_CACHE_DIR,
// $XDG_CACHE_HOME/libknit or ~/.cache/libknit) as strain-<16 hex digits>.npy and its axes file; key:
// FNV-1a 64 of the pattern (as .pyp text) and every table option.
struct CachedStrainTable {
    std::shared_ptr<const StrainTable> table;
    std::string path;    // the cache entry ("" when there is no cache folder)
    bool made = false;   // not in the cache: made now (and stored, when it could be)
    double seconds = 0;  // making it took (wall)
};
std::string strainCacheKey(const Pattern& pattern, const StrainTableOptions& options);
// The pattern's table from the cache, else `make()` (default: makeStrainTable(pattern, options))
// stored there atomically (a failure to store is not an error; an unreadable or mismatched entry
// is made again and replaced).
CachedStrainTable cachedStrainTable(const Pattern& pattern, const StrainTableOptions& options = {},
                                    const std::function<StrainTable()>& make = {});
// The cached table if there is one (table empty otherwise); never makes one.
CachedStrainTable findCachedStrainTable(const Pattern& pattern, const StrainTableOptions& options = {});

// ---- applying tables ---------------------------------------------------------------------------

enum class DeformMode { None, Strain };

// Why a scene deforms as it does (decideDeform; reports say it in their own words).
enum class DeformReason {
    Asked,          // the caller chose the mode (none, or strain with a table it gave)
    TableGiven,     // a table given, no mode asked: strain
    Cached,         // strain: the pattern's table was in the cache
    Made,           // strain: the pattern's table was made now (asked for, or quick to make) and cached
    TooSlowToMake,  // none: no table at hand and making one would take minutes
    CannotMake,     // none: the pattern cannot be relaxed into a table (open yarns, too few vertices)
};

// How a scene deforms its yarns (SceneOptions::deform): `None` maps them geometrically; `Strain`
// adds `table`'s displacements (which must then be given).
struct DeformOptions {
    DeformMode mode = DeformMode::None;
    std::shared_ptr<const StrainTable> table;
    DeformReason reason = DeformReason::Asked;  // for reports; does not change the result
    double tableSeconds = 0;  // for reports: Made, the seconds making the table took; TooSlowToMake, the estimate
};

// ---- choosing the deformation (one rule for every front end) ----------------------------------

// What the caller asked for: Auto (the default), None or Strain.
enum class DeformChoice { Auto, None, Strain };

// A pattern's table is quick to make (under a minute, so Auto makes it on first use) when its cell
// vertices times its samples are at most this: 32 cell vertices at the default 9 x 9 x 9. A
// count, not a timing, so that the choice (and the output) is the same on any machine and under
// any load. The table solver's cost grows about as the cube of the cell's vertices (dense damped
// Newton). Measured on this 2-core machine with the stiff-yarn solver: the default stockinette
// (24 vertices) 13.0 s CPU, 29.5 s wall at load 3.5 (`knit strain-table --pattern stockinette -o
// T.npy`); estimates printed by `knit build --pattern satin.pyp` (130 vertices): about 2200 s.
// (The first threshold, 96 vertices, was set against the earlier, ~9x cheaper solver.)
constexpr double kQuickStrainTableWork = 32.0 * 729.0;
bool strainTableIsQuick(const Pattern& pattern, const StrainTableOptions& options = {});

struct DeformDecision {
    DeformOptions deform;      // the mode, its table and why
    CachedStrainTable cached;  // Cached / Made: the cache entry, whether it was made and how long it took
    std::string whyNot;        // CannotMake: what the table maker said
};

// The one rule behind every front end's default (`--deform`, Python's deform=, Blender's Deform):
//  * None: geometric (Asked);
//  * a table given: strain with it (Asked when Strain was chosen, else TableGiven);
//  * Strain: the pattern's cached table, else made now and cached (Cached / Made);
//  * Auto: the cached table if there is one (Cached), else made now when strainTableIsQuick
//    (Made), else none with the estimate (TooSlowToMake; the caller names the command that makes
//    the table); none also for a pattern no table can be made for (CannotMake).
// A table made for a pattern is the same bytes whether made now or read from the cache, so Auto's
// output does not depend on what is cached. `make` makes the table (default: makeStrainTable),
// for progress output.
DeformDecision decideDeform(const Pattern& pattern, DeformChoice choice, std::shared_ptr<const StrainTable> given = {},
                            const std::function<StrainTable()>& make = {});

struct DeformStats {
    size_t vertices = 0;    // yarn vertices displaced (strain away from zero)
    size_t clamped = 0;     // yarn vertices whose strain lay outside the table (clamped)
    size_t degenerate = 0;  // yarn vertices on a triangle whose strain is undefined (zero displacement)
    size_t total = 0;       // yarn vertices looked at
};

// Where a strain deformer looks its table up. MeshVertices: once per UV vertex of the mesh and cell
// vertex, at the UV vertex's strain, the displacements (through F) then interpolated per yarn vertex
// (few lookups where many yarn vertices share a triangle, as on any garment at its gauge);
// YarnVertices: per yarn vertex at its interpolated strain (the reference; fewer lookups on a mesh
// finer than the pattern's cells). Both are continuous across triangle edges and agree to second
// order in the strain's change across a triangle. Auto: whichever looks up less.
enum class StrainLookupSite { Auto, MeshVertices, YarnVertices };

// Strain-aware deformation of one scene's yarns, set up once on the rest mesh and applied per pose.
class StrainDeformer {
public:
    // `mesh`: the rest mesh (its UVs give the pattern-space layout through `placement`);
    // `binding`: its binding (Binding::source must be filled); the table must fit `pattern`.
    // Throws knit::Error naming the table when it does not fit.
    StrainDeformer(const BaseMesh& mesh, const Pattern& pattern, const PatternPlacement& placement,
                   const Binding& binding, std::shared_ptr<const StrainTable> table,
                   StrainLookupSite site = StrainLookupSite::Auto);

    // Adds the table's displacement to `yarns` (evaluateBinding(binding, ...) on `positions`, the
    // same connectivity as the rest mesh), and its twist change to yarns.twist (the plies add it to
    // their phase; empty when the table has no twist). Zero strain leaves every point bit for bit.
    DeformStats apply(const Binding& binding, const std::vector<glm::dvec3>& positions, MappedYarns& yarns) const;

    // evaluateBinding and apply in one pass over the yarn vertices (the per-frame path; the same
    // bits as the two calls; four yarn vertices at a time in AVX2 where the CPU has it, as
    // evaluateBinding). `normals`: the pose's vertex normals. `withTwist` false: out.twist left
    // empty (for a caller that makes no plies; the points are the same).
    DeformStats evaluate(const Binding& binding, const std::vector<glm::dvec3>& positions,
                         const std::vector<glm::dvec3>& normals, MappedYarns& out, bool withTwist = true) const;

    const StrainTable& table() const { return *table_; }

private:
    struct Pose;  // per pose: the strain and map per UV vertex, which triangles have one
    Pose pose(const Binding& binding, const std::vector<glm::dvec3>& positions) const;
    struct MeshRows;  // per pose at the UV vertices: displacements, twists, per triangle its corners
    // The last phase: `point(i, p, n)` gives yarn vertex i's geometric point and normal and
    // returns where the displaced point goes; `block(begin, end, rows)` may do a range's first
    // vertices itself (returns the first it left). With `withTwist`, yarns.twist too.
    template <class Point, class Block>
    DeformStats run(const Binding& binding, const Pose& pose, Point point, Block block, MappedYarns& yarns,
                    bool withTwist) const;
    template <class Point, class Block>
    DeformStats runAtMeshVertices(const Binding& binding, const MeshRows& rows, Point point, Block block) const;
    template <class Point>
    DeformStats runAtYarnVertices(const Binding& binding, const Pose& pose, Point point) const;
    // The boundary ends (findBoundaryEnds) moved on from their displacement (`displacement(i, v,
    // n, e)` as in run) by t times the difference to the next vertex's.
    template <class Point, class Displacement>
    void moveEnds(const Point& point, const Displacement& displacement) const;
    // MeshVertices: per UV vertex and cell vertex, the displacement through F (x, y, z) and along
    // the normal (w) and (with `withTwist`) the twist change; per triangle its corners' rows and flag.
    MeshRows meshRows(const Pose& pose, bool withTwist) const;
    void meshDisplacements(const Pose& pose, bool withTwist, MeshRows& rows, std::vector<uint8_t>& flags) const;
    DeformStats rowStats(const MeshRows& rows) const;  // per triangle: its yarn vertices times its flag
    // Per yarn vertex the table's twist change (into yarns.twist), when the table has any (else
    // yarns.twist is left empty): looked up at its strain (YarnVertices) or interpolated from its
    // triangle's UV vertices' (MeshVertices).
    void twist(const Binding& binding, const Pose& pose, MappedYarns& yarns) const;
    void twist(const Binding& binding, const MeshRows& rows, MappedYarns& yarns) const;
    void findBoundaryEnds(const Pattern& pattern, const Binding& binding);  // into ends_

    std::vector<glm::uvec3> faces_, faceUvs_;
    std::vector<glm::dvec2> layout_;      // per UV vertex: pattern-space position (metres, object scale)
    std::vector<uint32_t> cellVertex_;    // per yarn vertex: its pattern vertex
    std::vector<uint32_t> faceVertices_;  // per triangle: the yarn vertices bound to it
    // A yarn cut at the mesh's boundary ends on a vertex inserted on the boundary edge, partway
    // (t) from the pattern vertex it leaves (its cellVertex_) to the next one (beyond): its
    // displacement is blended between the two, as the cell's segment there is (without it, a
    // stiff table's ends stuck out by t times the two vertices' difference: strainEnds).
    struct BoundaryEnd {
        uint32_t vertex = 0, beyond = 0;
        double t = 0;
    };
    std::vector<BoundaryEnd> ends_;
    std::vector<glm::dvec4> zero_;  // per pattern vertex: the table at zero strain
    double scale_ = 1;
    size_t uvCount_ = 0, positionCount_ = 0;
    bool atMeshVertices_ = false;
    bool hasTwist_ = false;  // some twist in the table differs from its vertex's zero-strain twist
    std::shared_ptr<const StrainTable> table_;
};

}  // namespace knit
