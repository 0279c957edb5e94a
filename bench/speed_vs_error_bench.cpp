// speed_vs_error_bench.cpp — the measurement program behind docs/speed-vs-error.md.
//
// Not a Google Benchmark suite: one program that measures six speed-against-error trade-offs of
// libknit's settings on the machine it runs on, then writes the report from those numbers only.
// Run it through scripts/speed-vs-error.sh (builds Release, runs both steps, draws the plots):
//
//   speed_vs_error_bench measure --results R.json --work DIR [--images DIR] [--items 6,1,4,2,3,5]
//                                [--commit HASH] [--dirty 0|1] [--date TEXT] [--command TEXT] [--nproc N]
//   speed_vs_error_bench report  --results R.json --markdown docs/speed-vs-error.md
//                                --images docs/speed-vs-error --data DIR
//
// `measure` writes every raw number to R.json; `report` turns R.json into the Markdown report,
// one data file per plot and a gnuplot script (DIR/plots.gp) that draws the SVGs into --images.
//
// Timing: wall clock (steady_clock) around library calls, all cores (TBB default), best of N runs
// (the machine is shared: the minimum is the least disturbed run); the load average is recorded
// before and after every item, and the garment item (6) runs first so its peak memory (VmHWM,
// reset through /proc/self/clear_refs) is its own. Errors are measured against analytic geometry
// (exact helices, cylinders, tori, spheres), against the decoded file, or against a high-sample
// reference image, never estimated.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include <sys/resource.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/plies.hpp"
#include "knit/scene.hpp"
#include "knit/stitch.hpp"
#include "knit/sweep.hpp"
#include "knit/tiling.hpp"
#include "knit/uv_grid.hpp"

// The exporters (items 2, 3, 6) and render_check (item 5) are separate libraries that a build may
// leave out (KNIT_BUILD_EXPORTERS / KNIT_BUILD_RENDER_CHECK); bench/CMakeLists.txt links them when
// they exist, and the items that need a missing one are reported as not measured.
#if __has_include("knit/export.hpp")
#define KNIT_SVE_HAVE_EXPORTERS 1
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "knit/export.hpp"
#else
#define KNIT_SVE_HAVE_EXPORTERS 0
#endif
#if __has_include("knit/render.hpp")
#define KNIT_SVE_HAVE_RENDER 1
#include "knit/image_io.hpp"
#include "knit/ply_bsdf.hpp"
#include "knit/render.hpp"
#else
#define KNIT_SVE_HAVE_RENDER 0
#endif

namespace {

using glm::dvec2;
using glm::dvec3;
using nlohmann::json;
namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// ---- machine, memory, timing -------------------------------------------------------------------

double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::array<double, 3> loadAverage() {
    std::array<double, 3> l{0, 0, 0};
    std::ifstream in("/proc/loadavg");
    in >> l[0] >> l[1] >> l[2];
    return l;
}

// A "Key:   value kB" field of /proc/self/status or /proc/meminfo, in bytes (0 if absent).
size_t procField(const char* file, const std::string& key) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) {
            std::istringstream v(line.substr(key.size()));
            size_t kb = 0;
            v >> kb;
            return kb * 1024;
        }
    return 0;
}
size_t rssBytes() { return procField("/proc/self/status", "VmRSS:"); }
size_t peakRssBytes() { return procField("/proc/self/status", "VmHWM:"); }
// Resets VmHWM to the current RSS (Linux >= 4.0); returns false if the kernel refused.
bool resetPeakRss() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return bool(out);
}

// Process CPU time (user + system, all threads) in seconds.
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const size_t c = line.find(':');
            return c == std::string::npos ? line : line.substr(c + 2);
        }
    return "unknown";
}

struct Timing {
    double best = 0, median = 0;
    int runs = 0;
};

// Runs f at least minRuns and at most maxRuns times, stopping after budget seconds in total.
template <class F>
Timing timeRuns(F&& f, int minRuns = 2, int maxRuns = 5, double budget = 1.5) {
    std::vector<double> t;
    double total = 0;
    while (int(t.size()) < maxRuns && (int(t.size()) < minRuns || total < budget)) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        t.push_back(seconds(t0));
        total += t.back();
    }
    std::sort(t.begin(), t.end());
    return {t.front(), t[t.size() / 2], int(t.size())};
}

// The same with an untimed setup step before every run (e.g. removing the previous output file).
template <class S, class F>
Timing timeRunsWithSetup(S&& setup, F&& f, int minRuns, int maxRuns, double budget) {
    std::vector<double> t;
    double total = 0;
    while (int(t.size()) < maxRuns && (int(t.size()) < minRuns || total < budget)) {
        setup();
        const auto t0 = std::chrono::steady_clock::now();
        f();
        t.push_back(seconds(t0));
        total += t.back();
    }
    std::sort(t.begin(), t.end());
    return {t.front(), t[t.size() / 2], int(t.size())};
}

json timingJson(const Timing& t) { return {{"best", t.best}, {"median", t.median}, {"runs", t.runs}}; }

json loadJson() {
    const auto l = loadAverage();
    return json::array({l[0], l[1], l[2]});
}

// Golden-section minimum of a unimodal f on [a, b].
template <class F>
double goldenMin(F&& f, double a, double b, int iterations = 60) {
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = f(c), fd = f(d);
    for (int i = 0; i < iterations; ++i) {
        if (fc < fd) {
            b = d, d = c, fd = fc;
            c = b - g * (b - a), fc = f(c);
        } else {
            a = c, c = d, fc = fd;
            d = a + g * (b - a), fd = f(d);
        }
    }
    return std::min(fc, fd);
}

// ---- item 1: ply resampling density ----------------------------------------------------------

// A yarn whose exact plies are known in closed form (what makePlies defines, see plies.hpp):
// straight along +x (surface normal +z, so N = +z, B = T x N = -y, parameter t = arc length), or
// a circle of radius rc in the xy-plane walked counter-clockwise (N = +z, B = outward radial,
// parameter t = angle, an integral number of ply turns around the loop).
struct AnalyticYarn {
    bool circle = false;
    double rc = 0, turns = 0, pitch = 0;

    dvec3 ply(const knit::PlyOptions& o, int i, double t) const {
        const double handed = o.twist == knit::Twist::Z ? 1.0 : -1.0;
        const double phase = 2.0 * kPi * i / o.count;
        dvec3 c, n(0, 0, 1), b;
        double theta;
        if (!circle) {
            c = dvec3(t, 0, 0);
            b = dvec3(0, -1, 0);
            theta = handed * 2.0 * kPi * t / pitch;
        } else {
            c = rc * dvec3(std::cos(t), std::sin(t), 0);
            b = dvec3(std::cos(t), std::sin(t), 0);
            theta = handed * turns * t;
        }
        return c + o.centerRadius * (std::cos(theta + phase) * n + std::sin(theta + phase) * b);
    }
    // Parameter guess for a point near the yarn and the bracket half-width for a chord of length len.
    double guess(const dvec3& q) const { return circle ? std::atan2(q.y, q.x) : q.x; }
    double bracket(double len) const { return circle ? 1.5 * len / rc + 1e-9 : 1.5 * len + 1e-12; }
};

struct PlyDeviation {
    double maxDistance = 0;
    size_t plyPoints = 0;
};

// Max distance from the ply polylines (vertices and 7 points inside every segment) to the exact
// helices: the deviation of the polyline from the curve, not only at its vertices.
PlyDeviation plyDeviation(const knit::Plies& plies, const AnalyticYarn& yarn, const knit::PlyOptions& o) {
    PlyDeviation d;
    d.plyPoints = plies.curves.pointCount();
    const knit::Polylines& c = plies.curves;
    for (size_t k = 0; k < c.curveCount(); ++k) {
        const int ply = plies.plyOfCurve[k];
        const uint32_t b = c.begin(k), n = c.size(k);
        for (uint32_t s = 0; s < c.segmentCount(k); ++s) {
            const dvec3 p0 = c.points[b + s], p1 = c.points[b + (s + 1) % n];
            const double len = glm::length(p1 - p0);
            for (int j = 0; j < 8; ++j) {
                const dvec3 q = p0 + (j / 8.0) * (p1 - p0);
                const double t0 = yarn.guess(q), w = yarn.bracket(len);
                const double d2 = goldenMin([&](double t) {
                    const dvec3 e = q - yarn.ply(o, ply, t);
                    return glm::dot(e, e);
                }, t0 - w, t0 + w);
                d.maxDistance = std::max(d.maxDistance, std::sqrt(d2));
            }
        }
    }
    return d;
}

knit::MappedYarns oneYarn(const std::vector<dvec3>& points, bool closed) {
    knit::MappedYarns y;
    y.curves.addCurve(points.data(), points.size(), closed);
    y.normals.assign(points.size(), dvec3(0, 0, 1));
    return y;
}

// The project's stockinette on the drape at `repeats`, without plies (the input of the ply,
// tube and Draco measurements).
knit::Scene knitScene(int meshRes, double meshSize, dvec2 repeats, bool plies) {
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = meshRes;
    mo.size = meshSize;
    knit::SceneOptions so;
    so.placement.repeats = repeats;
    so.buildPlies = plies;
    return knit::buildScene(knit::generateStockinette(), knit::makeDrape(mo), so);
}

json measurePlies() {
    json out;
    const double R = 0.001;                      // yarn radius (metres); errors are reported in R
    knit::PlyOptions base;
    base.yarnRadius = R;
    const knit::PlyOptions resolved = knit::resolvePlyOptions(base);
    const double pitch = resolved.pitch;
    // Input vertex spacings of the pattern's yarns: quantiles of the segment lengths of the
    // pipeline's mapped yarns, so the analytic yarns are resampled from the densities real ones
    // have (the resampler splits each input segment into a whole number of pieces, so the error
    // of one setting depends on the input spacing: the reported error is the worst over these).
    const knit::Scene speed = knitScene(64, 0.5, {70, 70}, false);
    std::vector<double> seg;
    for (size_t c = 0; c < speed.yarns.curves.curveCount(); ++c)
        for (uint32_t s = 0; s + 1 < speed.yarns.curves.size(c); ++s)
            seg.push_back(glm::distance(speed.yarns.curves.points[speed.yarns.curves.begin(c) + s],
                                        speed.yarns.curves.points[speed.yarns.curves.begin(c) + s + 1]) /
                          speed.yarnRadius);
    std::sort(seg.begin(), seg.end());
    // Tightest bends of the real yarns: circumradius of consecutive vertex triples (5% quantile).
    std::vector<double> bend;
    for (size_t c = 0; c < speed.yarns.curves.curveCount(); ++c)
        for (uint32_t s = 0; s + 2 < speed.yarns.curves.size(c); ++s) {
            const dvec3* p = speed.yarns.curves.points.data() + speed.yarns.curves.begin(c) + s;
            const double a = glm::distance(p[0], p[1]), b = glm::distance(p[1], p[2]), d = glm::distance(p[0], p[2]);
            const double area2 = glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
            if (area2 > 0) bend.push_back(a * b * d / (2 * area2) / speed.yarnRadius);
        }
    std::sort(bend.begin(), bend.end());
    const std::vector<double> quantiles = {0.05, 0.25, 0.5, 0.75, 0.95};
    std::vector<double> spacings;  // in R
    for (double q : quantiles) spacings.push_back(seg[std::min(seg.size() - 1, size_t(q * double(seg.size())))]);

    // Straight yarn: 12 ply turns; circle: as tight as the real yarns' tight bends (5% quantile
    // of their circumradius), rounded to a whole number of ply turns around the loop.
    const double tightBend = bend.empty() ? 4 * pitch / (2 * kPi) / R : bend[bend.size() / 20];
    AnalyticYarn straight;
    straight.pitch = pitch;
    const double length = 12 * pitch;
    AnalyticYarn circle;
    circle.circle = true;
    circle.turns = std::max(1.0, std::round(2 * kPi * tightBend * R / pitch));
    circle.rc = circle.turns * pitch / (2 * kPi);
    std::vector<knit::MappedYarns> straightYarns, circleYarns;
    for (double spacingInR : spacings) {
        const double spacing = spacingInR * R;
        std::vector<dvec3> sp, cp;
        const int ns = int(std::ceil(length / spacing));
        for (int i = 0; i <= ns; ++i) sp.emplace_back(length * i / ns, 0, 0);
        const int nc = int(std::ceil(2 * kPi * circle.rc / spacing));
        for (int i = 0; i < nc; ++i) {
            const double t = 2 * kPi * i / nc;
            cp.push_back(circle.rc * dvec3(std::cos(t), std::sin(t), 0));
        }
        straightYarns.push_back(oneYarn(sp, false));
        circleYarns.push_back(oneYarn(cp, true));
    }

    double speedLength = 0;  // total length of the speed scene's yarns
    for (size_t c = 0; c < speed.yarns.curves.curveCount(); ++c) {
        const uint32_t b = speed.yarns.curves.begin(c), n = speed.yarns.curves.size(c);
        for (uint32_t s = 0; s < speed.yarns.curves.segmentCount(c); ++s)
            speedLength += glm::distance(speed.yarns.curves.points[b + s], speed.yarns.curves.points[b + (s + 1) % n]);
    }
    out["yarn_radius_m"] = R;
    out["pitch_in_R"] = pitch / R;
    out["plies"] = resolved.count;
    out["ply_radius_in_R"] = resolved.plyRadius / R;
    out["center_radius_in_R"] = resolved.centerRadius / R;
    out["input_spacing_quantiles"] = quantiles;
    out["input_spacings_in_R"] = spacings;
    out["circle_radius_in_R"] = circle.rc / R;
    out["tight_bend_radius_in_R"] = tightBend;
    out["circle_turns"] = circle.turns;
    out["speed_scene"] = {{"yarn_vertices", speed.yarns.curves.pointCount()},
                          {"yarns", speed.yarns.curves.curveCount()},
                          {"cells", speed.grid.cells.size()}};
    for (int k : {4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 48, 64}) {
        knit::PlyOptions o = base;
        o.samplesPerTurn = k;
        const knit::PlyOptions ro = knit::resolvePlyOptions(o);
        PlyDeviation ds, dc;
        json perSpacing = json::array();
        for (size_t i = 0; i < spacings.size(); ++i) {
            const PlyDeviation a = plyDeviation(knit::makePlies(straightYarns[i], o), straight, ro);
            const PlyDeviation b = plyDeviation(knit::makePlies(circleYarns[i], o), circle, ro);
            perSpacing.push_back({{"spacing_R", spacings[i]}, {"straight_R", a.maxDistance / R}, {"circle_R", b.maxDistance / R}});
            ds.maxDistance = std::max(ds.maxDistance, a.maxDistance);
            dc.maxDistance = std::max(dc.maxDistance, b.maxDistance);
        }
        knit::PlyOptions so = o;
        so.yarnRadius = speed.yarnRadius;
        size_t plyVertices = 0;
        const Timing t = timeRuns([&] {
            const knit::Plies p = knit::makePlies(speed.yarns, so);
            plyVertices = p.curves.pointCount();
        }, 3, 15, 1.0);
        const double yarnVertices = double(speed.yarns.curves.pointCount());
        json row;
        row["samples_per_turn"] = k;
        row["straight_max_dev_R"] = ds.maxDistance / R;
        row["circle_max_dev_R"] = dc.maxDistance / R;
        row["max_dev_R"] = std::max(ds.maxDistance, dc.maxDistance) / R;
        row["per_spacing"] = perSpacing;
        row["ply_points_per_turn"] = double(plyVertices) / ro.count / (speedLength / (ro.pitch / R * speed.yarnRadius));
        row["ply_vertices"] = plyVertices;
        row["ply_vertices_per_yarn_vertex"] = double(plyVertices) / yarnVertices;
        row["seconds"] = timingJson(t);
        row["ply_vertices_per_second"] = double(plyVertices) / t.best;
        row["ns_per_yarn_vertex"] = t.best / yarnVertices * 1e9;
        out["rows"].push_back(row);
        std::fprintf(stderr, "  samples/turn %2d: max dev %.2e R (straight %.2e, circle %.2e), %.1f M ply vert/s\n", k,
                     row["max_dev_R"].get<double>(), ds.maxDistance / R, dc.maxDistance / R,
                     double(plyVertices) / t.best / 1e6);
    }
    return out;
}

