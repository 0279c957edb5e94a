// hard_cases.hpp — the catalogue of awkward inputs, generated in code, and the fixture that runs
// the whole pipeline (buildScene: grid, tiling, stitch, binding, evaluation, plies) over each case
// and checks the invariants every result must keep:
//   * nothing non-finite anywhere (UV yarns, binding, mapped yarns and normals, plies);
//   * a consistent structure (offsets, closed flags, counts in the stats);
//   * bound vertices on non-degenerate UV triangles with barycentrics in [0, 1];
//   * yarns continuous where the surface is continuous: no step longer than a pattern edge can
//     become on this mesh (largest UV-to-3D stretch times the longest pattern edge in UV, plus the
//     height offsets), so a yarn never jumps across a gap, a notch or a fold of the UV layout;
//   * the documented behaviour at every boundary: an open yarn end lies on the UV boundary (cut
//     where it leaves, clamped when within tolerance), welds only join ends that met in 3D;
//   * no crash and no hang (a watchdog aborts with the case name).
// Cases are built from small parametric pieces (sheets, charts, patterns) so new cases are one
// entry each; see docs/hard-cases.md for what happens in each class of case.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "knit/scene.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

namespace knit::hard {

using util::kPi;

// ---- watchdog --------------------------------------------------------------------------------
// Aborts the process with the case name when a case runs longer than the limit: a hang shows up
// as a named failure, not as a silent ctest timeout. KNIT_HARD_TIMEOUT (seconds) overrides it
// (sanitizer builds are several times slower).
class Watchdog {
public:
    explicit Watchdog(std::string what, double seconds = 240) : what_(std::move(what)) {
        if (const char* env = std::getenv("KNIT_HARD_TIMEOUT")) seconds = std::atof(env);
        thread_ = std::thread([this, seconds] {
            std::unique_lock<std::mutex> lock(mutex_);
            if (!cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return done_; })) {
                std::fprintf(stderr, "hard case '%s' did not finish within %.0f s (hang?)\n", what_.c_str(), seconds);
                std::fflush(stderr);
                std::abort();
            }
        });
    }
    ~Watchdog() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }

private:
    std::string what_;
    std::mutex mutex_;
    std::condition_variable cv_;
    bool done_ = false;
    std::thread thread_;
};

// ---- mesh pieces -----------------------------------------------------------------------------
using SurfaceFn = std::function<glm::dvec3(double s, double t)>;
using UvFn = std::function<glm::dvec2(double s, double t)>;

