// item_plies.cpp — item 1: ply resampling density (PlyOptions::samplesPerTurn). The ply polylines
// of yarns whose exact plies are known in closed form (a straight yarn, a circular loop), given at
// the vertex spacings the pipeline's own mapped stockinette has, against the exact helices; speed
// of makePlies on the mapped stockinette.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "items.hpp"
#include "knit/plies.hpp"

namespace sve {
namespace {

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
                const double d2 = goldenMin(
                    [&](double t) {
                        const dvec3 e = q - yarn.ply(o, ply, t);
                        return glm::dot(e, e);
                    },
                    t0 - w, t0 + w);
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

}  // namespace

json measurePlies() {
    json out;
    const double R = 0.001;  // yarn radius (metres); errors are reported in R
    knit::PlyOptions base;
    base.yarnRadius = R;
    const knit::PlyOptions resolved = knit::resolvePlyOptions(base);
    const double pitch = resolved.pitch;
    // Input vertex spacings of the pattern's yarns: quantiles of the segment lengths of the
    // pipeline's mapped yarns, so the analytic yarns are resampled from the densities real ones
    // have (the resampler splits each input segment into a whole number of pieces, so the error
    // of one setting depends on the input spacing: the reported error is the worst over these).
    const knit::Scene speed = knitScene(64, 0.5, {70, 70}, false);
    const knit::Polylines& speedYarns = speed.yarns().curves;
    std::vector<double> seg;
    for (size_t c = 0; c < speedYarns.curveCount(); ++c)
        for (uint32_t s = 0; s + 1 < speedYarns.size(c); ++s)
            seg.push_back(glm::distance(speedYarns.points[speedYarns.begin(c) + s],
                                        speedYarns.points[speedYarns.begin(c) + s + 1]) /
                          speed.yarnRadius());
    std::sort(seg.begin(), seg.end());
    // Tightest bends of the real yarns: circumradius of consecutive vertex triples (5% quantile).
    std::vector<double> bend;
    for (size_t c = 0; c < speedYarns.curveCount(); ++c)
        for (uint32_t s = 0; s + 2 < speedYarns.size(c); ++s) {
            const dvec3* p = speedYarns.points.data() + speedYarns.begin(c) + s;
            const double a = glm::distance(p[0], p[1]), b = glm::distance(p[1], p[2]), d = glm::distance(p[0], p[2]);
            const double area2 = glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
            if (area2 > 0) bend.push_back(a * b * d / (2 * area2) / speed.yarnRadius());
        }
    std::sort(bend.begin(), bend.end());
    const std::vector<double> quantiles = {0.05, 0.25, 0.5, 0.75, 0.95};
    std::vector<double> spacings;  // in R
    spacings.reserve(quantiles.size());
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
    for (size_t c = 0; c < speedYarns.curveCount(); ++c) {
        const uint32_t b = speedYarns.begin(c), n = speedYarns.size(c);
        for (uint32_t s = 0; s < speedYarns.segmentCount(c); ++s)
            speedLength += glm::distance(speedYarns.points[b + s], speedYarns.points[b + (s + 1) % n]);
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
    out["speed_scene"] = {{"yarn_vertices", speedYarns.pointCount()},
                          {"yarns", speedYarns.curveCount()},
                          {"cells", speed.grid().cells.size()}};
    for (int k : {4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 48, 64}) {
        knit::PlyOptions o = base;
        o.samplesPerTurn = k;
        const knit::PlyOptions ro = knit::resolvePlyOptions(o);
        PlyDeviation ds, dc;
        json perSpacing = json::array();
        for (size_t i = 0; i < spacings.size(); ++i) {
            const PlyDeviation a = plyDeviation(knit::makePlies(straightYarns[i], o), straight, ro);
            const PlyDeviation b = plyDeviation(knit::makePlies(circleYarns[i], o), circle, ro);
            perSpacing.push_back(
                {{"spacing_R", spacings[i]}, {"straight_R", a.maxDistance / R}, {"circle_R", b.maxDistance / R}});
            ds.maxDistance = std::max(ds.maxDistance, a.maxDistance);
            dc.maxDistance = std::max(dc.maxDistance, b.maxDistance);
        }
        knit::PlyOptions so = o;
        so.yarnRadius = speed.yarnRadius();
        size_t plyVertices = 0;
        const Timing t = timeRuns(
            [&] {
                const knit::Plies p = knit::makePlies(speed.yarns(), so);
                plyVertices = p.curves.pointCount();
            },
            3, 15, 1.0);
        const double yarnVertices = double(speedYarns.pointCount());
        json row;
        row["samples_per_turn"] = k;
        row["straight_max_dev_R"] = ds.maxDistance / R;
        row["circle_max_dev_R"] = dc.maxDistance / R;
        row["max_dev_R"] = std::max(ds.maxDistance, dc.maxDistance) / R;
        row["per_spacing"] = perSpacing;
        row["ply_points_per_turn"] =
            double(plyVertices) / ro.count / (speedLength / (ro.pitch / R * speed.yarnRadius()));
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

}  // namespace sve