// ---- item 2: tube sides ----------------------------------------------------------------------

using CgalK = CGAL::Simple_cartesian<double>;
using CgalTri = CgalK::Triangle_3;
using CgalPrimitive = CGAL::AABB_triangle_primitive<CgalK, std::vector<CgalTri>::const_iterator>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<CgalK, CgalPrimitive>>;

// Exact tube surfaces: a cylinder of radius r around the x axis (x in [0, length]) and a torus
// (circle of radius rc in the xy-plane, tube radius r).
struct ExactTube {
    bool torus = false;
    double r = 0, rc = 0, length = 0;
    double distance(const dvec3& p) const {
        if (!torus) return std::abs(std::hypot(p.y, p.z) - r);
        return std::abs(std::hypot(std::hypot(p.x, p.y) - rc, p.z) - r);
    }
    dvec3 sample(double a, double b) const {  // a, b in [0, 1)
        const double psi = 2 * kPi * b;
        if (!torus) return {a * length, r * std::cos(psi), r * std::sin(psi)};
        const double phi = 2 * kPi * a;
        const double rho = rc + r * std::cos(psi);
        return {rho * std::cos(phi), rho * std::sin(phi), r * std::sin(psi)};
    }
};

// Symmetric Hausdorff distance between a swept tube mesh and the exact surface: mesh -> surface
// analytically at 45 points per triangle; surface -> mesh with CGAL's AABB tree (closest point on
// the triangles) from a dense grid on the exact surface.
struct Hausdorff {
    double meshToSurface = 0, surfaceToMesh = 0;
    double value() const { return std::max(meshToSurface, surfaceToMesh); }
};
Hausdorff tubeHausdorff(const knit::TubeMesh& m, const ExactTube& exact, int na, int nb) {
    Hausdorff h;
    std::vector<CgalTri> tris;
    tris.reserve(m.triangles.size());
    auto vertex = [&](uint32_t i) { return m.origin + dvec3(m.positions[i]); };
    const int S = 8;
    for (const glm::uvec3& t : m.triangles) {
        const dvec3 a = vertex(t.x), b = vertex(t.y), c = vertex(t.z);
        tris.emplace_back(CgalK::Point_3(a.x, a.y, a.z), CgalK::Point_3(b.x, b.y, b.z), CgalK::Point_3(c.x, c.y, c.z));
        for (int i = 0; i <= S; ++i)
            for (int j = 0; i + j <= S; ++j) {
                const dvec3 p = a + (double(i) / S) * (b - a) + (double(j) / S) * (c - a);
                h.meshToSurface = std::max(h.meshToSurface, exact.distance(p));
            }
    }
    CgalTree tree(tris.begin(), tris.end());
    tree.accelerate_distance_queries();
    for (int i = 0; i < na; ++i)
        for (int j = 0; j < nb; ++j) {
            const double a = exact.torus ? double(i) / na : double(i) / (na - 1);
            const dvec3 p = exact.sample(a, double(j) / nb);
            h.surfaceToMesh = std::max(h.surfaceToMesh, std::sqrt(tree.squared_distance(CgalK::Point_3(p.x, p.y, p.z))));
        }
    return h;
}

std::string workFile(const std::string& work, const std::string& name) { return (fs::path(work) / name).string(); }

size_t fileBytes(const std::string& path) {
    std::error_code ec;
    const auto n = fs::file_size(path, ec);
    return ec ? 0 : size_t(n);
}

// The scenes of items 2 and 3: the stockinette at its physical size (1 mm yarn radius) on a
// drape of `size` metres, with the library's default plies.
knit::Scene physicalScene(double size) { return knitScene(64, size, {0, 0}, true); }

json sceneSummary(const knit::Scene& s) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const dvec3& p : s.plies.curves.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return {{"cells", s.grid.cells.size()},
            {"yarn_vertices", s.yarns.curves.pointCount()},
            {"ply_vertices", s.plies.curves.pointCount()},
            {"ply_curves", s.plies.curves.curveCount()},
            {"yarn_radius_m", s.yarnRadius},
            {"ply_radius_m", s.plies.plyRadius},
            {"extent_m", {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}}};
}

#if KNIT_SVE_HAVE_EXPORTERS
json measureTubeSides(const knit::Scene& scene, const std::string& work) {
    json out;
    const double r = 1.0;  // ply radius (errors are reported in ply radii and yarn radii)
    const double plyToYarn = scene.plies.plyRadius / scene.yarnRadius;
    // Cylinder: a straight ply of 16 radii at the ply sampling of the default settings; torus: a
    // loop whose radius is the curvature radius of a default ply helix, (Rc^2 + c^2) / Rc with
    // Rc the ply centre radius and c = pitch / 2 pi, sampled at 360 points (chord error ~2e-4 r,
    // far below the faceting).
    const knit::PlyOptions po = knit::resolvePlyOptions(knit::PlyOptions{});
    const double step = (po.pitch / po.samplesPerTurn) / po.plyRadius * r;
    ExactTube cyl;
    cyl.r = r;
    cyl.length = 16 * r;
    knit::Polylines cylCurve;
    {
        std::vector<dvec3> p;
        const int n = int(std::ceil(cyl.length / step));
        for (int i = 0; i <= n; ++i) p.emplace_back(cyl.length * i / n, 0, 0);
        cylCurve.addCurve(p.data(), p.size(), false);
    }
    ExactTube torus;
    torus.torus = true;
    torus.r = r;
    const double c = po.pitch / (2 * kPi);
    torus.rc = (po.centerRadius * po.centerRadius + c * c) / po.centerRadius / po.plyRadius * r;
    knit::Polylines torusCurve;
    {
        std::vector<dvec3> p;
        for (int i = 0; i < 360; ++i) {
            const double t = 2 * kPi * i / 360;
            p.push_back(torus.rc * dvec3(std::cos(t), std::sin(t), 0));
        }
        torusCurve.addCurve(p.data(), p.size(), true);
    }
    std::vector<dvec3> cylSeed(cylCurve.pointCount(), dvec3(0, 0, 1)), torusSeed(torusCurve.pointCount(), dvec3(0, 0, 1));
    out["scene"] = sceneSummary(scene);
    out["ply_radius_in_yarn_radii"] = plyToYarn;
    out["torus_rc_in_r"] = torus.rc / r;
    out["cylinder_step_in_r"] = step / r;
    const std::string path = workFile(work, "sides.glb");
    for (int sides : {4, 5, 6, 8, 10, 12, 16}) {
        knit::TubeOptions to;
        to.sides = sides;
        to.caps = false;
        to.seedNormals = &cylSeed;
        const knit::TubeMesh mc = knit::sweepTubes(cylCurve, r, to, 0, 1, dvec3(0.0));
        to.seedNormals = &torusSeed;
        const knit::TubeMesh mt = knit::sweepTubes(torusCurve, r, to, 0, 1, dvec3(0.0));
        const Hausdorff hc = tubeHausdorff(mc, cyl, 257, 720), ht = tubeHausdorff(mt, torus, 1440, 360);
        knit::ExportOptions eo;
        eo.path = path;
        eo.what = knit::ExportWhat::Tubes;
        eo.sides = sides;
        knit::ExportStats es;
        const Timing t = timeRunsWithSetup([&] { fs::remove(path); }, [&] { es = knit::exportScene(scene, eo); }, 3, 10, 1.5);
        json row;
        row["sides"] = sides;
        row["cylinder_hausdorff_r"] = hc.value() / r;
        row["torus_hausdorff_r"] = ht.value() / r;
        row["cylinder_mesh_to_surface_r"] = hc.meshToSurface / r;
        row["cylinder_surface_to_mesh_r"] = hc.surfaceToMesh / r;
        row["torus_mesh_to_surface_r"] = ht.meshToSurface / r;
        row["torus_surface_to_mesh_r"] = ht.surfaceToMesh / r;
        row["hausdorff_r"] = std::max(hc.value(), ht.value()) / r;
        row["hausdorff_R"] = std::max(hc.value(), ht.value()) / r * plyToYarn;
        row["triangles"] = es.triangles;
        row["vertices"] = es.vertices;
        row["triangles_per_ply_vertex"] = double(es.triangles) / double(scene.plies.curves.pointCount());
        row["bytes"] = fileBytes(path);
        row["export_seconds"] = timingJson(t);
        out["rows"].push_back(row);
        std::fprintf(stderr, "  sides %2d: Hausdorff %.4f r (cyl %.4f, torus %.4f), %zu tris, %.1f MB, %.2f s\n", sides,
                     row["hausdorff_r"].get<double>(), hc.value() / r, ht.value() / r, es.triangles,
                     double(fileBytes(path)) / 1e6, t.best);
        fs::remove(path);
    }
    return out;
}

// ---- item 3: Draco quantization bits -----------------------------------------------------------

struct GlbVertex {
    dvec3 p;      // world position (node translations applied, double)
    glm::vec3 n;  // normal
};
struct GlbTubes {
    std::vector<GlbVertex> vertices;
    std::vector<double> chunkExtent;  // per primitive: largest axis extent of its positions
    double decodeSeconds = 0;
    size_t primitives = 0;
};

const char* bytesAt(const std::vector<char>& bin, size_t offset, size_t length, const std::string& what) {
    if (offset + length > bin.size()) throw knit::Error("GLB reader: " + what + " lies outside the BIN chunk");
    return bin.data() + offset;
}