// An nu x nv quad sheet over (s, t) in [0,1]^2: position pos(s, t), uv uv(s, t); quads split
// (a, b, c), (a, c, d) like the built-in meshes. wrapS: column s = 1 reuses the positions of
// column s = 0 (a closed surface with a UV seam: two UV columns, one position column).
inline BaseMesh sheet(const std::string& name, int nu, int nv, const SurfaceFn& pos, const UvFn& uv,
                      bool wrapS = false) {
    BaseMesh m;
    m.name = name;
    const int cols = wrapS ? nu : nu + 1;
    for (int j = 0; j <= nv; ++j) {
        for (int i = 0; i < cols; ++i) m.positions.push_back(pos(double(i) / nu, double(j) / nv));
        for (int i = 0; i <= nu; ++i) m.uvs.push_back(uv(double(i) / nu, double(j) / nv));
    }
    auto P = [&](int i, int j) { return uint32_t(j * cols + (wrapS ? i % nu : i)); };
    auto U = [&](int i, int j) { return uint32_t(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            m.faces.emplace_back(P(i, j), P(i + 1, j), P(i + 1, j + 1));
            m.faceUvs.emplace_back(U(i, j), U(i + 1, j), U(i + 1, j + 1));
            m.faces.emplace_back(P(i, j), P(i + 1, j + 1), P(i, j + 1));
            m.faceUvs.emplace_back(U(i, j), U(i + 1, j + 1), U(i, j + 1));
        }
    return m;
}

// A flat square of side `size` at z = 0 (x, y = s, t times size), uv = (s, t).
inline BaseMesh flatSquare(int n = 8, double size = 0.1) {
    return sheet(
        "square", n, n, [=](double s, double t) { return glm::dvec3(s * size, t * size, 0.0); },
        [](double s, double t) { return glm::dvec2(s, t); });
}

// Appends `part` to `into` (its own positions and UVs: a separate chart and component).
inline void append(BaseMesh& into, const BaseMesh& part) {
    const uint32_t p0 = uint32_t(into.positions.size()), u0 = uint32_t(into.uvs.size());
    into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
    into.uvs.insert(into.uvs.end(), part.uvs.begin(), part.uvs.end());
    for (const glm::uvec3& f : part.faces) into.faces.push_back(f + glm::uvec3(p0));
    for (const glm::uvec3& f : part.faceUvs) into.faceUvs.push_back(f + glm::uvec3(u0));
}

// Welds positions that are exactly equal (like the file loaders do), so separately built charts
// of one surface share 3D topology along their seams.
inline void weldPositions(BaseMesh& m) {
    std::vector<uint32_t> remap(m.positions.size());
    std::vector<glm::dvec3> kept;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        size_t k = 0;
        while (k < kept.size() && kept[k] != m.positions[i]) ++k;
        if (k == kept.size()) kept.push_back(m.positions[i]);
        remap[i] = uint32_t(k);
    }
    for (glm::uvec3& f : m.faces) f = glm::uvec3(remap[f.x], remap[f.y], remap[f.z]);
    m.positions = std::move(kept);
}

inline glm::dvec3 onCylinder(double radius, double height, double s, double t) {
    const double a = 2 * kPi * std::fmod(s, 1.0);  // s = 1 is exactly s = 0 (weldable)
    return {radius * std::cos(a), radius * std::sin(a), t * height};
}

// ---- patterns --------------------------------------------------------------------------------
// Straight courses along x: one course per cell at y = yOffset, `samples` vertices per period
// starting at x = xOffset, heights 0: frames without curvature.
inline Pattern straightCourses(double px, double py, double radius, double yOffset, int samples = 4,
                               double xOffset = 0) {
    Pattern p;
    p.name = "straight";
    p.px = px, p.py = py, p.radius = radius;
    for (int k = 0; k < samples; ++k) {
        p.points.emplace_back(xOffset + px * k / samples, yOffset, 0.0);
        p.twist.push_back(0.0);
    }
    for (int k = 0; k + 1 < samples; ++k) p.edges.push_back({uint32_t(k), uint32_t(k + 1), 0, 0});
    p.edges.push_back({uint32_t(samples - 1), 0, 1, 0});
    return p;
}

// Two courses whose vertices lie exactly on cell corners and edge midpoints: with repeats equal
// to a regular grid's resolution they land exactly on mesh vertices, on shared edges and on the
// quad diagonals. Heights alternate +-0.3 radius.
inline Pattern gridAlignedPattern(double period = 0.01, double radius = 0.001) {
    Pattern p;
    p.name = "grid-aligned";
    p.px = p.py = period;
    p.radius = radius;
    const double h = 0.3 * radius;
    p.points = {{0, 0, h}, {period / 2, 0, -h}, {0, period / 2, -h}, {period / 2, period / 2, h}};
    p.twist.assign(4, 0.0);
    p.edges = {{0, 1, 0, 0}, {1, 0, 1, 0}, {2, 3, 0, 0}, {3, 2, 1, 0}};
    return p;
}

