// animator_bind_state.hpp (internal) — what an Animator decides on the rest pose (bind time),
// kept apart from the Animator so that a bound scene file (knit/bound_scene.hpp) stores it and the
// Animator of a loaded scene adopts it instead of resampling the rest yarns again: the resampling
// layout of every yarn, the rest arc length and twist phase of every resampled point, each yarn's
// rest pitch, rest length and first ply frame, the resampled points' colours, and the statistics'
// references (the rest length of every yarn segment and of all yarns). All of it is a pure
// function of the rest scene (its yarns, mesh, binding) and the resolved ply options. With the
// references stored too, an Animator of a loaded scene needs nothing of the rest yarns, so a
// loaded scene evaluates them only when something else asks (Scene::yarns).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/plies.hpp"
#include "knit/scene.hpp"
#include "util/shared_array.hpp"

namespace knit {

struct AnimatorBindState {
    // A yarn's first ply frame on the rest pose, with the frame of the triangle it is bound to.
    // Explicit padding: the struct is stored byte for byte (no indeterminate bytes in a file).
    struct Seed {
        glm::dvec3 tangent{0.0}, normal{0.0};
        glm::dmat3 surface{1.0};
        uint8_t valid = 0;  // 0: degenerate triangle (seed with the surface normal); else 1
        std::array<uint8_t, 7> unused{};
    };
    // Resampling layout per yarn (CSR over yarns): kept points and pieces per segment (ResampleLayout).
    std::vector<uint32_t> keptOffsets{0}, kept, pieceOffsets{0}, pieces;
    std::vector<uint32_t> centreOffsets{0};  // resampled points per yarn (CSR)
    // The per-point arrays a loaded scene uses in place in its file's memory map (format
    // version 5: util::SharedArray views that keep the map open; owned when computed here).
    // Only values live there, never an index or a size: a value checked on loading cannot turn
    // into a read out of bounds.
    util::SharedArray<double> restArc;        // rest arc length per resampled point
    util::SharedArray<glm::dvec2> restPhase;  // (cos, sin) of its twist phase
    std::vector<double> restPitch;            // per yarn
    std::vector<double> restLength;           // per yarn: resampled rest length (closed: with the closing segment)
    std::vector<Seed> seeds;                  // per yarn
    std::vector<glm::vec3> centreColour;      // per resampled point, when the rest yarns have colours
    // The stretch references (format version 4): per rest yarn vertex the length of the segment
    // starting there (the closing one at a closed yarn's last vertex; 0: none), and
    // totalYarnLength of the rest yarns. A view in a loaded scene, as restArc.
    util::SharedArray<double> restSegment;
    double restTotalLength = 0;
};
static_assert(sizeof(AnimatorBindState::Seed) == 128, "Seed is stored without padding");

// The orthonormal frame (first edge, in-plane perpendicular, normal) of triangle f; false when
// the triangle is degenerate.
bool triangleFrame(const std::vector<glm::dvec3>& x, const glm::uvec3& f, glm::dmat3& out);

// The bind-time work of an Animator on `rest` with the generator of its rest yarns (the
// Animator's constructor, step 1). Throws knit::Error for more than 2^32-1 resampled points.
AnimatorBindState computeAnimatorBindState(const Scene& rest, const PlyGenerator& generator);

// The stretch references of `yarns` (AnimatorBindState::restSegment, restTotalLength).
void restSegments(const Polylines& yarns, util::SharedArray<double>& segment, double& total);

// Checks what evaluation relies on when it replays a stored state on the rest yarns `binding`
// makes (their offsets, closed flags and colours: the yarns themselves are not needed): sizes per
// yarn, kept indices within their yarn, piece counts adding up to the resampled points, flags,
// finite values; throws knit::Error naming the yarn and what is wrong.
void checkAnimatorBindState(const AnimatorBindState& state, const Binding& binding);

}  // namespace knit