// Reads the tube primitives of a GLB written by knit::exportScene: plain float32 POSITION/NORMAL
// accessors or KHR_draco_mesh_compression (decoded with the Draco library, timed), with the node
// translations applied. Only what the exporter writes is supported (buffer 0 = BIN chunk,
// translation-only nodes); anything else is an error.
GlbTubes readGlbTubes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw knit::Error("GLB reader: cannot open " + path);
    std::vector<char> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto u32 = [&](size_t o) {
        uint32_t v;
        std::memcpy(&v, bytesAt(file, o, 4, "header"), 4);
        return v;
    };
    if (file.size() < 20 || u32(0) != 0x46546C67u) throw knit::Error("GLB reader: " + path + " is not a GLB");
    const uint32_t jsonLength = u32(12);
    const char* jsonText = bytesAt(file, 20, jsonLength, "JSON chunk");
    const json doc = json::parse(jsonText, jsonText + jsonLength);
    std::vector<char> bin;
    const size_t binHeader = 20 + jsonLength;
    if (binHeader + 8 <= file.size()) {
        const uint32_t binLength = u32(binHeader);
        const char* b = bytesAt(file, binHeader + 8, binLength, "BIN chunk");
        bin.assign(b, b + binLength);
    }
    file.clear();
    file.shrink_to_fit();
    for (const json& v : doc["bufferViews"])
        if (v.value("buffer", 0) != 0) throw knit::Error("GLB reader: external buffers are not supported");

    GlbTubes out;
    auto view = [&](int index, size_t& length) {
        const json& v = doc["bufferViews"][size_t(index)];
        length = v["byteLength"].get<size_t>();
        return bytesAt(bin, v.value("byteOffset", size_t(0)), length, "bufferView");
    };
    auto readFloats = [&](int accessor, int comps, std::vector<float>& dst) {
        const json& a = doc["accessors"][size_t(accessor)];
        if (a["componentType"].get<int>() != 5126) throw knit::Error("GLB reader: only float accessors are supported");
        const json& v = doc["bufferViews"][a["bufferView"].get<size_t>()];
        const size_t count = a["count"].get<size_t>();
        const size_t stride = v.value("byteStride", size_t(0)) ? v["byteStride"].get<size_t>() : size_t(4 * comps);
        size_t length = 0;
        const char* base = view(a["bufferView"].get<int>(), length) + a.value("byteOffset", size_t(0));
        dst.resize(count * comps);
        for (size_t i = 0; i < count; ++i) std::memcpy(&dst[i * comps], base + i * stride, 4 * size_t(comps));
    };
    std::function<void(int, dvec3)> visit = [&](int nodeIndex, dvec3 parent) {
        const json& node = doc["nodes"][size_t(nodeIndex)];
        if (node.contains("matrix") || node.contains("rotation") || node.contains("scale"))
            throw knit::Error("GLB reader: only translation nodes are supported");
        dvec3 t = parent;
        if (node.contains("translation")) t += dvec3(node["translation"][0], node["translation"][1], node["translation"][2]);
        if (node.contains("mesh")) {
            for (const json& prim : doc["meshes"][node["mesh"].get<size_t>()]["primitives"]) {
                if (prim.value("mode", 4) != 4) continue;  // tubes only
                std::vector<float> pos, nor;
                if (prim.contains("extensions") && prim["extensions"].contains("KHR_draco_mesh_compression")) {
                    const json& ext = prim["extensions"]["KHR_draco_mesh_compression"];
                    size_t length = 0;
                    const char* data = view(ext["bufferView"].get<int>(), length);
                    const auto t0 = std::chrono::steady_clock::now();
                    draco::DecoderBuffer db;
                    db.Init(data, length);
                    draco::Decoder decoder;
                    auto decoded = decoder.DecodeMeshFromBuffer(&db);
                    if (!decoded.ok()) throw knit::Error("GLB reader: Draco decoding failed: " + decoded.status().error_msg_string());
                    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
                    out.decodeSeconds += seconds(t0);
                    const draco::PointAttribute* pa = mesh->GetAttributeByUniqueId(ext["attributes"]["POSITION"].get<uint32_t>());
                    const draco::PointAttribute* na = mesh->GetAttributeByUniqueId(ext["attributes"]["NORMAL"].get<uint32_t>());
                    if (!pa || !na) throw knit::Error("GLB reader: Draco primitive without POSITION/NORMAL");
                    pos.resize(size_t(mesh->num_points()) * 3);
                    nor.resize(pos.size());
                    for (uint32_t i = 0; i < mesh->num_points(); ++i) {
                        pa->GetMappedValue(draco::PointIndex(i), &pos[3 * size_t(i)]);
                        na->GetMappedValue(draco::PointIndex(i), &nor[3 * size_t(i)]);
                    }
                } else {
                    readFloats(prim["attributes"]["POSITION"].get<int>(), 3, pos);
                    readFloats(prim["attributes"]["NORMAL"].get<int>(), 3, nor);
                }
                glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
                for (size_t i = 0; i < pos.size() / 3; ++i) {
                    const glm::vec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
                    lo = glm::min(lo, p), hi = glm::max(hi, p);
                    out.vertices.push_back({t + dvec3(p), glm::vec3(nor[3 * i], nor[3 * i + 1], nor[3 * i + 2])});
                }
                out.chunkExtent.push_back(double(std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z})));
                ++out.primitives;
            }
        }
        if (node.contains("children"))
            for (const json& c : node["children"]) visit(c.get<int>(), t);
    };
    const size_t sceneIndex = doc.value("scene", size_t(0));
    for (const json& n : doc["scenes"][sceneIndex]["nodes"]) visit(n.get<int>(), dvec3(0.0));
    return out;
}

// Max distance from decoded vertices (every `stride`-th) to their original: the nearest plain
// vertex within `radius` whose normal agrees within 0.05 (neighbouring ring vertices differ by
// far more, so the true original is the one found). Unmatched vertices are counted.
struct DracoError {
    double maxError = 0;
    size_t checked = 0, unmatched = 0;
};
DracoError dracoError(const GlbTubes& plain, const GlbTubes& decoded, double radius, size_t stride) {
    DracoError e;
    const double cell = radius;
    struct Key {
        int64_t x, y, z;
        bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
    };
    struct KeyHash {
        size_t operator()(const Key& k) const {
            return size_t(k.x * 73856093) ^ size_t(k.y * 19349663) ^ size_t(k.z * 83492791);
        }
    };
    auto key = [&](const dvec3& p) {
        return Key{int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)), int64_t(std::floor(p.z / cell))};
    };
    std::unordered_map<Key, std::vector<uint32_t>, KeyHash> grid;
    for (uint32_t i = 0; i < plain.vertices.size(); ++i) grid[key(plain.vertices[i].p)].push_back(i);
    for (size_t i = 0; i < decoded.vertices.size(); i += stride) {
        const GlbVertex& v = decoded.vertices[i];
        const Key k = key(v.p);
        double best = std::numeric_limits<double>::max();
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find({k.x + dx, k.y + dy, k.z + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t j : it->second) {
                        const GlbVertex& w = plain.vertices[j];
                        if (glm::length(v.n - w.n) > 0.05f) continue;
                        best = std::min(best, glm::length(v.p - w.p));
                    }
                }
        ++e.checked;
        if (best > radius) ++e.unmatched;
        else e.maxError = std::max(e.maxError, best);
    }
    return e;
}

json measureDraco(const knit::Scene& scene, const std::string& work) {
    json out;
    const double R = scene.yarnRadius;
    out["scene"] = sceneSummary(scene);
    knit::ExportOptions plain;
    plain.what = knit::ExportWhat::Tubes;
    plain.path = workFile(work, "plain.glb");
    knit::ExportStats ps;
    const Timing tp = timeRunsWithSetup([&] { fs::remove(plain.path); }, [&] { ps = knit::exportScene(scene, plain); }, 3, 5, 1.0);
    out["sides"] = plain.sides;
    out["plain_bytes"] = fileBytes(plain.path);
    out["plain_export_seconds"] = tp.best;
    out["tube_vertices"] = ps.vertices;
    const GlbTubes ref = readGlbTubes(plain.path);
    fs::remove(plain.path);
    for (int bits : {8, 9, 10, 11, 12, 13, 14, 15, 16}) {
        knit::ExportOptions d = plain;
        d.path = workFile(work, "draco.glb");
        d.draco = true;
        d.dracoBits = bits;
        knit::ExportStats ds;
        const Timing te = timeRunsWithSetup([&] { fs::remove(d.path); }, [&] { ds = knit::exportScene(scene, d); }, 2, 3, 2.0);
        const size_t bytes = fileBytes(d.path);
        double decodeBest = std::numeric_limits<double>::max();
        GlbTubes dec;
        for (int run = 0; run < 2; ++run) {
            dec = readGlbTubes(d.path);
            decodeBest = std::min(decodeBest, dec.decodeSeconds);
        }
        fs::remove(d.path);
        // Theoretical bound per chunk: half a quantization step per axis over the chunk's
        // largest extent; the search radius is 1.5 times the largest bound.
        double maxExtent = 0;
        for (double x : dec.chunkExtent) maxExtent = std::max(maxExtent, x);
        const double stepMax = maxExtent / double((1u << bits) - 1);
        const double bound = 0.5 * std::sqrt(3.0) * stepMax;
        const size_t stride = std::max<size_t>(1, dec.vertices.size() / 200000);
        const DracoError err = dracoError(ref, dec, 1.5 * bound + 1e-9, stride);
        json row;
        row["bits"] = bits;
        row["bytes"] = bytes;
        row["ratio_vs_plain"] = double(out["plain_bytes"].get<size_t>()) / double(bytes);
        row["export_seconds"] = timingJson(te);
        row["decode_seconds"] = decodeBest;
        row["decoded_vertices"] = dec.vertices.size();
        row["chunks"] = dec.primitives;
        row["max_chunk_extent_R"] = maxExtent / R;
        row["max_error_R"] = err.maxError / R;
        row["bound_R"] = bound / R;
        row["step_R"] = stepMax / R;
        row["checked_vertices"] = err.checked;
        row["unmatched_vertices"] = err.unmatched;
        out["rows"].push_back(row);
        std::fprintf(stderr, "  draco %2d bits: max error %.4f R (bound %.4f R), %.1f MB (plain %.1f MB), export %.2f s, decode %.2f s%s\n",
                     bits, err.maxError / R, bound / R, double(bytes) / 1e6, out["plain_bytes"].get<size_t>() / 1e6, te.best,
                     decodeBest, err.unmatched ? "  UNMATCHED VERTICES" : "");
    }
    return out;
}

#endif  // KNIT_SVE_HAVE_EXPORTERS

// ---- item 4: base-mesh resolution ----------------------------------------------------------------

struct AnalyticSurface {
    std::string name;
    knit::BaseMesh (*make)(const knit::ProceduralMeshOptions&);
    dvec2 repeats;
    double radius = 0.1, height = 0.3;
    bool sphere = false;
    // Exact point and unit normal at (u, v) (the parameterizations of procedural_mesh.cpp).
    std::pair<dvec3, dvec3> at(dvec2 uv) const {
        const double t = 2 * kPi * uv.x;
        if (!sphere) {
            const dvec3 n(std::cos(t), std::sin(t), 0);
            return {dvec3(radius * n.x, radius * n.y, uv.y * height), n};
        }
        const double phi = kPi * uv.y;
        const dvec3 n(std::sin(phi) * std::cos(t), std::sin(phi) * std::sin(t), -std::cos(phi));
        return {radius * n, n};
    }
};

json measureBaseMesh() {
    json out;
    const knit::Pattern pattern = knit::generateStockinette();
    const knit::PatternAdjacency adjacency = knit::buildAdjacency(pattern);
    AnalyticSurface cyl{"cylinder", &knit::makeCylinder, {80, 53}};
    AnalyticSurface sph{"sphere", &knit::makeSphere, {80, 56}};
    sph.sphere = true;
    out["surfaces"] = json::object();
    for (const AnalyticSurface& s : {cyl, sph}) {
        json js;
        js["radius_m"] = s.radius;
        if (!s.sphere) js["height_m"] = s.height;
        js["repeats"] = {s.repeats.x, s.repeats.y};
        for (int res : {8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256}) {
            knit::ProceduralMeshOptions mo;
            mo.radius = s.radius;
            mo.height = s.height;
            mo.resU = res;
            mo.resV = s.sphere ? res / 2 : std::max(1, int(std::lround(res * s.height / (2 * kPi * s.radius))));
            const knit::BaseMesh mesh = s.make(mo);
            const std::vector<dvec3> normals = knit::vertexNormals(mesh.positions, mesh.faces);
            knit::PlacementOptions place;
            place.repeats = s.repeats;
            const knit::PatternPlacement placement = knit::placePattern(pattern, mesh, place);
            knit::UvGridOptions go;
            go.cellSize = placement.cellSize();
            knit::UvGrid grid;
            const Timing tg = timeRuns([&] { grid = knit::buildUvGrid(mesh, go); }, 5, 20, 0.3);
            const knit::Tiling tiling = knit::tilesForCells(pattern, grid.cells);
            const knit::UvYarns uv = knit::stitchYarns(pattern, adjacency, tiling, placement);
            knit::BindOptions bo;
            bo.yarnRadius = pattern.radius * placement.scale;
            knit::BindResult bound;
            const Timing tb = timeRuns([&] { bound = knit::bindYarns(mesh, normals, grid, uv, bo); }, 5, 20, 0.5);
            knit::MappedYarns mapped;
            const Timing tv = timeRuns([&] {
                knit::evaluateBinding(bound.binding, mesh.faces, mesh.positions, normals, mapped);
            }, 3, 7, 0.3);
            // Error: mapped point against exact S(u, v) + h n(u, v) at the vertex's (u, v).
            const knit::Binding& b = bound.binding;
            double maxErr = 0, sumSq = 0;
            for (size_t i = 0; i < b.vertexCount(); ++i) {
                const glm::uvec3 fu = mesh.faceUvs[b.face[i]];
                const dvec2 w = b.bary[i];
                const dvec2 uvp = (1 - w.x - w.y) * mesh.uvs[fu.x] + w.x * mesh.uvs[fu.y] + w.y * mesh.uvs[fu.z];
                const auto [p, n] = s.at(uvp);
                const double e = glm::distance(mapped.curves.points[i], p + b.height[i] * n);
                maxErr = std::max(maxErr, e);
                sumSq += e * e;
            }
            const double R = bo.yarnRadius;
            const double cellWidth = 2 * kPi * s.radius / s.repeats.x;  // one stitch around (m)
            json row;
            row["res_u"] = mo.resU;
            row["res_v"] = mo.resV;
            row["triangles"] = mesh.faceCount();
            row["edge_in_stitches"] = (2 * kPi * s.radius / mo.resU) / cellWidth;
            row["yarn_vertices"] = b.vertexCount();
            row["max_error_R"] = maxErr / R;
            row["rms_error_R"] = std::sqrt(sumSq / double(std::max<size_t>(1, b.vertexCount()))) / R;
            row["grid_seconds"] = timingJson(tg);
            row["bind_seconds"] = timingJson(tb);
            row["evaluate_seconds"] = timingJson(tv);
            row["bind_total_seconds"] = tg.best + tb.best;
            row["yarn_vertices_per_second_bind"] = double(b.vertexCount()) / (tg.best + tb.best);
            js["yarn_radius_m"] = R;
            js["rows"].push_back(row);
            std::fprintf(stderr, "  %s %3dx%-3d: max error %.4f R, rms %.4f R, grid+bind %.1f ms, evaluate %.2f ms\n",
                         s.name.c_str(), mo.resU, mo.resV, maxErr / R, row["rms_error_R"].get<double>(),
                         (tg.best + tb.best) * 1e3, tv.best * 1e3);
        }
        out["surfaces"][s.name] = js;
    }
    return out;
}