// A course with a hairpin per period: right along y = py/2, up a leg, a half turn of radius
// `turn` (tighter than the ply offset), down the other leg, on to the right.
inline Pattern hairpinPattern(double radius = 0.001, double turn = 0.0003) {
    Pattern p;
    p.name = "hairpin";
    p.px = 8 * radius;
    p.py = 8 * radius;
    p.radius = radius;
    const double y0 = 0.5 * p.py, y1 = 0.8 * p.py, a = 3 * radius, step = 0.25 * radius;
    auto add = [&](double x, double y) {
        p.points.emplace_back(x, y, 0.0);
        p.twist.push_back(0.0);
    };
    for (double x = 0; x < a; x += step) add(x, y0);
    for (double y = y0; y < y1; y += step) add(a, y);
    for (int k = 0; k <= 8; ++k) {
        const double phi = kPi - kPi * k / 8;
        add(a + turn + turn * std::cos(phi), y1 + turn * std::sin(phi));
    }
    for (double y = y1 - step; y > y0; y -= step) add(a + 2 * turn, y);
    for (double x = a + 2 * turn; x < p.px - 1e-12; x += step) add(x, y0);
    const uint32_t n = uint32_t(p.points.size());
    for (uint32_t k = 0; k + 1 < n; ++k) p.edges.push_back({k, k + 1, 0, 0});
    p.edges.push_back({n - 1, 0, 1, 0});
    return p;
}

// Every vertex of `base` twice, the copies joined by zero-length edges (repeated points).
inline Pattern doubledPoints(const Pattern& base) {
    Pattern p = base;
    p.name = base.name + "-doubled";
    const uint32_t n = uint32_t(base.points.size());
    p.points.clear();
    p.twist.clear();
    for (uint32_t v = 0; v < n; ++v)
        for (int c = 0; c < 2; ++c) {
            p.points.push_back(base.points[v]);
            p.twist.push_back(base.twist[v]);
        }
    // Vertex v becomes (2v: arrival copy, 2v+1: departure copy).
    p.edges.clear();
    for (uint32_t v = 0; v < n; ++v) p.edges.push_back({2 * v, 2 * v + 1, 0, 0});
    for (const PeriodicEdge& e : base.edges) p.edges.push_back({2 * e.v0 + 1, 2 * e.v1, e.dx, e.dy});
    return p;
}

// One closed saddle ring per cell (no periodic edges): every tile is a closed loop whose RMF
// has a non-zero closing angle; `ringRadius` in units of the period.
inline Pattern ringPattern(double radius = 0.001, double ringRadius = 0.3, int samples = 29) {
    Pattern p;
    p.name = "rings";
    p.px = p.py = 10 * radius;
    p.radius = radius;
    for (int k = 0; k < samples; ++k) {
        const double a = 2 * kPi * k / samples;
        p.points.emplace_back(0.5 * p.px + ringRadius * p.px * std::cos(a),
                              0.5 * p.py + ringRadius * p.py * std::sin(a), 0.8 * radius * std::cos(2 * a));
        p.twist.push_back(0.0);
    }
    for (int k = 0; k < samples; ++k) p.edges.push_back({uint32_t(k), uint32_t((k + 1) % samples), 0, 0});
    return p;
}

// ---- expectations and the case type ----------------------------------------------------------
struct Expect {
    std::string errorHas;        // non-empty: buildScene must throw knit::Error containing it
    bool boundedSteps = true;    // the UV layout is continuous: steps bounded (see file comment)
    double extraStep = 0;        // metres added to the step bound (documented jumps, e.g. over a
                                 // zero-UV-area strip)
    bool endsOnBoundary = true;  // every open yarn end lies on the UV boundary
    int closedLoops = -1;        // exact count when >= 0
    int minClosedLoops = 0;
    int weldedEnds = -1;      // exact count when >= 0
    bool allowEmpty = false;  // the case may legitimately produce no yarns
};

struct HardCase {
    std::string name;
    Pattern pattern;
    BaseMesh mesh;
    SceneOptions options;
    Expect expect;
    // Case-specific checks on the built scene (the documented behaviour of this case).
    std::function<void(const Scene&)> check;
};

inline SceneOptions withRepeats(double u, double v, bool plies = true) {
    SceneOptions o;
    o.placement.repeats = {u, v};
    o.buildPlies = plies;
    return o;
}

// ---- invariant checks ------------------------------------------------------------------------
using util::finite;

