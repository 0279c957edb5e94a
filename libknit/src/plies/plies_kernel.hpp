// plies_kernel.hpp (internal) — the two per-yarn steps of PlyGenerator (plies.cpp): resample a
// yarn's centreline, then sweep its plies around it. PlyGenerator::generate runs both per yarn;
// makePlies runs the first for all yarns, lays the plies out, then runs the second in place.
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/frames.hpp"
#include "knit/plies.hpp"
#include "resample_curve.hpp"

namespace knit {

struct PlyScratch::Buffers {
    ResampleScratch resample;
    ResampleLayout layout;  // of the last centreline with colours
    std::vector<glm::dvec3> centre, tangent, normal;
    std::vector<glm::vec3> colour;  // per centre point, when the yarns have colours
    std::vector<double> arc;
    std::vector<double> twist;       // per centre point, when the yarns have twist (MappedYarns::twist)
    std::vector<float> frameFloats;  // curveFrames' float copies (FramePrecision::Float32)
};

namespace impl {

struct PlyKernel {
    // A generator that only replays a stored bind state (the Animator of a loaded bound scene):
    // `topology` holds the yarns' offsets and closed flags but no points, so only the options,
    // twistRate and sweepWithCosSin (which read the closed flags) may be used with it, never
    // generate, centreline, sweep or estimatePoints. Keeps a reference to `topology`.
    static PlyGenerator replayGenerator(const MappedYarns& topology, const PlyOptions& options);
    // The resampling spacing of the generator's yarns (pitch / samplesPerTurn).
    static double spacing(const PlyGenerator& generator) { return generator.spacing_; }
    // The buffers of `scratch`, allocated on first use.
    static PlyScratch::Buffers& buffers(PlyScratch& scratch);
    // The resampled centreline of yarn `y`, appended to `centre`, and its colours appended to
    // `colour` (when not null and the yarns have colours); returns its point count (< 2 means no
    // plies).
    // Likewise its twist (radians, per centre point) appended to `twist` when not null and the
    // yarns have twist. `layout`, when not null, receives the resampling's decisions (piecePlies
    // places a view's pieces on the resampled yarn with it).
    static size_t centreline(const PlyGenerator& generator, size_t y, std::vector<glm::dvec3>& centre,
                             PlyScratch& scratch, std::vector<glm::vec3>* colour = nullptr,
                             std::vector<double>* twist = nullptr, ResampleLayout* layout = nullptr);
    // The centre colours (m per yarn) repeated for each of the `count` plies: ply i's point j
    // goes to out[i * m + j].
    static void plyColours(const glm::vec3* colour, size_t m, uint32_t count, glm::vec3* out);
    // The `count` plies of yarn `y` swept around its m-point centreline: ply i's point j goes to
    // points[i * m + j] (and its unit radial direction to radial[i * m + j] unless radial is null);
    // `twist` (m values, or null) is added to the ply phase.
    static void sweep(const PlyGenerator& generator, size_t y, const glm::dvec3* centre, size_t m, glm::dvec3* points,
                      glm::dvec3* radial, PlyScratch& scratch, const double* twist = nullptr);
    // sweep's two parts (animation replays the second with the rest pose's phase): the arc length
    // of each centre point (written to `arc`) and the twist pitch (closed yarns: a whole number of
    // turns) ...
    static double arcAndPitch(const PlyGenerator& generator, size_t y, const glm::dvec3* centre, size_t m,
                              std::vector<double>& arc);
    // ... and the helices with a given arc length per point and pitch, and frame seed (the
    // surface normal at the first point, or null).
    static void sweepWithPhase(const PlyGenerator& generator, size_t y, const glm::dvec3* centre, size_t m,
                               const double* arc, double pitch, const glm::dvec3* seed, glm::dvec3* points,
                               glm::dvec3* radial, PlyScratch& scratch, const double* twist = nullptr);
    // Rotation-minimizing frames of a centreline into buf.tangent / buf.normal (seeds as below).
    static void frames(const PlyGenerator& generator, size_t y, const glm::dvec3* centre, size_t m,
                       const glm::dvec3* seed, const glm::dvec3* seedTangent, PlyScratch::Buffers& buf,
                       FramePrecision precision = FramePrecision::Double);
    // dtheta/ds of the helices for a pitch (signed by the twist).
    static double twistRate(const PlyGenerator& generator, double pitch);
    // The same helices for any pose of yarn `y` with the twist phase given per point as
    // (cos theta, sin theta) (animation: computed once from the rest pose, so the phase stays
    // attached to the yarn material), and the frame seed: the surface normal at the first point,
    // or null; with seedTangent, a normal carried over from another pose and transported onto
    // the first tangent (see curveFrames). `precision`: the frames' transport (FrameOptions).
    static void sweepWithCosSin(const PlyGenerator& generator, size_t y, const glm::dvec3* centre, size_t m,
                                const glm::dvec2* phase, const glm::dvec3* seed, const glm::dvec3* seedTangent,
                                glm::dvec3* points, PlyScratch& scratch, glm::dvec3* radial = nullptr,
                                FramePrecision precision = FramePrecision::Double);
};

}  // namespace impl
}  // namespace knit