// ---- item 5: render modes ------------------------------------------------------------------------

#if KNIT_SVE_HAVE_RENDER
json measureRender(const std::string& imageDir) {
    json out;
    // A small patch (6 cm plane, the stockinette at its physical size) in a small image.
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = 8;
    mo.size = 0.06;
    knit::SceneOptions so;
    const knit::Scene scene = knit::buildScene(knit::generateStockinette(), knit::makePlane(mo), so);
    knit::RenderOptions ro;
    ro.width = 80;
    ro.height = 60;
    ro.progress = false;
    ro.light = knit::LightPlacement::Front;
    const int refSpp = 1024;
    out["width"] = ro.width;
    out["height"] = ro.height;
    out["reference_spp"] = refSpp;
    out["light"] = knit::lightPlacementName(ro.light);
    out["tube_sides"] = ro.tubeSides;
    out["scene"] = {{"ply_vertices", scene.plies.curves.pointCount()},
                    {"ply_curves", scene.plies.curves.curveCount()},
                    {"cells", scene.grid.cells.size()},
                    {"plane_m", mo.size}};
    std::map<std::string, knit::Image> refs;
    for (const char* mode : {"curves", "tubes", "grid"}) {
        ro.mode = knit::parseMode(mode);
        ro.spp = refSpp;
        ro.seed = 1000003;
        if (!imageDir.empty()) {
            fs::create_directories(imageDir);
            ro.output = (fs::path(imageDir) / (std::string("render-") + mode + ".png")).string();
        }
        const knit::RenderResult ref = knit::renderScene(scene, ro);
        ro.output.clear();
        refs[mode] = ref.image;
        const double refLum = knit::luminance(ref.image.mean());
        json jm;
        jm["reference_seconds"] = ref.renderSeconds;
        jm["reference_mean_luminance"] = refLum;
        jm["scene_bytes"] = ref.memory.sceneBytes();
        jm["embree_bytes"] = ref.memory.embreeBytes;
        jm["geometry_bytes"] = ref.memory.geometryBytes;
        jm["shading_bytes"] = ref.memory.shadingBytes;
        jm["build_seconds"] = ref.buildSeconds;
        jm["primitives"] = ref.primitives;
        if (!imageDir.empty()) jm["reference_png"] = std::string("render-") + mode + ".png";
        for (int spp : {1, 2, 4, 8, 16, 32, 64}) {
            ro.spp = spp;
            ro.seed = 1;
            const knit::RenderResult r = knit::renderScene(scene, ro);
            const knit::ImageComparison c = knit::compareImages(r.image, ref.image);
            json row;
            row["spp"] = spp;
            row["render_seconds"] = r.renderSeconds;
            row["us_per_sample"] = r.renderSeconds / (double(ro.width) * ro.height * spp) * 1e6;
            row["rays_per_second"] = r.raysPerSecond;
            row["rmse"] = c.rmse;
            row["relative_rmse"] = c.rmse / refLum;
            jm["rows"].push_back(row);
            std::fprintf(stderr, "  %-6s spp %2d: RMSE %.2f%% of mean, %.2f us/sample, scene %.1f MB\n", mode, spp,
                         100 * c.rmse / refLum, row["us_per_sample"].get<double>(), ref.memory.sceneBytes() / 1e6);
        }
        out["modes"][mode] = jm;
    }
    // Differences between the modes' references (geometry, plus the references' own noise).
    // Expected from the references' noise alone: both 1-spp errors scaled to the reference spp.
    auto oneSpp = [&](const char* mode) { return out["modes"][mode]["rows"][0]["relative_rmse"].get<double>(); };
    for (const char* mode : {"tubes", "grid"}) {
        const knit::ImageComparison c = knit::compareImages(refs[mode], refs["curves"]);
        out["modes"][mode]["reference_vs_curves_relative_rmse"] = c.rmse / knit::luminance(refs["curves"].mean());
        out["modes"][mode]["reference_noise_relative_rmse"] =
            std::sqrt((oneSpp(mode) * oneSpp(mode) + oneSpp("curves") * oneSpp("curves")) / refSpp);
    }
    return out;
}

#endif  // KNIT_SVE_HAVE_RENDER

// ---- item 6: garment scale ---------------------------------------------------------------------

#if KNIT_SVE_HAVE_EXPORTERS
// The same garment with the plies held in memory (SceneOptions::buildPlies, what the non-glTF
// formats and tubes need): makePlies on the scene's yarns, then the GLB of those plies.
json measureMaterializedGarment(const knit::Scene& streamed, const std::string& path) {
    json out;
    out["reset_peak_ok"] = resetPeakRss();
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = cpuSeconds();
    const knit::Plies plies = knit::makePlies(streamed.yarns, streamed.plyOptions);
    out["plies_seconds"] = seconds(t0);
    knit::ExportInput in;
    in.curves = &plies.curves;
    in.radius = plies.plyRadius;
    knit::ExportOptions eo;
    eo.path = path;
    eo.what = knit::ExportWhat::Plies;
    const auto te = std::chrono::steady_clock::now();
    knit::exportCurves(in, eo);
    out["export_seconds"] = seconds(te);
    out["seconds"] = seconds(t0);
    out["cpu_seconds"] = cpuSeconds() - cpu0;
    out["peak_bytes"] = peakRssBytes();
    out["glb_bytes"] = fileBytes(path);
    fs::remove(path);
    std::fprintf(stderr, "  garment, plies in memory: %.2f s plies + %.2f s GLB, peak %.2f GB\n",
                 out["plies_seconds"].get<double>(), out["export_seconds"].get<double>(),
                 double(out["peak_bytes"].get<size_t>()) / 1e9);
    return out;
}

json measureGarment(int repeats, const std::string& work) {
    json out;
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = 256;
    mo.size = 2.0;
    const knit::Pattern pattern = knit::generateStockinette();
    knit::BaseMesh mesh = knit::makeDrape(mo);
    knit::SceneOptions so;
    so.placement.repeats = {double(repeats), double(repeats)};
    so.buildPlies = false;  // the GLB export generates and streams the plies (knit/export.hpp)
    // CPU time at every stage boundary (the progress callback runs before each stage): with the
    // wall times of Scene::timings this shows how much of the 2 cores each stage really got.
    std::vector<std::pair<std::string, double>> cpuMarks;
    so.progress = [&](const std::string& stage, int, int) { cpuMarks.emplace_back(stage, cpuSeconds()); };
    const std::string path = workFile(work, "garment.glb");
    fs::remove(path);
    out["reset_peak_ok"] = resetPeakRss();
    const size_t rss0 = rssBytes();
    const double cpu0 = cpuSeconds();
    const auto t0 = std::chrono::steady_clock::now();
    const knit::Scene scene = knit::buildScene(pattern, std::move(mesh), so);
    const double cpuBuilt = cpuSeconds();
    const size_t peakBuild = peakRssBytes();
    knit::ExportOptions eo;
    eo.path = path;
    eo.what = knit::ExportWhat::Plies;
    const auto te = std::chrono::steady_clock::now();
    const knit::ExportStats es = knit::exportScene(scene, eo);
    const double exportSeconds = seconds(te);
    const double total = seconds(t0);
    const double cpuTotal = cpuSeconds() - cpu0;
    const size_t peak = peakRssBytes();
    out["repeats"] = repeats;
    out["mesh"] = {{"name", "drape"}, {"res", mo.resU}, {"size_m", mo.size}, {"triangles", scene.mesh.faceCount()}};
    out["cells"] = scene.grid.cells.size();
    out["tiles"] = scene.tiling.tiles.size();
    out["yarn_vertices"] = scene.yarns.curves.pointCount();
    out["tiled_vertices"] = scene.uvYarns.vertexCount();
    out["ply_vertices"] = es.vertices;
    out["yarn_radius_m"] = scene.yarnRadius;
    out["samples_per_turn"] = knit::PlyOptions{}.samplesPerTurn;
    out["plies"] = knit::PlyOptions{}.count;
    for (size_t i = 0; i < scene.timings.size(); ++i) {
        const knit::StageTime& s = scene.timings[i];
        double cpu = -1;
        if (cpuMarks.size() == scene.timings.size() && cpuMarks[i].first == s.stage)
            cpu = (i + 1 < cpuMarks.size() ? cpuMarks[i + 1].second : cpuBuilt) - cpuMarks[i].second;
        out["stages"].push_back({{"stage", s.stage}, {"seconds", s.seconds}, {"cpu_seconds", cpu}});
    }
    out["stages"].push_back({{"stage", "plies_glb"}, {"seconds", exportSeconds}, {"cpu_seconds", cpuTotal - (cpuBuilt - cpu0)}});
    out["total_seconds"] = total;
    out["cpu_seconds"] = cpuTotal;
    out["glb_bytes"] = fileBytes(path);
    out["export_reported_peak_bytes"] = es.peakMemoryBytes;
    out["rss_before_bytes"] = rss0;
    out["peak_after_build_bytes"] = peakBuild;
    out["peak_bytes"] = peak;
    out["threads"] = std::thread::hardware_concurrency();
    fs::remove(path);
    std::fprintf(stderr, "  garment: %zu cells, %zu yarn vertices, %zu ply vertices: %.2f s (CPU %.2f s), peak %.2f GB\n",
                 scene.grid.cells.size(), scene.yarns.curves.pointCount(), es.vertices, total,
                 cpuTotal, double(peak) / 1e9);
    out["materialized"] = measureMaterializedGarment(scene, path);
    return out;
}

#endif  // KNIT_SVE_HAVE_EXPORTERS

// ---- measure command -------------------------------------------------------------------------------

void writeAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out.flush()) throw knit::Error("cannot write " + tmp);
    }
    fs::rename(tmp, path);
}

int measure(const std::string& resultsPath, const std::string& work, const std::string& imageDir, const std::string& items,
            const json& meta, int garmentRepeats) {
    static_cast<void>(imageDir);        // unused without render_check
    static_cast<void>(garmentRepeats);  // unused without the exporters
    fs::create_directories(work);
    if (fs::path(resultsPath).has_parent_path()) fs::create_directories(fs::path(resultsPath).parent_path());
    json r;
    r["meta"] = meta;
    r["machine"] = {{"cpu", cpuModel()},
                    {"hardware_threads", std::thread::hardware_concurrency()},
                    {"memory_bytes", procField("/proc/meminfo", "MemTotal:")}};
    r["defaults"] = {{"samples_per_turn", knit::PlyOptions{}.samplesPerTurn},
                     {"plies", knit::PlyOptions{}.count},
                     {"tube_options_sides", knit::TubeOptions{}.sides},
                     {"tube_options_caps", knit::TubeOptions{}.caps}};
#if KNIT_SVE_HAVE_EXPORTERS
    r["defaults"]["export_sides"] = knit::ExportOptions{}.sides;
    r["defaults"]["draco_bits"] = knit::ExportOptions{}.dracoBits;
#endif
#if KNIT_SVE_HAVE_RENDER
    r["defaults"]["render_tube_sides"] = knit::RenderOptions{}.tubeSides;
#endif
    r["load_start"] = loadJson();
    const auto start = std::chrono::steady_clock::now();
    for (char item : items) {
        if (item == ',' || item == ' ') continue;
        const std::string key = std::string("item") + item;
        std::fprintf(stderr, "speed-vs-error: item %c\n", item);
        const json loadBefore = loadJson();
        const auto t0 = std::chrono::steady_clock::now();
        json j;
        switch (item) {
            case '1': j = measurePlies(); break;
#if KNIT_SVE_HAVE_EXPORTERS
            case '2': j = measureTubeSides(physicalScene(0.2), work); break;
            case '3': j = measureDraco(physicalScene(0.1), work); break;
            case '6': j = measureGarment(garmentRepeats, work); break;
#else
            case '2':
            case '3':
            case '6': j = {{"skipped", "the exporters (knit::exporters) were not built"}}; break;
#endif
            case '4': j = measureBaseMesh(); break;
#if KNIT_SVE_HAVE_RENDER
            case '5': j = measureRender(imageDir); break;
#else
            case '5': j = {{"skipped", "render_check (knit::render_check) was not built"}}; break;
#endif
            default: throw knit::Error(std::string("unknown item '") + item + "' (expected 1..6)");
        }
        j["load_before"] = loadBefore;
        j["load_after"] = loadJson();
        j["item_seconds"] = seconds(t0);
        r[key] = j;
        // Written after every item, so a long run keeps what it measured.
        r["measure_seconds"] = seconds(start);
        r["load_end"] = loadJson();
        writeAtomically(resultsPath, r.dump(1));
    }
    return 0;
}

}  // namespace

// The report step lives in the second half of this file.
int writeReport(const std::string& resultsPath, const std::string& markdownPath, const std::string& imageDir,
                const std::string& dataDir);