// UV position of a bound vertex.
inline glm::dvec2 boundUv(const Scene& s, size_t i) {
    const Binding& b = s.binding();
    SurfacePoint sp{b.face[i], {1 - b.bary[i].x - b.bary[i].y, b.bary[i].x, b.bary[i].y}};
    return sp.interpolate(s.mesh().uvs, s.mesh().faceUvs);
}

// Largest stretch (largest singular value of the UV -> 3D Jacobian) over triangles with
// non-degenerate UVs.
inline double maxStretch(const BaseMesh& m) {
    double worst = 0;
    for (size_t f = 0; f < m.faces.size(); ++f) {
        const glm::uvec3 t = m.faces[f], tu = m.faceUvs[f];
        const glm::dvec3 e1 = m.positions[t.y] - m.positions[t.x], e2 = m.positions[t.z] - m.positions[t.x];
        const glm::dvec2 d1 = m.uvs[tu.y] - m.uvs[tu.x], d2 = m.uvs[tu.z] - m.uvs[tu.x];
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-12 * glm::length(d1) * glm::length(d2))) continue;
        const glm::dvec3 ju = (e1 * d2.y - e2 * d1.y) / det, jv = (e2 * d1.x - e1 * d2.x) / det;
        // Largest singular value of [ju jv] from its 2x2 Gram matrix.
        const double a = glm::dot(ju, ju), b = glm::dot(ju, jv), c = glm::dot(jv, jv);
        const double l = 0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b);
        worst = std::max(worst, std::sqrt(l));
    }
    return worst;
}

// Longest pattern edge in UV under the scene's placement.
inline double longestEdgeUv(const Scene& s) {
    const Pattern& p = s.pattern();
    const glm::dvec2 toUv(1.0 / (s.placement().repeats.x * p.px), 1.0 / (s.placement().repeats.y * p.py));
    double worst = 0;
    for (const PeriodicEdge& e : p.edges) {
        const glm::dvec2 d =
            glm::dvec2(p.points[e.v1]) + glm::dvec2(e.dx * p.px, e.dy * p.py) - glm::dvec2(p.points[e.v0]);
        worst = std::max(worst, glm::length(d * toUv));
    }
    return worst;
}

// Distance in UV from `uv` to the closest UV boundary edge of the mesh.
inline double distanceToUvBoundary(const Scene& s, glm::dvec2 uv) {
    double best = INFINITY;
    for (uint32_t he : s.grid().boundaryEdges) {
        const glm::uvec3 t = s.mesh().faceUvs[he / 3];
        const uint32_t c[3] = {t.x, t.y, t.z};
        const glm::dvec2 a = s.mesh().uvs[c[he % 3]], b = s.mesh().uvs[c[(he % 3 + 1) % 3]];
        const glm::dvec2 d = b - a;
        const double len2 = glm::dot(d, d);
        const double t01 = len2 > 0 ? std::clamp(glm::dot(uv - a, d) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, glm::distance(uv, a + t01 * d));
    }
    return best;
}

// Yarn radius in UV units as binding measures it (tolerances scale with it).
inline double radiusUv(const Scene& s) {
    const glm::dvec2 m = uvToMetreScale(s.mesh());
    return s.yarnRadius() / std::max(m.x, m.y);
}

// Yarn vertices whose offset surface folds over: the triangle's corners moved by the vertex's
// height along their normals have the opposite orientation from the triangle (the height
// exceeds the local radius of curvature, so the offset self-intersects). The report has no
// field for this yet; see docs/hard-cases.md (proposed: counts.folded_offset_vertices).
inline size_t foldedOffsetVertices(const Scene& s) {
    size_t folded = 0;
    const Binding& b = s.binding();
    for (size_t i = 0; i < b.vertexCount(); ++i) {
        const glm::uvec3 f = s.mesh().faces[b.face[i]];
        const glm::dvec3 x[3] = {s.mesh().positions[f.x], s.mesh().positions[f.y], s.mesh().positions[f.z]};
        const glm::dvec3 n[3] = {s.normals()[f.x], s.normals()[f.y], s.normals()[f.z]};
        const double h = b.height[i];
        const glm::dvec3 base = glm::cross(x[1] - x[0], x[2] - x[0]);
        const glm::dvec3 q0 = x[0] + h * n[0], q1 = x[1] + h * n[1], q2 = x[2] + h * n[2];
        if (glm::dot(glm::cross(q1 - q0, q2 - q0), base) < 0) ++folded;
    }
    return folded;
}

