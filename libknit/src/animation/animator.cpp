// animator.cpp — the yarns of one rest binding evaluated on every frame of a sequence.
//
// Bind time (constructor): the rest yarns are resampled once, recording each yarn's layout
// (ResampleLayout), the rest arc length of every resampled point, the rest pitch of every yarn
// and the rest length of every yarn segment (or adopts them from a loaded bound scene, without
// evaluating its rest yarns). An Animator of the yarns alone (no plies, no
// statistics: the Python module's Scene.evaluate) does none of it. Per frame (evaluate): vertex normals -> binding
// evaluation -> resampling with the fixed layouts -> rotation-minimizing frames and helices
// with the rest phase -> statistics.
//
// Frame seeds (temporal coherence): at bind time each yarn's first ply frame (tangent T0,
// normal N0: the surface normal projected, as makePlies seeds it) is recorded with the
// orthonormal frame of the triangle its first point is bound to. On a frame, that triangle's
// rotation R from the rest pose carries the rest frame along (R T0, R N0), and R N0 is turned by
// the minimal rotation from R T0 onto the frame's first tangent (parallel transport) before the
// rotation-minimizing frames run. So the plies turn with the surface (a rigid motion moves them
// exactly) and never flip when the yarn's first tangent passes through the surface normal (the
// projection of the surface normal, which each frame used to be seeded with, is undefined
// there). The transport starts from the rest pose, not from the previous frame: frames stay
// history-free, so frame k equals `knit build --rest REST --mesh FRAME_k` (the same Animator),
// and the transport has no drift accumulated over frames. On the rest pose R = I and the plies
// equal makePlies' up to rounding (~1e-15 m).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "knit/animation.hpp"
#include "animation/animator_bind_state.hpp"
#include "knit/error.hpp"
#include "plies/plies_kernel.hpp"
#include "plies/resample_curve.hpp"
#include "scene/scene_budget.hpp"
#include "util/checks.hpp"