int main(int argc, char** argv) {
    CLI::App app{"Measures libknit's speed-against-error trade-offs and writes docs/speed-vs-error.md"};
    app.require_subcommand(1);
    std::string results, work = "speed-vs-error-work", items = "6,1,4,2,3,5";
    json meta = json::object();
    std::string commit = "unknown", date = "unknown", command = "", dirty = "unknown";
    int garmentRepeats = 660;
    std::string nproc = "";
    CLI::App* m = app.add_subcommand("measure", "Run the measurements and write the results JSON");
    m->add_option("--results", results, "Results JSON to write")->required();
    m->add_option("--work", work, "Scratch folder for exported files (removed after each use)");
    m->add_option("--items", items, "Items to run, in order (1..6)");
    m->add_option("--commit", commit, "git commit of the measured tree");
    m->add_option("--dirty", dirty, "1 if the tree had uncommitted changes");
    m->add_option("--date", date, "Date of the run");
    m->add_option("--command", command, "The command that produced the run");
    m->add_option("--nproc", nproc, "Output of nproc (processing units available to the run)");
    m->add_option("--garment-repeats", garmentRepeats, "Repeats per side of the garment case (item 6)");
    std::string markdown, images, data;
    m->add_option("--images", images, "Folder for the reference renders of item 5 (PNG)");
    CLI::App* rep = app.add_subcommand("report", "Write the Markdown report, plot data and gnuplot script");
    rep->add_option("--results", results, "Results JSON")->required();
    rep->add_option("--markdown", markdown, "Markdown report to write")->required();
    rep->add_option("--images", images, "Folder for the SVG plots (the report links them relative to itself)")->required();
    rep->add_option("--data", data, "Folder for plot data and plots.gp")->required();
    CLI11_PARSE(app, argc, argv);
    try {
        if (m->parsed()) {
            meta = {{"commit", commit}, {"dirty", dirty}, {"date", date}, {"command", command}, {"items", items}, {"nproc", nproc}};
            return measure(results, work, images, items, meta, garmentRepeats);
        }
        return writeReport(results, markdown, images, data);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "speed_vs_error_bench: error: %s\n", e.what());
        return 1;
    }
}

// ==== report: results JSON -> Markdown + plot data + gnuplot script ================================

namespace {

std::string fmt(double v, int digits = 3) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}
std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}
std::string mb(double bytes) { return fixed(bytes / 1e6, bytes < 1e7 ? 2 : 1); }
std::string gib(double bytes) { return fixed(bytes / double(1ull << 30), 2); }
std::string loadText(const json& l) {
    if (!l.is_array() || l.size() < 3) return "n/a";
    return fixed(l[0].get<double>(), 2) + " / " + fixed(l[1].get<double>(), 2) + " / " + fixed(l[2].get<double>(), 2);
}
std::string str(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }
std::string marks(bool knee, bool def) {
    if (knee && def) return " (knee, default)";
    return knee ? " (knee)" : def ? " (default)" : "";
}

// Kneedle (Satopaa et al. 2011) on a decreasing error-vs-cost curve: both axes normalised to
// [0, 1] over the measured range, the score of a point is its distance below the chord from the
// cheapest to the most expensive setting (1 - x - y). Where the curve is flat near its knee
// several points score almost alike, so the knee is the cheapest point scoring within 1% of the
// best (robust to tiny changes of the data or of the sweep).
struct Knee {
    size_t index = 0;
    std::vector<double> score;
};
Knee kneedle(const std::vector<double>& cost, const std::vector<double>& err) {
    const auto [cmin, cmax] = std::minmax_element(cost.begin(), cost.end());
    const auto [emin, emax] = std::minmax_element(err.begin(), err.end());
    const double cr = std::max(*cmax - *cmin, 1e-300), er = std::max(*emax - *emin, 1e-300);
    Knee k;
    double best = -1e300;
    for (size_t i = 0; i < cost.size(); ++i) {
        k.score.push_back(1.0 - (cost[i] - *cmin) / cr - (err[i] - *emin) / er);
        best = std::max(best, k.score.back());
    }
    const double threshold = best - 0.01 * std::abs(best);
    bool found = false;
    for (size_t i = 0; i < cost.size(); ++i)
        if (k.score[i] >= threshold && (!found || cost[i] < cost[k.index])) {
            k.index = i;
            found = true;
        }
    return k;
}

std::vector<double> column(const json& rows, const std::string& key) {
    std::vector<double> v;
    for (const json& r : rows) {
        const json& x = r.at(key);
        v.push_back(x.is_object() ? x.at("best").get<double>() : x.get<double>());
    }
    return v;
}

struct Report {
    std::ostringstream md;
    std::ostringstream gp;
    std::string dataDir, imageDir, imageRel;
    json summary = json::array();  // rows of the summary table
    double budgetR = std::nan("");  // faceting error of the default tube (yarn radii), from item 2
    int budgetSides = 0;

    void data(const std::string& name, const std::string& text) {
        std::ofstream out(fs::path(dataDir) / name);
        out << text;
    }
    void plotHeader(const std::string& svg, const std::string& title, const std::string& xlabel,
                    const std::string& ylabel, bool logx, bool logy) {
        gp << "\nreset\nset terminal svg size 760,460 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n"
           << "set output '" << (fs::path(imageDir) / svg).string() << "'\n"
           << "set title \"" << title << "\"\nset xlabel \"" << xlabel << "\"\nset ylabel \"" << ylabel << "\"\n"
           << "set grid\nset key top right box opaque\n"
           << (logx ? "set logscale x\n" : "") << (logy ? "set logscale y\nset format y '%g'\n" : "");
    }
    // Two panels side by side sharing the y axis meaning: call panel() before each plot command,
    // endMulti() after the second.
    void multiHeader(const std::string& svg, const std::string& title) {
        gp << "\nreset\nset terminal svg size 1040,440 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n"
           << "set output '" << (fs::path(imageDir) / svg).string() << "'\n"
           << "set multiplot layout 1,2 title \"" << title << "\"\n";
    }
    void panel(const std::string& xlabel, const std::string& ylabel, bool logx, bool logy,
               const std::string& key = "top right") {
        gp << "unset logscale\nset xlabel \"" << xlabel << "\"\nset ylabel \"" << ylabel << "\"\n"
           << "set grid\nset key " << key << " box opaque\nset format x '%g'\nset format y '%g'\n"
           << (logx ? "set logscale x\n" : "") << (logy ? "set logscale y\n" : "");
    }
    void endMulti() { gp << "unset multiplot\n"; }
    std::string dat(const std::string& name) const { return "'" + (fs::path(dataDir) / name).string() + "'"; }
    std::string image(const std::string& file, const std::string& alt) const {
        return "![" + alt + "](" + imageRel + "/" + file + ")\n";
    }
};

// ---- 1 ----
void reportPlies(Report& rep, const json& j, const json& defaults) {
    const json& rows = j["rows"];
    std::ostringstream d;
    d << "# samples_per_turn ns_per_yarn_vertex straight_dev circle_dev ply_vertices_per_yarn_vertex\n";
    for (const json& r : rows)
        d << r["samples_per_turn"] << " " << r["ns_per_yarn_vertex"] << " " << r["straight_max_dev_R"] << " "
          << r["circle_max_dev_R"] << " " << r["ply_vertices_per_yarn_vertex"] << "\n";
    rep.data("plies.dat", d.str());
    const std::vector<double> cost = column(rows, "ply_vertices_per_yarn_vertex"), err = column(rows, "max_dev_R");
    const Knee kn = kneedle(cost, err);
    size_t first = kn.index, last = first;
    // Settings that produce the identical output (the resampler splits each input segment into
    // a whole number of pieces) form one point; the default takes the largest of them.
    while (last + 1 < rows.size() && cost[last + 1] == cost[first] && err[last + 1] == err[first]) ++last;
    const json& k = rows[last];
    const int knee = k["samples_per_turn"], def = defaults["samples_per_turn"];
    size_t next = last + 1;
    while (next < rows.size() && cost[next] == cost[last]) ++next;
    rep.data("plies_knee.dat", std::to_string(k["ns_per_yarn_vertex"].get<double>()) + " " +
                                   std::to_string(k["max_dev_R"].get<double>()) + " " +
                                   std::to_string(k["ply_vertices_per_yarn_vertex"].get<double>()) + "\n");
    rep.multiHeader("samples-per-turn.svg", "Ply resampling density: deviation from the exact helix against vertex count and time (labels: samples per turn)");
    for (int panel = 0; panel < 2; ++panel) {
        const std::string x = panel == 0 ? "5" : "2", kx = panel == 0 ? "3" : "1";
        rep.panel(panel == 0 ? "ply vertices per yarn vertex" : "makePlies time per yarn vertex (ns, best of runs)",
                  "max deviation of the ply polyline (yarn radii)", false, true);
        rep.gp << "plot " << rep.dat("plies.dat") << " using " << x << ":3 with linespoints pt 7 title 'straight yarn', \\\n  "
               << rep.dat("plies.dat") << " using " << x << ":4 with linespoints pt 5 title 'circular yarn', \\\n  "
               << rep.dat("plies.dat") << " using " << x << ":(($3>$4?$3:$4)):1 with labels offset 1.5,0.7 notitle, \\\n  "
               << rep.dat("plies_knee.dat") << " using " << kx << ":2 with points pt 6 ps 3 lw 2 lc rgb 'red' title 'knee'\n";
    }
    rep.endMulti();

    std::ostringstream& md = rep.md;
    md << "## 1. Ply resampling density (`PlyOptions::samplesPerTurn`, `--samples-per-turn`)\n\n"
       << "**Error**: the largest distance from the ply polylines to the exact ply helices, measured at every "
          "vertex and at 7 points inside every segment (so the chord sag between vertices counts); each point's "
          "distance to the analytic helix is found by a golden-section search along the helix. Two yarns whose "
          "plies are known exactly: a straight yarn (12 ply turns) and a circular loop of radius "
       << fixed(j["circle_radius_in_R"], 2) << " R (" << j["circle_turns"].get<double>() << " ply turns around it; as tight as "
          "the mapped stockinette's tight bends, whose radius (5% quantile of the circumradius of three consecutive "
          "yarn vertices) is " << fixed(j["tight_bend_radius_in_R"], 2) << " R, rounded to whole turns), each given at "
          "the vertex spacings the pipeline's own mapped stockinette has (the 5, 25, 50, 75 and 95% quantiles "
          "of its yarn segment lengths: ";
    for (size_t i = 0; i < j["input_spacings_in_R"].size(); ++i)
        md << (i ? ", " : "") << fixed(j["input_spacings_in_R"][i], 2);
    md << " R); the worst over these spacings is reported, because the resampler splits every input segment into "
          "a whole number of pieces and the error of one setting depends on the spacing. So the centripetal "
          "Catmull-Rom resampling, the rotation-minimizing frames and the helix sweep all contribute. "
       << j["plies"].get<int>() << " plies, pitch " << fmt(j["pitch_in_R"]) << " R, ply centre radius "
       << fmt(j["center_radius_in_R"]) << " R (R = yarn radius, the library defaults).\n\n"
       << "**Speed**: `knit::makePlies` on the stockinette mapped onto the drape ("
       << j["speed_scene"]["yarn_vertices"].get<size_t>() << " yarn vertices, "
       << j["speed_scene"]["yarns"].get<size_t>() << " yarns), best of the runs.\n\n"
       << "| samples/turn | ply points per turn (speed scene) | max dev. straight (R) | max dev. circle (R) | ply vertices | ply vertices per yarn vertex | makePlies (s) | ply vertices/s | ns per yarn vertex |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (size_t i = 0; i < rows.size(); ++i) {
        const json& r = rows[i];
        const int v = r["samples_per_turn"];
        md << "| " << v << marks(i >= first && i <= last, v == def) << " | "
           << fixed(r["ply_points_per_turn"], 1) << " | " << fmt(r["straight_max_dev_R"]) << " | "
           << fmt(r["circle_max_dev_R"]) << " | " << r["ply_vertices"].get<size_t>() << " | "
           << fixed(r["ply_vertices_per_yarn_vertex"], 2) << " | " << fmt(r["seconds"]["best"]) << " | "
           << fmt(r["ply_vertices_per_second"].get<double>() / 1e6) << " M | " << fixed(r["ns_per_yarn_vertex"], 0) << " |\n";
    }
    md << "\n" << rep.image("samples-per-turn.svg", "samples per turn: speed against error") << "\n";
    md << "**Knee** (Kneedle: max deviation against ply vertices per yarn vertex, both normalised over the measured "
          "range; the vertex count is the deterministic cost that makePlies time, memory, export size and render "
          "memory all scale with): **" << knee << " samples per turn**";
    if (first != last)
        md << " (" << rows[first]["samples_per_turn"] << ".." << knee
           << " give identical plies at this input spacing, because the resampler splits each input segment into a "
              "whole number of pieces; the default takes the largest, which guarantees at least " << knee
           << " samples per turn for any input spacing)";
    md << ": max deviation " << fmt(k["max_dev_R"]) << " R at " << fixed(k["ply_vertices_per_yarn_vertex"], 2)
       << " ply vertices per yarn vertex. Kneedle scores (distance below the chord, normalised):";
    for (size_t i = 0; i < rows.size(); ++i)
        md << (i ? ", " : " ") << rows[i]["samples_per_turn"] << ": " << fixed(kn.score[i], 3);
    md << ".";
    if (next < rows.size())
        md << " The next denser setting (" << rows[next]["samples_per_turn"] << ") costs "
           << fixed(cost[next] / cost[last], 2) << "x the vertices for " << fixed(err[last] / err[next], 2)
           << "x less deviation; the next coarser one";
    if (first > 0) {
        size_t prev = first - 1;
        md << " (" << rows[prev]["samples_per_turn"] << ") saves " << fixed(100 * (1 - cost[prev] / cost[last]), 0)
           << "% of the vertices but deviates " << fixed(err[prev] / err[last], 2) << "x more.";
    }
    md << " The straight yarn's deviation keeps falling like the square of the ply segment length; the circular "
          "loop's levels off at " << fmt(rows.back()["circle_max_dev_R"]) << " R: that part is the Catmull-Rom "
          "interpolation of a tight bend given by few input vertices, which no samples-per-turn setting removes.";
    if (std::isfinite(rep.budgetR))
        md << " At the knee the deviation is " << fixed(k["max_dev_R"].get<double>() / rep.budgetR, 2)
           << " times the faceting error of the default " << rep.budgetSides << "-sided ply tube (" << fmt(rep.budgetR)
           << " R, item 2).";
    md << (knee == def ? " The library default `PlyOptions::samplesPerTurn` is " + std::to_string(def) + ", at the knee."
                       : " The library default `PlyOptions::samplesPerTurn` is " + std::to_string(def) +
                             ": **not at the knee of this run**.")
       << "\n\n";
    rep.summary.push_back({{"setting", "`PlyOptions::samplesPerTurn`"},
                           {"rule", "Kneedle knee (cheapest within 1% of the best score)"},
                           {"knee", knee},
                           {"default", def},
                           {"error", fmt(k["max_dev_R"]) + " R max deviation from the exact helix"}});
}