// The invariants of the file comment; failures name the case.
inline void checkInvariants(const std::string& name, const Scene& s, const SceneOptions& o, const Expect& e) {
    SCOPED_TRACE("hard case " + name);
    // 1. Finite everywhere.
    const UvYarns& uvYarns = s.stages().uvYarns;
    for (size_t i = 0; i < uvYarns.vertexCount(); ++i) {
        ASSERT_TRUE(finite(uvYarns.uv[i])) << "uv yarn vertex " << i;
        ASSERT_TRUE(std::isfinite(uvYarns.height[i]) && std::isfinite(uvYarns.twist[i])) << "uv yarn vertex " << i;
    }
    const Binding& b = s.binding();
    for (size_t i = 0; i < b.vertexCount(); ++i) {
        ASSERT_LT(b.face[i], s.mesh().faceCount()) << "bound vertex " << i;
        ASSERT_NE(s.grid().faceOrientation[b.face[i]], 0) << "bound vertex " << i << " on a zero-area UV triangle";
        const glm::dvec3 bary(1 - b.bary[i].x - b.bary[i].y, b.bary[i].x, b.bary[i].y);
        ASSERT_TRUE(finite(bary) && std::isfinite(b.height[i]) && std::isfinite(b.twist[i])) << "bound vertex " << i;
        for (int k = 0; k < 3; ++k) {
            ASSERT_GE(bary[k], -1e-12) << "bound vertex " << i;
            ASSERT_LE(bary[k], 1 + 1e-12) << "bound vertex " << i;
        }
    }
    const Polylines& c = s.yarns().curves;
    ASSERT_EQ(c.offsets.size(), c.curveCount() + 1);
    ASSERT_EQ(c.offsets.back(), c.pointCount());
    ASSERT_EQ(s.yarns().normals.size(), c.pointCount());
    for (size_t i = 0; i < c.pointCount(); ++i) {
        ASSERT_TRUE(finite(c.points[i])) << "yarn point " << i;
        ASSERT_NEAR(glm::length(s.yarns().normals[i]), 1.0, 1e-9) << "yarn normal " << i;
    }
    for (size_t i = 0; i < s.plies().curves.pointCount(); ++i) {
        ASSERT_TRUE(finite(s.plies().curves.points[i])) << "ply point " << i;
        ASSERT_NEAR(glm::length(s.plies().radial[i]), 1.0, 1e-9) << "ply radial " << i;
    }

    // 2. Structure and counts.
    size_t closed = 0, open = 0;
    for (size_t y = 0; y < c.curveCount(); ++y) {
        ASSERT_LE(c.begin(y), c.end(y));
        ASSERT_GE(c.size(y), 2u) << "yarn " << y << " is a single point";
        (c.isClosed(y) ? closed : open)++;
    }
    EXPECT_EQ(s.bindStats().closedLoops, closed);
    EXPECT_EQ(s.bindStats().openEnds, 2 * open);
    EXPECT_EQ(s.bindStats().weldedEnds % 2, 0u);
    if (!e.allowEmpty) EXPECT_GT(c.pointCount(), 0u) << "no yarn at all";
    if (e.closedLoops >= 0) EXPECT_EQ(closed, size_t(e.closedLoops));
    EXPECT_GE(closed, size_t(e.minClosedLoops));
    if (e.weldedEnds >= 0) EXPECT_EQ(s.bindStats().weldedEnds, size_t(e.weldedEnds));
    if (o.buildPlies) {
        size_t expectedPlyCurves = 0;
        for (size_t y = 0; y < c.curveCount(); ++y) expectedPlyCurves += size_t(o.plies.count);
        EXPECT_EQ(s.plies().curves.curveCount(), expectedPlyCurves);
        for (size_t k = 0; k < s.plies().curves.curveCount(); ++k)
            ASSERT_EQ(s.plies().curves.closed[k], c.closed[s.plies().yarnOfCurve[k]]) << "ply curve " << k;
    }

    // 3. Yarns stay on the surface: inside the mesh's box grown by the largest height.
    double hMax = 0;
    for (double h : b.height) hMax = std::max(hMax, std::abs(h));
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::uvec3& f : s.mesh().faces)
        for (int k = 0; k < 3; ++k)
            lo = glm::min(lo, s.mesh().positions[f[k]]), hi = glm::max(hi, s.mesh().positions[f[k]]);
    const double scale = std::max(glm::length(hi - lo), std::max(glm::length(hi), glm::length(lo)));
    const double slack = hMax + 1e-12 * scale;
    for (size_t i = 0; i < c.pointCount(); ++i) {
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(c.points[i], lo - slack)) &&
                    glm::all(glm::lessThanEqual(c.points[i], hi + slack)))
            << "yarn point " << i << " left the surface's box";
    }
    if (c.pointCount() == 0) return;

    // 4. Continuity: no step longer than the longest pattern edge can become on this mesh
    //    (plus the clamp tolerance at both ends, the height offsets and a weld's gap).
    const double tolUv = o.bind.clampTolerance * radiusUv(s);
    if (e.boundedSteps) {
        const double bound = maxStretch(s.mesh()) * (longestEdgeUv(s) + 2 * tolUv) + 2 * hMax +
                             o.bind.weldTolerance * s.yarnRadius() + e.extraStep + 1e-9 * scale;
        double worst = 0;
        size_t worstAt = 0;
        for (size_t y = 0; y < c.curveCount(); ++y)
            for (uint32_t k = 0; k < c.segmentCount(y); ++k) {
                const size_t i = c.begin(y) + k, j = c.begin(y) + (k + 1) % c.size(y);
                const double step = glm::distance(c.points[i], c.points[j]);
                if (step > worst) worst = step, worstAt = i;
            }
        EXPECT_LE(worst, bound) << "yarn jumps " << worst << " m at point " << worstAt << " (bound " << bound << ")";
    }

    // 5. Boundaries: an open yarn ends where it leaves the UV region (cut) or on the boundary
    //    point it was clamped to.
    if (e.endsOnBoundary) {
        const double limit = tolUv * (1 + 1e-9) + 1e-12;
        for (size_t y = 0; y < c.curveCount(); ++y) {
            if (c.isClosed(y)) continue;
            for (size_t i : {size_t(c.begin(y)), size_t(c.end(y) - 1)}) {
                const double d = distanceToUvBoundary(s, boundUv(s, i));
                EXPECT_LE(d, limit) << "yarn " << y << " ends inside the UV region (vertex " << i << ", " << d
                                    << " UV units from the boundary)";
            }
        }
    }
}

// Runs the pipeline on a case under the watchdog: the scene, or nullopt after checking the
// expected error.
inline std::optional<Scene> runCase(const HardCase& hc) {
    Watchdog dog(hc.name);
    if (!hc.expect.errorHas.empty()) {
        try {
            buildScene(hc.pattern, hc.mesh, hc.options);
            ADD_FAILURE() << hc.name << ": expected knit::Error containing '" << hc.expect.errorHas << "'";
        } catch (const Error& err) {
            EXPECT_NE(std::string(err.what()).find(hc.expect.errorHas), std::string::npos)
                << hc.name << ": " << err.what();
        }
        return std::nullopt;
    }
    return buildScene(hc.pattern, hc.mesh, hc.options);
}

}  // namespace knit::hard
