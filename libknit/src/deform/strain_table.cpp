// Strain tables made by the project's own yarn-level solver: the pattern's cell relaxed on the
// lattice deformed by each sample's F (chart/relax_lattice.hpp), displacements recorded against
// the cell relaxed on the undeformed lattice. Samples are walked outwards from the one nearest zero
// strain, each warm-started from its neighbour one step closer (samples at the same step count run
// in parallel; each one's start is fixed, so the table does not depend on the thread count).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <sstream>
#include <thread>
#include <ctime>

#include <tbb/parallel_for.h>

#include "chart/relax_lattice.hpp"
#include "knit/error.hpp"
#include "knit/strain.hpp"

namespace knit {
namespace {

using Index3 = std::array<int, 3>;

// estimateStrainTableSeconds' work model, in the estimate's own timed Newton iterations: per
// lattice stage of the table (over two threads' worth of samples) and for the serial rest cell,
// for either Newton path (measured, docs/deformation.md "400-vertex patterns").
constexpr double kDensePerStage = 80, kSparsePerStage = 70, kRest = 1400;

std::vector<double> linspace(const std::array<double, 2>& r, int n) {
    std::vector<double> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) v[size_t(i)] = n == 1 ? r[0] : r[0] + (r[1] - r[0]) * double(i) / double(n - 1);
    return v;
}

void validateOptions(const StrainTableOptions& o) {
    for (int a = 0; a < 3; ++a)
        if (o.samples[size_t(a)] < 1 || o.samples[size_t(a)] > 64)
            throw Error("the strain samples must be 1 to 64 per axis, got " + std::to_string(o.samples[size_t(a)]));
    // Two or more samples need a range that increases (a table's axes must); one sample may sit at one value.
    const auto range = [](const std::array<double, 2>& r, int samples, double lo, double hi, const char* name) {
        if (!(samples == 1 ? r[0] <= r[1] : r[0] < r[1]) || !(r[0] > lo) || !(r[1] < hi) || !std::isfinite(r[0]) ||
            !std::isfinite(r[1])) {
            std::ostringstream m;
            m << "the " << name << " range " << r[0] << " " << r[1] << " must be increasing and within (" << lo << ", "
              << hi << ")";
            throw Error(m.str());
        }
    };
    range(o.sxRange, o.samples[0], -1, 10, "sx");
    range(o.saRange, o.samples[1], -0.95, 0.95, "sa");
    range(o.syRange, o.samples[2], -1, 10, "sy");
    if (!(o.stretch > 0) || !(o.bend >= 0) || !(o.contact >= 0) || !(o.barrier >= 0) || o.maxIterations < 1)
        throw Error("the strain table's stretch weight must be positive, its bend and contact weights >= 0 and its "
                    "iteration count >= 1");
    if (o.startsPerSample < 1 || o.startsPerSample > 3)
        throw Error("the strain table's starts per sample must be 1 to 3, got " + std::to_string(o.startsPerSample));
    if (!(o.barrierDistance > 0) || !(o.contactDistance >= o.barrierDistance) || !(o.contactDistance < 10))
        throw Error("the strain table's barrier distance must be positive and at most its contact distance, which "
                    "must be below 10 radii");
}

impl::LatticeRelaxOptions solverOptions(const StrainTableOptions& o) {
    impl::LatticeRelaxOptions lo;
    lo.stretch = o.stretch;
    lo.bend = o.bend;
    lo.contact = o.contact;
    lo.barrier = o.barrier;
    lo.contactDistance = o.contactDistance;
    lo.barrierDistance = o.barrierDistance;
    lo.maxIterations = o.maxIterations;
    return lo;
}

// The sample nearest zero strain along each axis.
Index3 nearestZero(const std::array<std::vector<double>, 3>& axes) {
    Index3 z{};
    for (size_t a = 0; a < 3; ++a) {
        size_t best = 0;
        for (size_t i = 0; i < axes[a].size(); ++i)
            if (std::abs(axes[a][i]) < std::abs(axes[a][best])) best = i;
        z[a] = int(best);
    }
    return z;
}

// The samples grouped by their step count from `zero`; each one's parent is its neighbour one step
// closer (along the first axis where they differ).
struct Walk {
    std::vector<std::vector<Index3>> layers;
};
Walk walkFrom(const Index3& zero, const Index3& n) {
    Walk w;
    for (int y = 0; y < n[2]; ++y)
        for (int a = 0; a < n[1]; ++a)
            for (int x = 0; x < n[0]; ++x) {
                const size_t d = size_t(std::abs(x - zero[0]) + std::abs(a - zero[1]) + std::abs(y - zero[2]));
                if (w.layers.size() <= d) w.layers.resize(d + 1);
                w.layers[d].push_back({x, a, y});
            }
    return w;
}
Index3 parentOf(const Index3& i, const Index3& zero) {
    Index3 p = i;
    for (size_t a = 0; a < 3; ++a)
        if (p[a] != zero[a]) {
            p[a] += p[a] < zero[a] ? 1 : -1;
            break;
        }
    return p;
}

Strain strainAt(const std::array<std::vector<double>, 3>& axes, const Index3& i) {
    return {axes[0][size_t(i[0])], axes[1][size_t(i[1])], axes[2][size_t(i[2])]};
}

// The neighbours of i one step closer to `zero`, the parent (parentOf) first.
std::vector<Index3> lowerNeighbours(const Index3& i, const Index3& zero) {
    std::vector<Index3> out{parentOf(i, zero)};
    for (size_t a = 0; a < 3; ++a)
        if (i[a] != zero[a]) {
            Index3 q = i;
            q[a] += q[a] < zero[a] ? 1 : -1;
            if (q != out.front()) out.push_back(q);
        }
    return out;
}

// Sample i relaxed from up to `starts` of its already relaxed lower neighbours (the parent first);
// the lowest energy kept (a later start only when lower by more than round-off), so that
// neighbouring samples settle on the same branch where a stiff yarn has several (buckled or not).
template <class Flat>
impl::LatticeRelaxResult relaxFromNeighbours(const impl::LatticeCell& cell,
                                             const std::array<std::vector<double>, 3>& axes,
                                             const std::vector<impl::LatticeRelaxResult>& result, const Flat& flat,
                                             const Index3& i, const Index3& zero, int starts) {
    const glm::dmat2 F = latticeMap(strainAt(axes, i));
    impl::LatticeRelaxResult best;
    bool have = false;
    int iterations = 0, stages = 0;  // of every start: the work done (StrainTableStats)
    const std::vector<Index3> from = lowerNeighbours(i, zero);
    for (size_t k = 0; k < from.size() && int(k) < starts; ++k) {
        impl::LatticeRelaxResult r = cell.relax(F, result[flat(from[k])].points, latticeMap(strainAt(axes, from[k])));
        iterations += r.iterations;
        stages += r.stages;
        if (!have || r.energy < best.energy - 1e-9 * (1 + std::abs(best.energy))) best = std::move(r);
        have = true;
    }
    best.iterations = iterations;
    best.stages = stages;
    return best;
}

}  // namespace