namespace knit {
namespace {

using glm::dvec3;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Yarns per parallel task: small enough to balance (a garment has only a few hundred yarns of
// thousands of points each, so 64 made a dozen tasks for the two cores: one finished long before
// the other), large enough to amortize. Each yarn is computed alone, so the result does not
// depend on it.
constexpr size_t kYarnGrain = 2;

}  // namespace

Animator::Animator(const Scene& rest, const AnimatorOptions& options) : rest_(rest), options_(options) {
    plyOfYarn_.assign(rest.binding().yarnCount() + 1, 0);
    // The yarns alone are the binding evaluated (step 2 of evaluate): no ply options, no resampling.
    if (!options_.plies && !options_.stats) return;

    // Step 1: the rest yarns resampled, with each layout and the rest arc lengths / pitches /
    // phases / frame seeds / segment lengths (animator_bind_state.cpp). A loaded bound scene
    // stores them: its generator then reads only the yarns' offsets and closed flags (from the
    // binding), and the budget the exact resampled point count, so the rest yarns, which a
    // loaded scene evaluates lazily (Scene::yarns), are never evaluated for an Animator.
    bind_ = rest.animatorState();
    if (bind_) {
        auto topology = std::make_shared<MappedYarns>();
        topology->curves.offsets = rest.binding().offsets;
        topology->curves.closed = rest.binding().closed;
        restTopology_ = topology;
        generator_.emplace(impl::PlyKernel::replayGenerator(*restTopology_, rest.plyOptions()));
        impl::checkPlyBudget(double(bind_->centreOffsets.back()), generator_->options(), options_.budget);
    } else {
        generator_.emplace(rest.yarns(), rest.plyOptions());
        impl::checkPlyBudget(rest.yarns(), generator_->options(), options_.budget);  // before resampling
        bind_ = std::make_shared<const AnimatorBindState>(computeAnimatorBindState(rest, *generator_));
    }
    const PlyGenerator& generator = *generator_;
    const AnimatorBindState& b = *bind_;
    const std::vector<uint8_t>& closed = generator.yarns().curves.closed;
    const size_t yarnCount = generator.yarnCount();
    plyOfYarn_.assign(yarnCount + 1, 0);

    // Step 2: the constant ply layout (yarn-major, ply-minor, as makePlies).
    const uint32_t n = static_cast<uint32_t>(generator.options().count);
    size_t total = 0;
    for (size_t y = 0; y < yarnCount && options_.plies; ++y) {
        plyOfYarn_[y] = total;
        const size_t m = b.centreOffsets[y + 1] - b.centreOffsets[y];
        if (m < 2) continue;
        for (uint32_t i = 0; i < n; ++i) {
            total += m;
            if (total > UINT32_MAX)
                throw Error(
                    "more than 2^32-1 ply points per frame; raise the ply pitch or lower the samples per ply turn");
            plyTopology_.curves.offsets.push_back(static_cast<uint32_t>(total));
            plyTopology_.curves.closed.push_back(closed[y]);
            plyTopology_.yarnOfCurve.push_back(static_cast<uint32_t>(y));
            plyTopology_.plyOfCurve.push_back(static_cast<uint8_t>(i));
            if (!b.centreColour.empty())
                plyTopology_.colour.insert(plyTopology_.colour.end(), b.centreColour.begin() + b.centreOffsets[y],
                                           b.centreColour.begin() + b.centreOffsets[y + 1]);
        }
    }
    plyOfYarn_[yarnCount] = total;
    plyTopology_.plyRadius = generator.options().plyRadius;
    plyTopology_.centerRadius = generator.options().centerRadius;
    plyTopology_.pitch = generator.options().pitch;
}

void Animator::evaluate(const std::vector<dvec3>& positions, AnimationFrame& out, AnimationStageTimes* times) const {
    const BaseMesh& mesh = rest_.mesh();
    if (positions.size() != mesh.positions.size())
        throw Error("the animation frame has " + std::to_string(positions.size()) + " vertices but the rest mesh " +
                    std::to_string(mesh.positions.size()));
    for (size_t i = 0; i < positions.size(); ++i)
        if (!util::finite(positions[i]))
            throw Error("the animation frame's vertex " + std::to_string(i) + " is not finite");
    AnimationStageTimes t;

    // Step 1: the frame's vertex normals.
    auto t0 = Clock::now();
    out.meshNormals = vertexNormals(positions, mesh.faces);  // same size every frame
    t.normals = since(t0);

    // Step 2: the binding evaluated on the frame.
    t0 = Clock::now();
    out.deform = {};
    if (options_.deform && rest_.deformer())  // the gather and the displacement in one pass (twist for the plies)
        out.deform = rest_.deformer()->evaluate(rest_.binding(), positions, out.meshNormals, out.yarns, options_.plies);
    else evaluateBinding(rest_.binding(), mesh.faces, positions, out.meshNormals, out.yarns);
    t.evaluate = since(t0);

    // Step 3: the centrelines resampled with the rest layouts (for the plies and the statistics).
    t0 = Clock::now();
    if (options_.plies || options_.stats) resample(out);
    t.resample = since(t0);

    // Step 4: frames and helices with the rest twist phase.
    t0 = Clock::now();
    if (options_.plies) sweep(positions, out);
    t.plies = since(t0);

    // Step 5: stretch and the closest approach of different yarns.
    t0 = Clock::now();
    if (options_.stats) {
        const AnimatorBindState& b = *bind_;
        out.stats.maxStretch = maxYarnStretch(out.yarns.curves, b.restSegment.view());
        out.stats.yarnLengthRatio = b.restTotalLength > 0 ? totalYarnLength(out.yarns.curves) / b.restTotalLength : 1.0;
        out.stats.minYarnDistance =
            minYarnDistance(out.centres, b.restArc.view(), b.restLength, rest_.yarnRadius(), options_, out.distance);
        t.stats = since(t0);
    }
    if (times) *times = t;
}

void Animator::resample(AnimationFrame& out) const {
    const AnimatorBindState& b = *bind_;
    const size_t yarnCount = b.restPitch.size();
    Polylines& c = out.centres;
    if (c.offsets != b.centreOffsets) {  // first frame with this buffer
        c.offsets = b.centreOffsets;
        c.closed = generator_->yarns().curves.closed;
        c.points.resize(b.centreOffsets.back());
    }
    tbb::enumerable_thread_specific<ResampleScratch> scratches;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarnCount, kYarnGrain), [&](const tbb::blocked_range<size_t>& r) {
        ResampleScratch& scratch = scratches.local();
        for (size_t y = r.begin(); y < r.end(); ++y)
            resampleCurveWithLayout(out.yarns.curves, y, b.kept.data() + b.keptOffsets[y],
                                    b.keptOffsets[y + 1] - b.keptOffsets[y], b.pieces.data() + b.pieceOffsets[y],
                                    c.points.data() + b.centreOffsets[y], scratch);
    });
}

