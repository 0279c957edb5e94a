// detail_plies.cpp — piecePlies (knit/detail.hpp): the plies of a view's pieces, cut from the plies
// of their whole source yarns.
//
// Steps per source yarn (yarns in parallel): resample the whole yarn and sweep its plies exactly
// as makePlies does, through the same kernel (same resampling, frames seeded at the yarn's first
// point, twist phase from its arc length plus a strain table's twist change); give every
// resampled point its position in vertex units of the yarn (from the resampling layout: kept
// input points and the pieces of each segment between them); then for each span copy the
// resampled points from the last one at or before its begin to the first one at or after its
// end (cyclically, unwrapped, on a closed yarn), for every ply.
#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/detail.hpp"
#include "knit/error.hpp"
#include "plies/plies_kernel.hpp"
#include "plies/resample_curve.hpp"

namespace knit {
namespace {

using glm::dvec3;

// One source yarn's plies as makePlies makes them: n curves of m points (ply-major).
struct YarnPlies {
    size_t m = 0;
    std::vector<dvec3> points, radial;
    std::vector<glm::vec3> colour;  // per resampled point (empty without colours)
    std::vector<double> at;         // per resampled point: its position in vertex units
};

void sweepYarn(const PlyGenerator& g, size_t y, YarnPlies& out, PlyScratch& scratch) {
    const MappedYarns& yarns = g.yarns();
    std::vector<dvec3> centre;
    std::vector<double> twist;  // a strain table's twist change, as makePlies adds it to the phase
    ResampleLayout layout;
    out.colour.clear();
    out.m = impl::PlyKernel::centreline(g, y, centre, scratch, &out.colour, &twist, &layout);
    if (out.m < 2) return;
    const size_t n = size_t(g.options().count), m = out.m;
    out.points.resize(n * m);
    out.radial.resize(n * m);
    impl::PlyKernel::sweep(g, y, centre.data(), m, out.points.data(), out.radial.data(), scratch,
                           twist.empty() ? nullptr : twist.data());
    // Positions: segment k runs from kept[k] to kept[k + 1] (closed: the last one back to kept[0]
    // + the vertex count) in pieces[k] equal steps.
    const double count = double(yarns.curves.size(y));
    const size_t kept = layout.kept.size();
    out.at.clear();
    for (size_t k = 0; k < layout.pieces.size(); ++k) {
        const double a = layout.kept[k], b = k + 1 < kept ? double(layout.kept[k + 1]) : layout.kept[0] + count;
        for (uint32_t i = 0; i < layout.pieces[k]; ++i) out.at.push_back(a + (b - a) * i / layout.pieces[k]);
    }
    if (!yarns.curves.isClosed(y)) out.at.push_back(layout.kept.back());
    if (out.at.size() != m) throw Error("piecePlies: the resampling layout does not match the resampled yarn");
}

// The resampled indices of a span: from the last point at or before begin to the first at or after
// end (a loop: every point once).
std::vector<size_t> spanIndices(const YarnPlies& p, const YarnSpan& s, bool closed, double count) {
    std::vector<size_t> out;
    const size_t m = p.m;
    if (s.loop) {
        for (size_t j = 0; j < m; ++j) out.push_back(j);
        return out;
    }
    double begin = s.begin, end = s.end;
    if (closed)
        while (begin >= count) begin -= count, end -= count;
    size_t j0 = 0;
    while (j0 + 1 < m && p.at[j0 + 1] <= begin) ++j0;
    for (size_t step = 0; step <= m; ++step) {  // at most once round a closed yarn
        const size_t j = (j0 + step) % m;
        if (!closed && j0 + step >= m) break;
        const double at = p.at[j] + (j0 + step >= m ? count : 0.0);
        out.push_back(j);
        if (at >= end) break;
    }
    return out;
}

void appendSpan(const YarnPlies& p, const std::vector<size_t>& idx, uint32_t yarn, bool loop, uint32_t count,
                Plies& out) {
    if (idx.size() < 2) return;
    for (uint32_t i = 0; i < count; ++i) {
        for (const size_t j : idx) {
            out.curves.points.push_back(p.points[i * p.m + j]);
            out.radial.push_back(p.radial[i * p.m + j]);
            if (!p.colour.empty()) out.colour.push_back(p.colour[j]);
        }
        out.curves.offsets.push_back(static_cast<uint32_t>(out.curves.points.size()));
        out.curves.closed.push_back(loop ? 1 : 0);
        out.yarnOfCurve.push_back(yarn);
        out.plyOfCurve.push_back(static_cast<uint8_t>(i));
    }
}

}  // namespace

Plies piecePlies(const MappedYarns& yarns, const std::vector<YarnSpan>& spans, const PlyOptions& options) {
    const PlyGenerator g(yarns, options);
    // Step 1: the spans grouped by source yarn (they come in ascending yarn order).
    std::vector<size_t> groupStart;
    for (size_t k = 0; k < spans.size(); ++k) {
        if (spans[k].yarn >= yarns.curves.curveCount())
            throw Error("piecePlies: span " + std::to_string(k) + " names yarn " + std::to_string(spans[k].yarn) +
                        " of " + std::to_string(yarns.curves.curveCount()));
        if (k > 0 && spans[k].yarn < spans[k - 1].yarn)
            throw Error("piecePlies: the spans are not in ascending yarn order");
        if (k == 0 || spans[k].yarn != spans[k - 1].yarn) groupStart.push_back(k);
    }
    groupStart.push_back(spans.size());
    // Step 2: per source yarn, its whole plies and the spans cut from them (in parallel).
    const size_t groups = groupStart.size() - 1;
    const uint32_t count = static_cast<uint32_t>(g.options().count);
    std::vector<Plies> parts(groups);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, groups, 1), [&](const tbb::blocked_range<size_t>& r) {
        PlyScratch scratch;
        YarnPlies p;
        for (size_t k = r.begin(); k < r.end(); ++k) {
            const uint32_t y = spans[groupStart[k]].yarn;
            parts[k].curves.offsets.assign(1, 0);
            sweepYarn(g, y, p, scratch);
            if (p.m < 2) continue;
            const bool closed = yarns.curves.isClosed(y);
            for (size_t s = groupStart[k]; s < groupStart[k + 1]; ++s)
                appendSpan(p, spanIndices(p, spans[s], closed, double(yarns.curves.size(y))), y, spans[s].loop, count,
                           parts[k]);
        }
    });
    // Step 3: concatenated in span order.
    Plies out;
    out.plyRadius = g.options().plyRadius;
    out.centerRadius = g.options().centerRadius;
    out.pitch = g.options().pitch;
    for (Plies& part : parts) {
        if (out.curves.points.size() + part.curves.points.size() > UINT32_MAX)
            throw Error("more than 2^32-1 ply points; raise the ply pitch or lower the samples per turn");
        out.curves.append(part.curves);
        out.yarnOfCurve.insert(out.yarnOfCurve.end(), part.yarnOfCurve.begin(), part.yarnOfCurve.end());
        out.plyOfCurve.insert(out.plyOfCurve.end(), part.plyOfCurve.begin(), part.plyOfCurve.end());
        out.radial.insert(out.radial.end(), part.radial.begin(), part.radial.end());
        out.colour.insert(out.colour.end(), part.colour.begin(), part.colour.end());
        std::vector<dvec3>().swap(part.curves.points);  // release as we go
    }
    return out;
}

}  // namespace knit