// ---- 2 ----
void reportTubes(Report& rep, const json& j, const json& defaults) {
    const json& rows = j["rows"];
    const double toR = j["ply_radius_in_yarn_radii"];
    std::ostringstream d;
    d << "# sides export_seconds cylinder_r torus_r MB triangles\n";
    for (const json& r : rows)
        d << r["sides"] << " " << r["export_seconds"]["best"] << " " << r["cylinder_hausdorff_r"] << " "
          << r["torus_hausdorff_r"] << " " << r["bytes"].get<double>() / 1e6 << " " << r["triangles"] << "\n";
    rep.data("tubes.dat", d.str());
    const std::vector<double> cost = column(rows, "triangles"), err = column(rows, "hausdorff_r");
    const Knee kn = kneedle(cost, err);
    const json& k = rows[kn.index];
    const int knee = k["sides"], def = defaults["export_sides"];
    rep.data("tubes_knee.dat", std::to_string(k["export_seconds"]["best"].get<double>()) + " " +
                                   std::to_string(k["hausdorff_r"].get<double>()) + " " +
                                   std::to_string(k["triangles"].get<double>() / 1e6) + "\n");
    rep.multiHeader("tube-sides.svg", "Tube sides: Hausdorff distance to the exact tube against triangles and GLB export time (labels: sides)");
    for (int panel = 0; panel < 2; ++panel) {
        const std::string x = panel == 0 ? "($6/1e6)" : "2", kx = panel == 0 ? "3" : "1";
        rep.panel(panel == 0 ? "triangles of the test scene's ply tubes (millions; GLB size is proportional)"
                             : "GLB tube export of the test scene (s, best of runs)",
                  "Hausdorff distance (ply radii)", false, true);
        rep.gp << "plot " << rep.dat("tubes.dat") << " using " << x << ":3 with linespoints pt 7 title 'cylinder (straight ply)', \\\n  "
               << rep.dat("tubes.dat") << " using " << x << ":4 with linespoints pt 5 title 'torus (bent ply)', \\\n  "
               << rep.dat("tubes.dat") << " using " << x << ":(($3>$4?$3:$4)):1 with labels offset 1.5,0.7 notitle, \\\n  "
               << rep.dat("tubes_knee.dat") << " using " << kx << ":2 with points pt 6 ps 3 lw 2 lc rgb 'red' title 'knee'\n";
    }
    rep.endMulti();
    const json& s = j["scene"];
    std::ostringstream& md = rep.md;
    md << "## 2. Tube sides (`TubeOptions::sides`, `ExportOptions::sides`, `--sides`)\n\n"
       << "**Error**: the symmetric Hausdorff distance between the swept tube (`knit::sweepTubes`) and the exact "
          "swept surface, measured against the analytic surface (not against a finer mesh): a straight ply gives an "
          "exact cylinder (16 ply radii long, sampled at the default ply spacing of "
       << fixed(j["cylinder_step_in_r"], 2) << " r), a circular ply of radius " << fmt(j["torus_rc_in_r"])
       << " r (the curvature radius of a default ply helix; 360 samples, chord error "
       << fmt(j["torus_rc_in_r"].get<double>() * (1 - std::cos(kPi / 360)), 2) << " r) gives an exact "
          "torus. Mesh to surface: 45 points per triangle, analytic distance. Surface to mesh: a grid on the exact "
          "surface (257 x 720 and 1440 x 360 points), distance to the triangles with CGAL's AABB tree "
          "(`CGAL::AABB_tree`, closest point). r = ply radius = " << fmt(toR) << " R.\n\n"
       << "**Cost**: `knit::exportScene` of the ply tubes to GLB (sweep + write) of the stockinette at its physical "
          "size on a 0.2 m drape (" << s["cells"].get<size_t>() << " cells, " << s["ply_vertices"].get<size_t>()
       << " ply vertices, yarn radius " << fmt(s["yarn_radius_m"].get<double>() * 1e3)
       << " mm), best of the runs; triangles, tube vertices and file size of that export.\n\n"
       << "| sides | Hausdorff cylinder (r) | Hausdorff torus (r) | max (R) | triangles | tube vertices | triangles per ply vertex | GLB (MB) | export (s) |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const json& r : rows)
        md << "| " << r["sides"] << marks(r["sides"].get<int>() == knee, r["sides"].get<int>() == def)
           << " | " << fmt(r["cylinder_hausdorff_r"]) << " | " << fmt(r["torus_hausdorff_r"]) << " | "
           << fmt(r["hausdorff_R"]) << " | " << r["triangles"].get<size_t>() << " | " << r["vertices"].get<size_t>()
           << " | " << fixed(r["triangles_per_ply_vertex"], 1) << " | " << mb(r["bytes"]) << " | "
           << fmt(r["export_seconds"]["best"]) << " |\n";
    md << "\n" << rep.image("tube-sides.svg", "tube sides: speed against error") << "\n"
       << "**Knee** (Kneedle on Hausdorff distance against triangle count over the measured 4..16 sides, the "
          "cheapest setting scoring within 1% of the best): **" << knee << " sides**, " << fmt(k["hausdorff_r"])
       << " ply radii (" << fmt(k["hausdorff_R"]) << " yarn radii). Kneedle scores:";
    for (size_t i = 0; i < rows.size(); ++i) md << (i ? ", " : " ") << rows[i]["sides"] << ": " << fixed(kn.score[i], 3);
    md << ". "
       << "The faceting error falls like 1 - cos(pi/sides) (the measured values match it) while triangles, vertices, "
          "bytes and export time grow linearly with the sides; both directions of the Hausdorff distance agree (the "
          "rings lie on the surface, the largest gap is at the face centres). ";
    md << (knee == def ? "The library defaults (`TubeOptions::sides`, `ExportOptions::sides`, `RenderOptions::tubeSides`) are " +
                             std::to_string(def) + ", at the knee."
                       : "The library default (`ExportOptions::sides`) is " + std::to_string(def) +
                             ": **not at the knee of this run**.")
       << " This faceting error of the default tube is the error budget the other settings are held to below.\n\n";
    rep.summary.push_back({{"setting", "`TubeOptions::sides`, `ExportOptions::sides`"},
                           {"rule", "Kneedle knee (cheapest within 1% of the best score)"},
                           {"knee", knee},
                           {"default", def},
                           {"error", fmt(k["hausdorff_r"]) + " r = " + fmt(k["hausdorff_R"]) + " R Hausdorff to the exact tube"}});
}

// ---- 3 ----
void reportDraco(Report& rep, const json& j, const json& defaults) {
    const json& rows = j["rows"];
    std::ostringstream d;
    d << "# bits MB max_error_R bound_R decode_s export_s\n";
    for (const json& r : rows)
        d << r["bits"] << " " << r["bytes"].get<double>() / 1e6 << " " << r["max_error_R"] << " " << r["bound_R"] << " "
          << r["decode_seconds"] << " " << r["export_seconds"]["best"] << "\n";
    rep.data("draco.dat", d.str());
    const bool haveBudget = std::isfinite(rep.budgetR);
    const double tolerance = haveBudget ? 0.5 * rep.budgetR : 0.02;
    double perStep = 0;  // measured error in quantization steps (the worst over the settings)
    for (const json& r : rows) perStep = std::max(perStep, r["max_error_R"].get<double>() / r["step_R"].get<double>());
    const double extent = rows[0]["max_chunk_extent_R"];
    int hereBits = -1;
    for (const json& r : rows)
        if (hereBits < 0 && r["max_error_R"].get<double>() <= tolerance) hereBits = r["bits"];
    auto bitsFor = [&](double extentR) { return int(std::ceil(std::log2(perStep * extentR / tolerance + 1.0))); };
    const double refExtent = 1000.0;
    const int chosen = bitsFor(refExtent), def = defaults["draco_bits"];
    rep.multiHeader("draco-bits.svg", "Draco position bits: max position error against file size and time (labels: bits)");
    rep.panel("GLB size with KHR\\\\_draco\\\\_mesh\\\\_compression (MB)", "max position error (yarn radii)", false, true,
              "top right");
    rep.gp << "plot " << rep.dat("draco.dat") << " using 2:3 with linespoints pt 7 title 'measured (decoded file)', \\\n  "
           << rep.dat("draco.dat") << " using 2:4 with lines dt 2 title 'bound: half a step per axis', \\\n  "
           << rep.dat("draco.dat") << " using 2:3:1 with labels offset 1.5,0.7 notitle, \\\n  " << tolerance
           << " with lines lc rgb 'red' dt 3 title 'tolerance: half the default tube faceting'\n";
    rep.panel("seconds (best of runs)", "max position error (yarn radii)", false, true, "top center");
    rep.gp << "plot " << rep.dat("draco.dat") << " using 6:3 with linespoints pt 7 title 'exportScene (sweep + encode + write)', \\\n  "
           << rep.dat("draco.dat") << " using 5:3 with linespoints pt 5 title 'decode all primitives', \\\n  "
           << rep.dat("draco.dat") << " using 6:3:1 with labels offset 1.5,0.7 notitle\n";
    rep.endMulti();
    const json& s = j["scene"];
    std::ostringstream& md = rep.md;
    md << "## 3. Draco position quantization (`ExportOptions::dracoBits`, `--draco-bits`)\n\n"
       << "**Error**: the ply tubes (" << j["sides"] << " sides, " << j["tube_vertices"].get<size_t>()
       << " tube vertices) of the stockinette at its physical size on a 0.1 m drape (yarn radius "
       << fmt(s["yarn_radius_m"].get<double>() * 1e3) << " mm) are written once as plain float32 GLB and once per "
          "setting with `--draco`. Both files are read back; every Draco primitive is decoded with the Draco decoder "
          "(`draco::Decoder`), node translations are applied, and each decoded vertex (every n-th, about 200k) is "
          "matched to its original (the nearest plain vertex whose normal agrees within 0.05). Reported: the largest "
          "distance in yarn radii, next to the bound of half a quantization step per axis. Draco quantizes each chunk "
          "over its largest axis extent (here up to " << fixed(extent, 0)
       << " R), so the error scales with the chunk extent measured in yarn radii.\n\n"
       << "**Cost**: file size (plain GLB: " << mb(j["plain_bytes"]) << " MB), `exportScene` time (sweep + encode + "
          "write; the plain export took " << fmt(j["plain_export_seconds"]) << " s) and the time to decode every "
          "primitive of the written file.\n\n"
       << "| bits | max error (R) | bound (R) | GLB (MB) | plain / Draco size | export (s) | decode (s) | decode (M vertices/s) | vertices checked | unmatched |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const json& r : rows)
        md << "| " << r["bits"] << marks(r["bits"].get<int>() == chosen, r["bits"].get<int>() == def) << " | " << fmt(r["max_error_R"])
           << " | " << fmt(r["bound_R"]) << " | " << mb(r["bytes"]) << " | " << fixed(r["ratio_vs_plain"], 1) << " | "
           << fmt(r["export_seconds"]["best"]) << " | " << fmt(r["decode_seconds"]) << " | "
           << fixed(r["decoded_vertices"].get<double>() / r["decode_seconds"].get<double>() / 1e6, 2) << " | "
           << r["checked_vertices"].get<size_t>() << " | " << r["unmatched_vertices"].get<size_t>() << " |\n";
    md << "\n" << rep.image("draco-bits.svg", "Draco bits: size against error") << "\n";
    md << "**Knee.** The error halves with every bit while the file grows by a few percent per bit (and the "
          "coarsest settings are not even smaller), so on normalised axes the curve has no knee of its own: it "
          "flattens only against the error the geometry already has. ";
    if (haveBudget)
        md << "The rule: the fewest bits whose quantization error is at most half the faceting error of the default "
           << rep.budgetSides << "-sided tube (" << fmt(rep.budgetR) << " R, item 2), i.e. tolerance " << fmt(tolerance)
           << " R; from there on more bits change the geometry's total error by less than half. ";
    else
        md << "Item 2 was not measured in this run, so the tolerance is 0.02 R. ";
    md << "For this test's chunk extent that is **"
       << (hereBits > 0 ? std::to_string(hereBits) + " bits" : std::string("more than the measured 16 bits"))
       << "**. The measured error is at most " << fixed(perStep, 2) << " quantization steps, so a chunk of extent E "
          "(in yarn radii) needs ceil(log2(" << fixed(perStep, 2) << " E / " << fmt(tolerance) << " + 1)) bits:\n\n"
       << "| chunk extent (yarn radii) | example | bits needed |\n|---:|---|---:|\n";
    const std::vector<std::pair<double, std::string>> examples = {
        {extent, "this test"},
        {500, "0.5 m garment, 1 mm yarn radius"},
        {1000, "1 m garment, 1 mm yarn radius; 0.5 m garment, 0.5 mm"},
        {2000, "1 m garment, 0.5 mm yarn radius"},
        {4000, "2 m sheet, 0.5 mm yarn radius"}};
    for (const auto& [e, what] : examples) md << "| " << fixed(e, 0) << " | " << what << " | " << bitsFor(e) << " |\n";
    const std::vector<double> exportT = column(rows, "export_seconds"), decodeT = column(rows, "decode_seconds");
    const double perBit = 100.0 * (rows.back()["bytes"].get<double>() / rows[rows.size() - 2]["bytes"].get<double>() - 1.0);
    md << "\nA chunk spans whole yarn courses, so its extent is about the garment's width. The default is chosen for "
          "garments up to " << fixed(refExtent, 0) << " yarn radii across: **" << chosen << " bits**. "
       << (chosen == def ? "The library default `ExportOptions::dracoBits` is " + std::to_string(def) + ", matching."
                         : "The library default `ExportOptions::dracoBits` is " + std::to_string(def) +
                               ": **it does not match this run**.")
       << " Larger garments or finer yarn should pass `--draco-bits` from the table; the last bit measured here added "
       << fixed(perBit, 0) << "% to the file; across all settings the export took "
       << fmt(*std::min_element(exportT.begin(), exportT.end())) << " to " << fmt(*std::max_element(exportT.begin(), exportT.end()))
       << " s and decoding " << fmt(*std::min_element(decodeT.begin(), decodeT.end())) << " to "
       << fmt(*std::max_element(decodeT.begin(), decodeT.end())) << " s.\n\n";
    rep.summary.push_back({{"setting", "`ExportOptions::dracoBits`"},
                           {"rule", "error <= half the default tube's faceting, chunks up to 1000 R"},
                           {"knee", chosen},
                           {"default", def},
                           {"error", "<= " + fmt(tolerance) + " R position error"}});
}