StrainTable makeStrainTable(const Pattern& pattern, const StrainTableOptions& options, StrainTableStats* stats) {
    validateOptions(options);
    const auto t0 = std::chrono::steady_clock::now();
    const impl::LatticeCell cell(pattern, solverOptions(options));
    const size_t nv = cell.vertexCount();
    StrainTable table;
    table.source = pattern.name;
    table.pattern = pattern.name;
    table.px = pattern.px;
    table.py = pattern.py;
    table.radius = pattern.radius;
    table.vertexCount = nv;
    table.axes = {linspace(options.sxRange, options.samples[0]), linspace(options.saRange, options.samples[1]),
                  linspace(options.syRange, options.samples[2])};
    const Index3 n = options.samples;
    const size_t total = table.samples();
    const auto flat = [&](const Index3& i) {
        return size_t(i[0]) + size_t(n[0]) * (size_t(i[1]) + size_t(n[1]) * size_t(i[2]));
    };

    // 1. The rest cell: relaxed on the undeformed lattice; every displacement is against it.
    impl::LatticeRelaxResult rest;
    rest.points = impl::restCell(pattern, solverOptions(options));
    rest = cell.relax(glm::dmat2(1.0), rest.points);  // its closest distance (a few steps at most)
    // 2. The samples, outwards from zero strain (a sample at zero strain is the rest cell itself).
    const Index3 zero = nearestZero(table.axes);
    std::vector<impl::LatticeRelaxResult> result(total);
    std::mutex progressMutex;
    size_t done = 0;
    for (const std::vector<Index3>& layer : walkFrom(zero, n).layers)
        tbb::parallel_for(size_t(0), layer.size(), [&](size_t k) {
            const Index3& i = layer[k];
            const Strain s = strainAt(table.axes, i);
            if (s.sx == 0 && s.sa == 0 && s.sy == 0) {
                result[flat(i)] = rest;
                result[flat(i)].stages = 0;  // no relaxation of its own
            } else if (i == zero) result[flat(i)] = cell.relax(latticeMap(s), rest.points);
            else
                result[flat(i)] = relaxFromNeighbours(cell, table.axes, result, flat, i, zero, options.startsPerSample);
            if (options.progress) {
                const std::lock_guard<std::mutex> lock(progressMutex);
                options.progress(++done, total);
            }
        });
    // 3. Displacements in the table's layout, the cell's translation (free in the relaxation) removed.
    table.data.assign(4 * nv * total, 0.0F);
    StrainTableStats st;
    st.samples = total + 1;
    st.restMinDistance = rest.minDistance;
    st.minDistance = rest.minDistance;
    for (size_t s = 0; s < total; ++s) {
        const impl::LatticeRelaxResult& r = result[s];
        st.unconverged += r.converged ? 0 : 1;
        st.iterations += size_t(r.iterations);
        st.stages += size_t(r.stages);
        st.minDistance = std::min(st.minDistance, r.minDistance);
        glm::dvec3 mean(0.0);
        for (size_t v = 0; v < nv; ++v) mean += r.points[v] - rest.points[v];
        mean /= double(nv);
        for (size_t v = 0; v < nv; ++v) {
            const glm::dvec3 d = r.points[v] - rest.points[v] - mean;
            float* row = &table.data[4 * (s + total * v)];
            row[0] = float(d.x);
            row[1] = float(d.y);
            row[2] = float(d.z);
            row[3] = 0.0F;  // the solver has no twist variable: no twist change
        }
    }
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (stats) *stats = st;
    return table;
}

