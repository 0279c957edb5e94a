// python/src/frame_plies.cpp — plies of a new pose in the rest layout (frame_plies.hpp).
#include "frame_plies.hpp"

#include <algorithm>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "knit/error.hpp"
#include "plies/plies_kernel.hpp"  // internal: the per-yarn resample and sweep steps

namespace knitpy {

namespace {

// Re-samples the polyline `in` (closed: with the segment back to the first point) to `m`
// points uniformly by arc length; the first point is kept.
void resampleToCount(const std::vector<glm::dvec3>& in, bool closed, size_t m, std::vector<glm::dvec3>& out) {
    const size_t n = in.size();
    const size_t segments = closed ? n : n - 1;
    std::vector<double> arc(segments + 1, 0.0);
    for (size_t i = 0; i < segments; ++i) arc[i + 1] = arc[i] + glm::length(in[(i + 1) % n] - in[i]);
    const double step = arc[segments] / double(closed ? m : m - 1);
    out.resize(m);
    size_t seg = 0;
    for (size_t k = 0; k < m; ++k) {
        const double s = std::min(step * double(k), arc[segments]);
        while (seg + 1 < segments && arc[seg + 1] < s) ++seg;
        const double len = arc[seg + 1] - arc[seg];
        const double t = len > 0 ? (s - arc[seg]) / len : 0.0;
        out[k] = in[seg] + t * (in[(seg + 1) % n] - in[seg]);
    }
}

// Per yarn: its first ply curve in `rest` and the points per ply curve (0: no plies).
struct RestLayout {
    std::vector<size_t> firstCurve, points;
};

RestLayout restLayout(const knit::Plies& rest, size_t yarnCount) {
    RestLayout l{std::vector<size_t>(yarnCount, 0), std::vector<size_t>(yarnCount, 0)};
    for (size_t c = 0; c < rest.curves.curveCount(); ++c) {
        const uint32_t y = rest.yarnOfCurve[c];
        if (y >= yarnCount) throw knit::Error("plies: the rest plies do not belong to these yarns");
        if (rest.plyOfCurve[c] == 0) {
            l.firstCurve[y] = c;
            l.points[y] = rest.curves.size(c);
        }
    }
    return l;
}

}  // namespace

knit::Plies pliesWithRestLayout(const knit::MappedYarns& yarns, const knit::PlyOptions& options,
                                const knit::Plies& rest) {
    // Step 1: the generator (validates options and yarns) and the rest layout.
    const knit::PlyGenerator generator(yarns, options);
    const RestLayout layout = restLayout(rest, generator.yarnCount());
    knit::Plies out = rest;  // offsets, flags, radii; points and radial are overwritten
    // Step 2: per yarn, its centreline at the rest count, swept into the rest slots.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, generator.yarnCount()), [&](const tbb::blocked_range<size_t>& r) {
        knit::PlyScratch scratch;
        std::vector<glm::dvec3> centre, fixed;
        for (size_t y = r.begin(); y < r.end(); ++y) {
            const size_t m = layout.points[y];
            if (m < 2) continue;
            centre.clear();
            knit::impl::PlyKernel::centreline(generator, y, centre, scratch);
            const std::vector<glm::dvec3>* line = &centre;
            if (centre.size() != m) {
                resampleToCount(centre, yarns.curves.isClosed(y), m, fixed);
                line = &fixed;
            }
            const size_t base = rest.curves.begin(layout.firstCurve[y]);
            knit::impl::PlyKernel::sweep(generator, y, line->data(), m, out.curves.points.data() + base,
                                           out.radial.empty() ? nullptr : out.radial.data() + base, scratch);
        }
    });
    return out;
}

}  // namespace knitpy