// ---- 4 ----
void reportBaseMesh(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const double budget = std::isfinite(rep.budgetR) ? rep.budgetR : 0.04;
    md << "## 4. Base-mesh resolution (how coarse the mesh under the knit may be)\n\n"
       << "**Error**: every bound yarn vertex has a triangle, barycentrics and a height h; its (u, v) is the "
          "barycentric blend of the triangle's UVs. The exact position is S(u, v) + h n(u, v) on the analytic surface "
          "the procedural mesh samples (cylinder: (r cos 2 pi u, r sin 2 pi u, v H); sphere: latitude-longitude; "
          "exact unit normals); the mapped position is `knit::evaluateBinding` on the mesh (vertex normals from "
          "`knit::vertexNormals`). Max and RMS of the distance over all yarn vertices, in yarn radii. The chord sag "
          "r (1 - cos(pi / resolution)) of the mesh's edges around the surface is listed for comparison.\n\n"
       << "**Speed**: `buildUvGrid` + `bindYarns` (the binding, computed once per rest mesh), best of the runs; "
          "`evaluateBinding` (once per animation frame) for reference.\n\n";
    rep.plotHeader("base-mesh.svg", "Base-mesh resolution: binding time against mapping error (labels: quads around)",
                   "UV grid + binding time (ms, best of runs)", "max mapping error (yarn radii)", true, true);
    std::string plot = "plot ";
    int series = 0;
    std::string guidance;
    for (const auto& [name, s] : j["surfaces"].items()) {
        const json& rows = s["rows"];
        const double R = s["yarn_radius_m"], radius = s["radius_m"];
        std::ostringstream dd;
        dd << "# res_u bind_ms max_error_R\n";
        for (const json& r : rows)
            dd << r["res_u"] << " " << r["bind_total_seconds"].get<double>() * 1e3 << " " << r["max_error_R"] << "\n";
        rep.data("mesh_" + name + ".dat", dd.str());
        int pick = -1;
        for (size_t i = 0; i < rows.size(); ++i)
            if (pick < 0 && rows[i]["max_error_R"].get<double>() <= budget) pick = int(i);
        plot += std::string(series ? ", \\\n  " : "") + rep.dat("mesh_" + name + ".dat") + " using 2:3 with linespoints pt " +
                std::to_string(series ? 5 : 7) + " title '" + name + "', \\\n  " + rep.dat("mesh_" + name + ".dat") +
                " using 2:3:1 with labels offset 1.5,0.7 notitle";
        ++series;
        md << "**" << name << "** (radius " << fmt(radius) << " m" << (s.contains("height_m") ? ", height " + fmt(s["height_m"]) + " m" : "")
           << ", repeats " << fmt(s["repeats"][0]) << " x " << fmt(s["repeats"][1]) << ", yarn radius "
           << fmt(R * 1e3) << " mm):\n\n"
           << "| resolution (u x v) | triangles | mesh edge (stitches) | max error (R) | RMS error (R) | chord sag (R) | grid + bind (ms) | M yarn vertices/s | evaluate (ms) |\n"
           << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (size_t i = 0; i < rows.size(); ++i) {
            const json& r = rows[i];
            const double sag = radius * (1 - std::cos(kPi / r["res_u"].get<double>())) / R;
            md << "| " << r["res_u"] << " x " << r["res_v"] << (int(i) == pick ? " (coarsest in budget)" : "") << " | "
               << r["triangles"].get<size_t>() << " | " << fixed(r["edge_in_stitches"], 2) << " | " << fmt(r["max_error_R"])
               << " | " << fmt(r["rms_error_R"]) << " | " << fmt(sag) << " | "
               << fixed(r["bind_total_seconds"].get<double>() * 1e3, 1) << " | "
               << fixed(r["yarn_vertices_per_second_bind"].get<double>() / 1e6, 1) << " | "
               << fixed(r["evaluate_seconds"]["best"].get<double>() * 1e3, 2) << " |\n";
        }
        const json& lo = rows[0];
        const json& hi = rows[rows.size() - 1];
        md << "\n";
        if (pick >= 0) {
            const json& k = rows[size_t(pick)];
            md << "Coarsest " << name << " mesh whose mapping error stays within the budget (" << fmt(budget)
               << " R, the default tube's faceting error): **" << k["res_u"] << " x " << k["res_v"] << "** (mesh edge "
               << fixed(k["edge_in_stitches"], 2) << " stitches, " << fixed(2 * kPi * radius / k["res_u"].get<double>() / R, 1)
               << " yarn radii, max error " << fmt(k["max_error_R"]) << " R, grid + bind "
               << fixed(k["bind_total_seconds"].get<double>() * 1e3, 1) << " ms). ";
            guidance += (guidance.empty() ? "" : ", ") + name + " " + std::to_string(k["res_u"].get<int>()) + " x " +
                        std::to_string(k["res_v"].get<int>());
        } else {
            md << "No measured " << name << " resolution is within the budget (" << fmt(budget) << " R). ";
        }
        md << "From " << lo["res_u"] << " to " << hi["res_u"] << " quads around, the error fell "
           << fixed(lo["max_error_R"].get<double>() / hi["max_error_R"].get<double>(), 0) << "x while grid + binding time grew "
           << fixed(hi["bind_total_seconds"].get<double>() / lo["bind_total_seconds"].get<double>(), 1) << "x.\n\n";
        rep.summary.push_back({{"setting", "base mesh resolution (" + name + ", an input)"},
                               {"rule", "coarsest mesh with error <= the default tube's faceting"},
                               {"knee", pick >= 0 ? std::to_string(rows[size_t(pick)]["res_u"].get<int>()) + " x " +
                                                        std::to_string(rows[size_t(pick)]["res_v"].get<int>())
                                                  : std::string("none measured")},
                               {"default", "-"},
                               {"error", pick >= 0 ? fmt(rows[size_t(pick)]["max_error_R"]) + " R max mapping error" : "-"}});
    }
    rep.gp << plot << "\n";
    md << rep.image("base-mesh.svg", "base mesh resolution: binding time against mapping error") << "\n"
       << "The mapping error is the mesh's chord error (it falls with the square of the edge length: on the cylinder "
          "it equals the chord sag column) plus the vertex normals' error times the height; the sphere's is larger "
          "(curved in both directions, longer diagonals, pole fans). Binding time grows only slowly with the mesh, so "
          "a finer base mesh is cheap: as a rule, an edge of length e on a surface of curvature radius rho costs "
          "about e^2 / (8 rho) of error, so keep e <= sqrt(8 rho E) for an error budget E. There is no library "
          "default to change (meshes are inputs; the built-in meshes' 32 x 32 is only a demo size).\n\n";
}

// ---- 5 ----
void reportRender(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const json& s = j["scene"];
    const int refSpp = j["reference_spp"];
    md << "## 5. Render modes (`knit render --mode curves|tubes|grid`)\n\n"
       << "The stockinette on a " << fmt(s["plane_m"].get<double>() * 100) << " cm plane ("
       << s["ply_vertices"].get<size_t>() << " ply vertices, " << s["cells"].get<size_t>() << " grid cells), "
       << j["light"].get<std::string>() << "-lit, " << j["width"] << " x " << j["height"]
       << " pixels, rendered with `knit::renderScene` at 1..64 samples per pixel (seed 1) and compared "
          "(`knit::compareImages`: luminance RMSE over pixels, here divided by the reference's mean luminance) with a "
          "reference of the same mode at " << refSpp << " spp (another seed). The reference's own noise adds "
          "sqrt(1 + spp / " << refSpp << ") to the measured RMSE (" << fixed(100 * (std::sqrt(1 + 64.0 / refSpp) - 1), 0)
       << "% at 64 spp). Memory: the mode's scene memory "
          "(Embree BVH + our intersection buffers, `TraceMemory::sceneBytes`); tubes use " << j["tube_sides"]
       << " sides.\n\n"
       << "| mode | spp | relative RMSE | render (s) | us per sample | M rays/s |\n|---|---:|---:|---:|---:|---:|\n";
    std::string plot = "plot ";
    int series = 0;
    std::ostringstream mem, pics;
    mem << "| mode | scene memory (MB) | Embree (MB) | geometry (MB) | primitives | build (s) | us per sample (spp >= 4, median) | RMSE^2 x time (lower is better) | reference vs curves reference | of which noise alone |\n"
        << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string mode : {"curves", "tubes", "grid"}) {
        if (!j["modes"].contains(mode)) continue;
        const json& m = j["modes"][mode];
        std::ostringstream dd;
        dd << "# spp render_s relative_rmse\n";
        std::vector<double> eff, us;
        for (const json& r : m["rows"]) {
            dd << r["spp"] << " " << r["render_seconds"] << " " << r["relative_rmse"] << "\n";
            md << "| " << mode << " | " << r["spp"] << " | " << fixed(100 * r["relative_rmse"].get<double>(), 2) << "% | "
               << fmt(r["render_seconds"]) << " | " << fixed(r["us_per_sample"], 2) << " | "
               << fixed(r["rays_per_second"].get<double>() / 1e6, 2) << " |\n";
            if (r["spp"].get<int>() >= 4) {
                eff.push_back(std::pow(r["relative_rmse"].get<double>(), 2) * r["render_seconds"].get<double>());
                us.push_back(r["us_per_sample"]);
            }
        }
        std::sort(eff.begin(), eff.end());
        std::sort(us.begin(), us.end());
        rep.data("render_" + mode + ".dat", dd.str());
        plot += std::string(series ? ", \\\n  " : "") + rep.dat("render_" + mode + ".dat") + " using 2:3 with linespoints pt " +
                std::to_string(5 + 2 * series) + " title '" + mode + " (scene " + mb(m["scene_bytes"]) + " MB)', \\\n  " +
                rep.dat("render_" + mode + ".dat") + " using 2:3:1 with labels offset 1.5,0.7 notitle";
        ++series;
        mem << "| " << mode << " | " << mb(m["scene_bytes"]) << " | " << mb(m["embree_bytes"]) << " | " << mb(m["geometry_bytes"])
            << " | " << m["primitives"].get<size_t>() << " | " << fmt(m["build_seconds"]) << " | "
            << (us.empty() ? std::string("-") : fixed(us[us.size() / 2], 2)) << " | "
            << (eff.empty() ? std::string("-") : fmt(eff[eff.size() / 2])) << " | "
            << (m.contains("reference_vs_curves_relative_rmse") ? fixed(100 * m["reference_vs_curves_relative_rmse"].get<double>(), 2) + "%"
                                                               : std::string("-"))
            << " | "
            << (m.contains("reference_noise_relative_rmse") ? fixed(100 * m["reference_noise_relative_rmse"].get<double>(), 2) + "%"
                                                           : std::string("-"))
            << " |\n";
        if (m.contains("reference_png"))
            pics << "| ![" << mode << " reference](" << rep.imageRel << "/" << m["reference_png"].get<std::string>() << ") ";
    }
    rep.plotHeader("render-modes.svg", "Render modes: time against image error (labels: samples per pixel)",
                   "render time of the image (s)", "RMSE / mean luminance of the reference", true, true);
    rep.gp << plot << "\n";
    md << "\n" << mem.str() << "\n" << rep.image("render-modes.svg", "render modes: time against RMSE") << "\n";
    if (!pics.str().empty()) {
        md << "References (" << refSpp << " spp):\n\n";
        for (const std::string mode : {"curves", "tubes", "grid"})
            if (j["modes"].contains(mode)) md << "| " << mode << " ";
        md << "|\n";
        for (size_t i = 0; i < j["modes"].size(); ++i) md << "|---";
        md << "|\n" << pics.str() << "|\n\n";
    }
    md << "RMSE falls like 1/sqrt(spp) in every mode (Monte Carlo noise), so the modes differ by cost per sample and "
          "memory: RMSE^2 x time (median over spp >= 4) is the inverse efficiency, lower is better. The last two "
          "columns compare the modes' references with the curves reference: the measured difference (geometry plus the "
          "references' own noise) and what the noise alone would give (the 1-spp errors scaled to the reference's spp); "
          "the excess is the geometric difference between the modes (tube faceting, the grid mode's trimmed cylinders "
          "against Embree's round curves).\n\n";
}