size_t strainTableStages(const StrainTableOptions& options) {
    validateOptions(options);
    const std::array<std::vector<double>, 3> axes = {linspace(options.sxRange, options.samples[0]),
                                                     linspace(options.saRange, options.samples[1]),
                                                     linspace(options.syRange, options.samples[2])};
    const Index3 zero = nearestZero(axes);
    size_t stages = 0;
    for (const std::vector<Index3>& layer : walkFrom(zero, options.samples).layers)
        for (const Index3& i : layer) {
            const Strain s = strainAt(axes, i);
            const glm::dmat2 F = latticeMap(s);
            if (s.sx == 0 && s.sa == 0 && s.sy == 0) continue;  // the rest cell itself
            if (i == zero) {
                stages += size_t(impl::latticeStages(F, glm::dmat2(1.0)));
                continue;
            }
            const std::vector<Index3> from = lowerNeighbours(i, zero);
            for (size_t k = 0; k < from.size() && int(k) < options.startsPerSample; ++k)
                stages += size_t(impl::latticeStages(F, latticeMap(strainAt(axes, from[k]))));
        }
    return stages;
}

namespace {

// CPU seconds of the calling thread.
double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

double estimateStrainTableSeconds(const Pattern& pattern, const StrainTableOptions& options) {
    validateOptions(options);
    // A few Newton iterations timed (thread CPU time, repeated to at least 50 ms so that a small
    // cell's 2 ms are not one scheduler tick), times the work a table does in units of those
    // iterations. The iterations: the pattern's cell on the lattice stretched by 10 % along the
    // courses (distances only grow, so no crossing is pressed through at the start; the stretched
    // yarn makes every step a real one), the gradient tolerance 0 so none stops early.
    constexpr int kTimedIterations = 10;
    impl::LatticeRelaxOptions timed = solverOptions(options);
    timed.maxIterations = kTimedIterations;
    timed.gradientTolerance = 0;
    const impl::LatticeCell cell(pattern, timed);  // throws for a pattern no table can be made for
    const glm::dmat2 stretched(glm::dvec2(1.1, 0.0), glm::dvec2(0.0, 1.0));
    double spent = 0;
    int iterations = 0;
    while (spent < 0.05 || iterations == 0) {
        const double c0 = threadSeconds();
        iterations += std::max(1, cell.relax(stretched, {}, stretched).iterations);
        spent += threadSeconds() - c0;
    }
    const double perIteration = spent / double(iterations);
    // The work, in timed iterations, measured on whole default tables (process CPU over their
    // lattice stages and over the timed iterations' cost, back to back on the same machine,
    // docs/deformation.md "400-vertex patterns"). Dense Newton (up to 64 cell vertices): the
    // stockinette; sparse: chart:basketweave, whose timed iterations (from the unrelaxed cell,
    // each a new factorisation) cost several times a table's (conjugate gradients on a kept
    // factor). The rest cell (up to 8 x the cap at a thousandth of the tolerance) runs alone first.
    const bool dense = impl::denseNewton(cell.vertexCount());
    const double perStage = dense ? kDensePerStage : kSparsePerStage;
    const double cap = std::min(1.0, double(options.maxIterations) / 600.0);  // a lower iteration cap: less work
    const unsigned threads = std::max(1U, std::thread::hardware_concurrency());
    return perIteration * cap * (perStage * double(strainTableStages(options)) / double(threads) + kRest);
}

StrainCellResult relaxStrainCell(const Pattern& pattern, const Strain& strain, const StrainTableOptions& solver,
                                 double restLengthScale) {
    validateOptions(solver);
    impl::LatticeRelaxOptions o = solverOptions(solver);
    o.restLengthScale = restLengthScale;
    const glm::dmat2 F = latticeMap(strain);
    const impl::LatticeRelaxResult r = impl::LatticeCell(pattern, o).relax(F, {});
    return {impl::cellYarnLength(pattern, r.points, F) / impl::cellYarnLength(pattern, pattern.points, glm::dmat2(1.0)),
            r.minDistance, r.iterations, r.converged};
}

}  // namespace knit
