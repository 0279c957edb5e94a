// animator_bind_state.cpp — an Animator's bind-time work on the rest yarns (the resampling
// layout, rest arc lengths, pitches and twist phases, frame seeds, colours, stretch references),
// and the checks of a stored one (a bound scene file's) against the binding it is replayed on.
#include "animation/animator_bind_state.hpp"

#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

#include <glm/geometric.hpp>

#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "plies/frames_curve.hpp"
#include "plies/plies_kernel.hpp"
#include "plies/resample_curve.hpp"

namespace knit {
namespace {

using glm::dvec3;

// Yarn y's first ply frame on the rest pose (its resampled centreline `centre`).
AnimatorBindState::Seed frameSeed(const Scene& rest, size_t y, const std::vector<dvec3>& centre) {
    const size_t m = centre.size(), first = rest.yarns().curves.begin(y);
    std::vector<dvec3> tangent(m), normal(m);
    const dvec3* surfaceNormal = rest.yarns().normals.empty() ? nullptr : rest.yarns().normals.data() + first;
    curveFrames(centre.data(), m, rest.yarns().curves.isClosed(y), surfaceNormal, tangent.data(), normal.data());
    AnimatorBindState::Seed s;
    s.tangent = tangent[0];
    s.normal = normal[0];
    s.valid = triangleFrame(rest.mesh().positions, rest.mesh().faces[rest.binding().face[first]], s.surface) ? 1 : 0;
    return s;
}

std::string yarnName(size_t y) { return "yarn " + std::to_string(y) + ": "; }

// The CSR offsets `o` over `yarns` yarns ending at `size` elements.
void checkOffsets(const std::vector<uint32_t>& o, size_t yarns, size_t size, const char* what) {
    if (o.size() != yarns + 1 || o.front() != 0 || o.back() != size)
        throw Error(std::string("the ") + what + " offsets do not cover " + std::to_string(yarns) + " yarns");
    for (size_t y = 0; y < yarns; ++y)
        if (o[y + 1] < o[y]) throw Error(yarnName(y) + "its " + what + " offsets decrease");
}

// Every double of `v` (a vector or a util::SharedArray of doubles or of vectors of them).
template <class Array>
bool allFinite(const Array& v) {
    using T = std::remove_const_t<std::remove_reference_t<decltype(*v.data())>>;
    const auto* d = reinterpret_cast<const double*>(v.data());
    bool finite = true;
    for (size_t i = 0; i < v.size() * sizeof(T) / sizeof(double); ++i) finite &= std::isfinite(d[i]);
    return finite;
}

}  // namespace

bool triangleFrame(const std::vector<dvec3>& x, const glm::uvec3& f, glm::dmat3& out) {
    const dvec3 e = x[f.y] - x[f.x], n = glm::cross(e, x[f.z] - x[f.x]);
    const double le = glm::length(e), ln = glm::length(n);
    if (!(le > 0.0) || !(ln > 0.0) || !std::isfinite(ln)) return false;
    const dvec3 e1 = e / le, e3 = n / ln;
    out = glm::dmat3(e1, glm::cross(e3, e1), e3);
    return true;
}

AnimatorBindState computeAnimatorBindState(const Scene& rest, const PlyGenerator& generator) {
    const Polylines& yarns = rest.yarns().curves;
    const size_t yarnCount = yarns.curveCount();
    const double spacing = generator.options().pitch / generator.options().samplesPerTurn;
    AnimatorBindState s;
    s.restPitch.assign(yarnCount, 0.0);
    s.restLength.assign(yarnCount, 0.0);
    s.seeds.assign(yarnCount, {});
    // Resample the rest yarns, recording each layout and the rest arc lengths / pitches.
    ResampleLayout layout;
    ResampleScratch resampleScratch;
    std::vector<double> arc, restArc;
    std::vector<glm::dvec2> restPhase;
    std::vector<dvec3> centre;
    for (size_t y = 0; y < yarnCount; ++y) {
        centre.clear();
        const size_t m = resampleCurve(rest.yarns(), y, spacing, centre, nullptr, resampleScratch, &layout);
        if (!rest.yarns().colour.empty())  // the chart's colours, as makePlies gives them
            resampleColours(rest.yarns().colour.data() + yarns.begin(y), yarns.isClosed(y), layout, s.centreColour);
        s.kept.insert(s.kept.end(), layout.kept.begin(), layout.kept.end());
        s.keptOffsets.push_back(static_cast<uint32_t>(s.kept.size()));
        s.pieces.insert(s.pieces.end(), layout.pieces.begin(), layout.pieces.end());
        s.pieceOffsets.push_back(static_cast<uint32_t>(s.pieces.size()));
        if (s.centreOffsets.back() + m > UINT32_MAX)
            throw Error("more than 2^32-1 resampled yarn points; raise the ply pitch");
        s.centreOffsets.push_back(static_cast<uint32_t>(s.centreOffsets.back() + m));
        if (m < 2) {
            restArc.insert(restArc.end(), m, 0.0);
            restPhase.insert(restPhase.end(), m, glm::dvec2(1.0, 0.0));
            continue;
        }
        s.restPitch[y] = impl::PlyKernel::arcAndPitch(generator, y, centre.data(), m, arc);
        s.seeds[y] = frameSeed(rest, y, centre);
        restArc.insert(restArc.end(), arc.begin(), arc.end());
        const double rate = impl::PlyKernel::twistRate(generator, s.restPitch[y]);
        for (const double a : arc) restPhase.emplace_back(std::cos(rate * a), std::sin(rate * a));
        s.restLength[y] = arc[m - 1] + (yarns.isClosed(y) ? glm::length(centre[0] - centre[m - 1]) : 0.0);
    }
    s.restArc = std::move(restArc);
    s.restPhase = std::move(restPhase);
    restSegments(yarns, s.restSegment, s.restTotalLength);
    return s;
}

void restSegments(const Polylines& yarns, util::SharedArray<double>& out, double& total) {
    std::vector<double> segment(yarns.pointCount(), 0.0);
    for (size_t y = 0; y < yarns.curveCount(); ++y) {
        const uint32_t first = yarns.begin(y), e = yarns.end(y);
        for (uint32_t i = first; i < e; ++i) {
            const uint32_t j = i + 1 < e ? i + 1 : (yarns.isClosed(y) && e - first > 2 ? first : i);
            segment[i] = glm::length(yarns.points[j] - yarns.points[i]);
        }
    }
    out = std::move(segment);
    total = totalYarnLength(yarns);
}

void checkAnimatorBindState(const AnimatorBindState& s, const Binding& binding) {
    Polylines yarns;  // the rest yarns' topology (no points: none are read)
    yarns.offsets = binding.offsets;
    yarns.closed = binding.closed;
    const size_t yarnCount = yarns.curveCount();
    // Step 1: sizes.
    checkOffsets(s.keptOffsets, yarnCount, s.kept.size(), "kept point");
    checkOffsets(s.pieceOffsets, yarnCount, s.pieces.size(), "piece");
    checkOffsets(s.centreOffsets, yarnCount, s.restArc.size(), "resampled point");
    const size_t centres = s.restArc.size();
    if (s.restPhase.size() != centres)
        throw Error("the twist phases (" + std::to_string(s.restPhase.size()) + ") are not one per resampled point (" +
                    std::to_string(centres) + ")");
    if (s.restPitch.size() != yarnCount || s.restLength.size() != yarnCount || s.seeds.size() != yarnCount)
        throw Error("the pitches, lengths and frame seeds are not one per yarn (" + std::to_string(yarnCount) + ")");
    if (s.restSegment.size() != binding.vertexCount())
        throw Error("the rest segment lengths (" + std::to_string(s.restSegment.size()) +
                    ") are not one per yarn vertex (" + std::to_string(binding.vertexCount()) + ")");
    if (s.centreColour.size() != (binding.colour.empty() ? 0 : centres))
        throw Error("the resampled points' colours (" + std::to_string(s.centreColour.size()) +
                    ") do not match the yarns' colours");
    // Step 2: per yarn, what resampling with the layout reads and writes.
    for (size_t y = 0; y < yarnCount; ++y) {
        const uint32_t* kept = s.kept.data() + s.keptOffsets[y];
        const size_t keptCount = s.keptOffsets[y + 1] - s.keptOffsets[y];
        for (size_t i = 0; i < keptCount; ++i)
            if (kept[i] >= yarns.size(y) || (i > 0 && kept[i] <= kept[i - 1]))
                throw Error(yarnName(y) + "kept point " + std::to_string(i) + " (" + std::to_string(kept[i]) +
                            ") is not increasing within its " + std::to_string(yarns.size(y)) + " points");
        const bool closed = yarns.isClosed(y);
        const size_t segments = keptCount < 2 ? 0 : (closed ? keptCount : keptCount - 1);
        if (s.pieceOffsets[y + 1] - s.pieceOffsets[y] != segments)
            throw Error(yarnName(y) + std::to_string(s.pieceOffsets[y + 1] - s.pieceOffsets[y]) + " pieces for " +
                        std::to_string(segments) + " segments");
        uint64_t points = keptCount < 2 ? keptCount : (closed ? 0 : 1);
        for (size_t i = s.pieceOffsets[y]; i < s.pieceOffsets[y + 1]; ++i) {
            if (s.pieces[i] == 0) throw Error(yarnName(y) + "a segment has 0 pieces");
            points += s.pieces[i];
        }
        if (points != s.centreOffsets[y + 1] - s.centreOffsets[y])
            throw Error(yarnName(y) + "its layout makes " + std::to_string(points) + " resampled points, not " +
                        std::to_string(s.centreOffsets[y + 1] - s.centreOffsets[y]));
        if (s.seeds[y].valid > 1) throw Error(yarnName(y) + "its frame seed has a bad flag");
    }
    // Step 3: finite values.
    if (!allFinite(s.restArc) || !allFinite(s.restPhase) || !allFinite(s.restPitch) || !allFinite(s.restLength))
        throw Error("a rest arc length, twist phase, pitch or length is not finite");
    bool segments = std::isfinite(s.restTotalLength) && s.restTotalLength >= 0.0;
    for (const double l : s.restSegment) segments &= std::isfinite(l) && l >= 0.0;
    if (!segments) throw Error("a rest segment length or the rest yarns' total length is negative or not finite");
    for (size_t y = 0; y < yarnCount; ++y) {
        const AnimatorBindState::Seed& seed = s.seeds[y];
        bool finite = true;
        for (int k = 0; k < 3; ++k)
            finite &= std::isfinite(seed.tangent[k]) && std::isfinite(seed.normal[k]) &&
                      std::isfinite(seed.surface[k][0]) && std::isfinite(seed.surface[k][1]) &&
                      std::isfinite(seed.surface[k][2]);
        if (!finite) throw Error(yarnName(y) + "its frame seed is not finite");
    }
}

}  // namespace knit