void Animator::sweep(const std::vector<dvec3>& positions, AnimationFrame& out) const {
    Plies& p = out.plies;
    if (p.curves.offsets != plyTopology_.curves.offsets) {  // first frame with this buffer
        p = plyTopology_;
        p.curves.points.resize(plyTopology_.curves.offsets.back());
        if (options_.radial) p.radial.resize(plyTopology_.curves.offsets.back());
    }
    const AnimatorBindState& b = *bind_;
    const size_t yarnCount = b.restPitch.size();
    const std::vector<glm::uvec3>& faces = rest_.mesh().faces;
    tbb::enumerable_thread_specific<PlyScratch> scratches;
    // The strain table's twist (when it has any): the rest phase turned by the frame's twist.
    const std::vector<float>& twist = out.yarns.twist;
    tbb::enumerable_thread_specific<std::pair<std::vector<double>, std::vector<glm::dvec2>>> twisted;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, yarnCount, kYarnGrain), [&](const tbb::blocked_range<size_t>& r) {
        PlyScratch& scratch = scratches.local();
        for (size_t y = r.begin(); y < r.end(); ++y) {
            const size_t m = b.centreOffsets[y + 1] - b.centreOffsets[y];
            if (m < 2) continue;
            const glm::dvec2* phase = b.restPhase.data() + b.centreOffsets[y];
            if (!twist.empty()) {
                auto& [angle, turned] = twisted.local();
                angle.resize(m);
                turned.resize(m);
                resampleTwist(twist.data() + out.yarns.curves.begin(y), out.yarns.curves.isClosed(y),
                              b.kept.data() + b.keptOffsets[y], b.keptOffsets[y + 1] - b.keptOffsets[y],
                              b.pieces.data() + b.pieceOffsets[y], angle.data());
                for (size_t j = 0; j < m; ++j) {
                    const double c = std::cos(angle[j]), s = std::sin(angle[j]);
                    turned[j] = {phase[j].x * c - phase[j].y * s, phase[j].y * c + phase[j].x * s};
                }
                phase = turned.data();
            }
            // The rest frame carried by the bound triangle's rotation (see the file comment);
            // a degenerate triangle falls back to the surface normal.
            const size_t first = out.yarns.curves.begin(y);
            const AnimatorBindState::Seed& s = b.seeds[y];
            glm::dmat3 now;
            dvec3 seedNormal = out.yarns.normals[first], seedTangent(0.0);
            const bool carried = s.valid != 0 && triangleFrame(positions, faces[rest_.binding().face[first]], now);
            if (carried) {
                const glm::dmat3 r = now * glm::transpose(s.surface);
                seedNormal = r * s.normal;
                seedTangent = r * s.tangent;
            }
            impl::PlyKernel::sweepWithCosSin(
                *generator_, y, out.centres.points.data() + b.centreOffsets[y], m, phase, &seedNormal,
                carried ? &seedTangent : nullptr, p.curves.points.data() + plyOfYarn_[y], scratch,
                options_.radial ? p.radial.data() + plyOfYarn_[y] : nullptr, options_.framePrecision);
        }
    });
}

}  // namespace knit