// ---- 6 ----
void reportGarment(Report& rep, const json& j) {
    std::ostringstream& md = rep.md;
    const double yv = j["yarn_vertices"], pv = j["ply_vertices"], total = j["total_seconds"], cpu = j["cpu_seconds"];
    const int threads = j["threads"];
    std::ostringstream dd;
    dd << "# stage wall cpu\n";
    md << "## 6. Garment scale: the whole pipeline to a plies GLB\n\n"
       << "The stockinette tiled " << j["repeats"] << " x " << j["repeats"] << " over the built-in drape ("
       << j["mesh"]["res"] << " x " << j["mesh"]["res"] << " quads, " << j["mesh"]["triangles"].get<size_t>() << " triangles, "
       << fmt(j["mesh"]["size_m"]) << " m sheet): **" << j["cells"].get<size_t>() << " pattern cells, "
       << j["yarn_vertices"].get<size_t>() << " yarn vertices, " << j["ply_vertices"].get<size_t>() << " ply vertices** ("
       << j["plies"] << " plies, " << j["samples_per_turn"] << " samples per turn, yarn radius "
       << fmt(j["yarn_radius_m"].get<double>() * 1e3, 2) << " mm). `knit::buildScene` (in-memory pattern and mesh, "
          "`buildPlies = false`), then `knit::exportScene` to a plies GLB: stage `plies_glb` generates the plies "
          "(resampling, frames, helices), converts them to float32 and writes them chunk by chunk in a TBB pipeline, "
          "without ever holding all plies (`knit build` does the same for .glb / .gltf); one non-indexed LINE_STRIP per "
          "ply curve with `_RADIUS`. One run, "
       << threads << " hardware threads. CPU = user + system time of the process during the stage (all threads).\n\n"
       << "| stage | wall (s) | share | CPU (s) | cores used | M vertices/s | ns per yarn vertex |\n|---|---:|---:|---:|---:|---:|---:|\n";
    std::vector<std::pair<double, std::string>> big;
    for (const json& s : j["stages"]) {
        const std::string name = s["stage"];
        const double t = s["seconds"], c = s["cpu_seconds"];
        const bool perPly = name == "plies_glb";
        const double items = perPly ? pv : yv;
        big.emplace_back(t, name);
        dd << "\"" << name << "\" " << t << " " << std::max(c, 0.0) << "\n";
        md << "| " << name << " | " << fixed(t, 3) << " | " << fixed(100 * t / total, 1) << "% | "
           << (c >= 0 ? fixed(c, 2) : std::string("-")) << " | " << (c >= 0 && t > 0 ? fixed(c / t, 2) : std::string("-"))
           << " | " << fixed(items / std::max(t, 1e-12) / 1e6, 1) << (perPly ? " (ply)" : " (yarn)") << " | "
           << fixed(t / yv * 1e9, 1) << " |\n";
    }
    md << "| **total** | **" << fixed(total, 2) << "** | 100% | " << fixed(cpu, 2) << " | " << fixed(cpu / total, 2) << " | "
       << fixed(yv / total / 1e6, 2) << " (yarn) | " << fixed(total / yv * 1e9, 1) << " |\n\n";
    std::sort(big.rbegin(), big.rend());
    rep.data("garment.dat", dd.str());
    rep.plotHeader("garment.svg", "Garment scale: time per stage", "", "seconds", false, false);
    rep.gp << "set termoption noenhanced\nset style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.7 border -1\n"
           << "set xtics rotate by -30\nset key top left\nplot " << rep.dat("garment.dat")
           << " using 2:xtic(1) lc rgb '#4477aa' title 'wall', '' using 3 lc rgb '#ee8866' title 'CPU (all threads)'\n";
    const double target = 5.0 * yv / 1e7;
    // Stages that kept to about one core while the process as a whole got clearly more look serial:
    // on an idle machine they cannot go below their CPU time.
    std::string serialText;
    double serialCpu = 0;
    if (cpu / total > 1.2) {
        std::string names;
        for (const json& s : j["stages"])
            if (s["seconds"].get<double>() > 0.05 * total && s["cpu_seconds"].get<double>() >= 0 &&
                s["cpu_seconds"].get<double>() < 1.1 * s["seconds"].get<double>()) {
                names += (names.empty() ? "" : ", ") + s["stage"].get<std::string>();
                serialCpu += s["cpu_seconds"].get<double>();
            }
        if (!names.empty())
            serialText = " Stages that used about one core while the process averaged " + fixed(cpu / total, 2) +
                         " look serial (" + names + ": " + fixed(serialCpu, 2) + " s of CPU that a second core does not shorten).";
    }
    const double idle = (cpu - serialCpu) / threads + serialCpu;  // lower bound of the idle-machine wall time  // lower bound of the wall time with all cores to ourselves
    md << rep.image("garment.svg", "garment scale: seconds per stage") << "\n"
       << "Peak resident memory (VmHWM" << (j["reset_peak_ok"].get<bool>() ? ", reset before the run" : ", could not be reset: includes earlier items")
       << "): **" << gib(j["peak_bytes"]) << " GiB** (" << fixed(j["peak_bytes"].get<double>() / yv, 0)
       << " bytes per yarn vertex; " << gib(j["peak_after_build_bytes"]) << " GiB after `buildScene`); GLB "
       << mb(j["glb_bytes"]) << " MB. Cost per yarn vertex: " << fixed(total / yv * 1e9, 0) << " ns wall, "
       << fixed(cpu / yv * 1e9, 0) << " ns CPU.\n\n"
       << "**Target** (<= 5 s for 10M yarn vertices to a plies GLB on 2 cores, i.e. " << fixed(target, 2) << " s for these "
       << fixed(yv / 1e6, 2) << "M): **" << (total <= target ? "met" : "not met") << "**: " << fixed(total, 2) << " s wall, "
       << fixed(total / target, 2) << "x the target. ";
    if (total <= target) {
        md << "The process used " << fixed(cpu / total, 2) << " of the " << threads << " hardware threads on average."
           << serialText << " The largest stages: " << big[0].second << " (" << fixed(100 * big[0].first / total, 0)
           << "%), " << big[1].second << " (" << fixed(100 * big[1].first / total, 0) << "%).\n\n";
    } else {
    md << "The process used " << fixed(cpu / total, 2) << " of the " << threads
       << " hardware threads on average (the machine was shared), so on an idle machine the wall time would lie between "
       << fixed(idle, 2) << " s (" << (serialCpu > 0 ? "the parallel CPU work spread over " + std::to_string(threads) + " cores, the serial stages named below on one"
                                                     : "all CPU work spread over " + std::to_string(threads) + " cores")
       << ") and the measured " << fixed(total, 2)
       << " s; " << (idle <= target ? "so this run neither shows the target met nor rules it out for an idle machine."
                                    : "even that lower bound misses the target, so it would not be met on an idle 2-core machine "
                                      "either (unless the CPU time itself shrinks there: contention also costs cache).")
       << serialText << " The largest stages: " << big[0].second << " (" << fixed(100 * big[0].first / total, 0) << "%), "
       << big[1].second << " (" << fixed(100 * big[1].first / total, 0) << "%), " << big[2].second << " ("
       << fixed(100 * big[2].first / total, 0) << "%).\n\n";
    }
    if (j.contains("materialized")) {
        const json& m = j["materialized"];
        md << "For comparison, the same plies held in memory (`buildPlies = true`: what OBJ, PLY, BCC, pbrt and tube "
              "exports need) cost " << fixed(m["plies_seconds"].get<double>(), 2) << " s for `makePlies` plus "
           << fixed(m["export_seconds"].get<double>(), 2) << " s for the GLB of them (" << fixed(m["cpu_seconds"].get<double>(), 2)
           << " s CPU) with a peak of " << gib(m["peak_bytes"]) << " GiB"
           << (m["reset_peak_ok"].get<bool>() ? "" : " (peak not reset: includes the streamed run)")
           << ", on top of the stages before the plies: streaming saves "
           << fixed(m["seconds"].get<double>() - j["stages"].back()["seconds"].get<double>(), 2) << " s and "
           << gib(m["peak_bytes"].get<double>() - j["peak_bytes"].get<double>()) << " GiB here.\n\n";
    }
    rep.summary.push_back({{"setting", "garment: " + fixed(yv / 1e6, 1) + "M yarn vertices to a plies GLB"},
                           {"rule", "target <= 5 s per 10M yarn vertices on 2 cores"},
                           {"knee", "-"},
                           {"default", "-"},
                           {"error", fixed(total, 1) + " s wall, " + gib(j["peak_bytes"]) + " GiB peak: target " +
                                         (total <= target ? "met" : "not met")}});
}

}  // namespace

int writeReport(const std::string& resultsPath, const std::string& markdownPath, const std::string& imageDir,
                const std::string& dataDir) {
    std::ifstream in(resultsPath);
    if (!in) throw knit::Error("cannot read " + resultsPath);
    const json r = json::parse(in);
    fs::create_directories(imageDir);
    fs::create_directories(dataDir);
    Report rep;
    rep.dataDir = fs::absolute(dataDir).string();
    rep.imageDir = fs::absolute(imageDir).string();
    rep.imageRel = fs::relative(fs::absolute(imageDir), fs::absolute(markdownPath).parent_path()).generic_string();
    const json& meta = r["meta"];
    const json& defaults = r["defaults"];
    const int hw = r["machine"]["hardware_threads"];
    double maxLoad = 0;
    for (const auto& [key, v] : r.items())
        if (key.rfind("item", 0) == 0)
            for (const char* f : {"load_before", "load_after"}) maxLoad = std::max(maxLoad, v[f][0].get<double>());
    auto measured = [&](const char* key) { return r.contains(key) && !r[key].contains("skipped"); };
    if (measured("item2")) {
        rep.budgetSides = defaults["export_sides"];
        for (const json& row : r["item2"]["rows"])
            if (row["sides"].get<int>() == rep.budgetSides) rep.budgetR = row["hausdorff_R"];
    }

    std::ostringstream body;
    std::swap(body, rep.md);
    if (measured("item1")) reportPlies(rep, r["item1"], defaults);
    if (measured("item2")) reportTubes(rep, r["item2"], defaults);
    if (measured("item3")) reportDraco(rep, r["item3"], defaults);
    if (measured("item4")) reportBaseMesh(rep, r["item4"]);
    if (measured("item5")) reportRender(rep, r["item5"]);
    if (measured("item6")) reportGarment(rep, r["item6"]);
    std::swap(body, rep.md);

    std::ostringstream& md = rep.md;
    md << "# Speed against error: choosing libknit's settings\n\n"
       << "Generated by `" << meta["command"].get<std::string>() << "` (program: `bench/speed_vs_error_bench.cpp`). "
          "Every number, table and plot below comes from that one run; the raw results are in ["
       << rep.imageRel << "/results.json](" << rep.imageRel << "/results.json). Rerun the command to measure your "
          "machine.\n\n"
       << "| | |\n|---|---|\n"
       << "| date | " << meta["date"].get<std::string>() << " |\n"
       << "| commit | `" << meta["commit"].get<std::string>() << "`"
       << (meta["dirty"] == "1" ? " + uncommitted changes (dirty tree)" : meta["dirty"] == "0" ? " (clean tree)" : "") << " |\n"
       << "| CPU | " << r["machine"]["cpu"].get<std::string>() << " |\n"
       << "| nproc / hardware threads | " << meta.value("nproc", std::string("?")) << " / " << hw << " |\n"
       << "| memory | " << gib(r["machine"]["memory_bytes"]) << " GiB |\n"
       << "| build | Release, all cores through TBB |\n"
       << "| measurement time | " << fixed(r["measure_seconds"], 0) << " s (items in the order " << meta.value("items", std::string("?")) << ") |\n"
       << "| load average (1 / 5 / 15 min) at start, end | " << loadText(r["load_start"]) << "; " << loadText(r["load_end"]) << " |\n\n";
    if (maxLoad > 0.75 * hw)
        md << "**The machine was loaded** during the run (1-minute load average up to " << fixed(maxLoad, 1) << " on " << hw
           << " hardware threads: other engineers were compiling and testing on it). Timings are best-of-N wall-clock "
              "times and still pessimistic; errors, vertex counts and sizes do not depend on the load.\n\n";
    md << "## Summary: defaults at the knee\n\n"
       << "| setting | rule | value in this run | library default | error there |\n|---|---|---:|---:|---|\n";
    for (const json& s : rep.summary)
        md << "| " << str(s["setting"]) << " | " << str(s["rule"]) << " | " << str(s["knee"]) << " | " << str(s["default"])
           << " | " << str(s["error"]) << " |\n";
    md << "\nR = yarn radius, r = ply radius. Timings are wall clock, best of the runs recorded in results.json (with "
          "the load average before and after each item).\n\n";
    for (char item = '1'; item <= '6'; ++item) {
        const std::string key = std::string("item") + item;
        if (!r.contains(key))
            md << "**Item " << item << " was not measured in this run: no numbers are reported for it.**\n\n";
        else if (r[key].contains("skipped"))
            md << "**Item " << item << " was not measured in this run (" << r[key]["skipped"].get<std::string>()
               << "): no numbers are reported for it.**\n\n";
    }
    md << body.str();
    writeAtomically(markdownPath, md.str());
    writeAtomically((fs::path(dataDir) / "plots.gp").string(), rep.gp.str());
    return 0;
}
