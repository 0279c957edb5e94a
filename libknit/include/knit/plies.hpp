// knit/plies.hpp — plies twisted around the mapped yarns, in object space.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "knit/binding.hpp"

namespace knit {

namespace impl {
struct PlyKernel;  // the per-yarn steps of PlyGenerator (internal: libknit/src/plies/plies_kernel.hpp)
}

// Yarn held vertical: S strands slant like the middle of "S" (a left-handed helix,
// theta = -2 pi s / pitch with B = T x N), Z strands like the middle of "Z" (right-handed,
// theta = +2 pi s / pitch).
enum class Twist : uint8_t { S, Z };

struct PlyOptions {
    int count = 2;              // plies per yarn
    double yarnRadius = 0.001;  // metres (the pipeline sets it from the pattern)
    // 0 = touching plies that fill the yarn: centre radius R/(1 + sin(pi/n)), ply radius
    // centreRadius * sin(pi/n).
    double centerRadius = 0.0;
    double plyRadius = 0.0;
    double pitch = 0.0;  // length of one full ply turn (metres); 0 = 6 yarn radii
    Twist twist = Twist::S;
    int samplesPerTurn = 12;  // resampling density of the yarn centreline (knee: docs/speed-vs-error.md)
};

struct Plies {
    Polylines curves;
    std::vector<uint32_t> yarnOfCurve;  // source yarn of each ply curve
    std::vector<uint8_t> plyOfCurve;    // ply index i in [0, count)
    double plyRadius = 0.0;
    double centerRadius = 0.0;
    double pitch = 0.0;  // effective pitch of open yarns
    // Per ply point: the unit radial direction from the yarn centre (the ply's outward normal
    // reference; a renderer derives the ply phase from it).
    std::vector<glm::dvec3> radial;
    // Per ply point: the linear yarn colour at that arc position of its yarn; empty when the
    // yarns have no colours.
    std::vector<glm::vec3> colour;
};

// Resolved option values (auto radii / pitch filled in); throws knit::Error on invalid options.
PlyOptions resolvePlyOptions(const PlyOptions& options);

// Resamples each yarn to `samplesPerTurn` points per ply turn, builds rotation-minimizing
// frames seeded with the surface normal and sweeps the helices
//   c_i(s) = C(s) + R (cos(theta + 2 pi i / n) N + sin(theta + 2 pi i / n) B),
//   theta = +-2 pi s / pitch.
// On closed yarns the number of turns is rounded so the helix closes with no twist jump.
Plies makePlies(const MappedYarns& yarns, const PlyOptions& options);

// Reusable buffers of PlyGenerator::generate (one per thread; allocated on first use, kept
// between calls). Movable, not copyable.
class PlyScratch {
public:
    PlyScratch();
    ~PlyScratch();
    PlyScratch(PlyScratch&&) noexcept;
    PlyScratch& operator=(PlyScratch&&) noexcept;

private:
    friend struct impl::PlyKernel;
    struct Buffers;
    std::unique_ptr<Buffers> buffers_;
};

// The plies of a yarn set, batch by batch: what makePlies computes, for consumers that never
// need all plies at once (the streaming glTF export writes each batch and drops it). Every yarn
// is independent, so any batching gives the same curves as makePlies, bit for bit.
class PlyGenerator {
public:
    // Resolves and validates the options and validates the yarns (finite points and normals,
    // consistent offsets); throws knit::Error. Keeps a reference to `yarns`.
    PlyGenerator(const MappedYarns& yarns, const PlyOptions& options);

    const PlyOptions& options() const { return options_; }  // resolved
    size_t yarnCount() const { return yarns_.curves.curveCount(); }
    // A lower bound of the ply points of yarn `y` (count * resampled points); for planning.
    size_t estimatePoints(size_t y) const;
    // Replaces `out` with the plies of yarns [first, last): curves yarn-major and ply-minor,
    // yarnOfCurve holds the yarns' global indices. Const and thread-safe (one scratch per
    // thread); never throws except std::bad_alloc. `withRadial = false` leaves out.radial
    // empty (for consumers of the curves alone: less memory traffic).
    void generate(size_t first, size_t last, Plies& out, PlyScratch& scratch, bool withRadial = true) const;

    const MappedYarns& yarns() const { return yarns_; }

private:
    friend struct impl::PlyKernel;
    struct TopologyOnly {};
    // Options resolved and validated, `yarns` taken as they are (impl::PlyKernel::replayGenerator).
    PlyGenerator(const MappedYarns& yarns, const PlyOptions& options, TopologyOnly);
    const MappedYarns& yarns_;
    PlyOptions options_;
    double spacing_ = 0;
    double cosPly_[16] = {}, sinPly_[16] = {};  // phase offsets 2 pi i / count of the plies
};

// All plies of the generator's yarns (what makePlies(yarns, options) returns).
Plies makePlies(const PlyGenerator& generator);

}  // namespace knit
