// item_tube_sides.cpp — item 2: tube sides (TubeOptions::sides, ExportOptions::sides). The swept
// tube of a straight ply (an exact cylinder) and of a bent one (an exact torus) against the
// analytic surface, symmetric Hausdorff distance; cost of the GLB tube export of a test scene.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "items.hpp"
#include "knit/export.hpp"
#include "knit/plies.hpp"
#include "knit/sweep.hpp"

namespace sve {
namespace {

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
            h.surfaceToMesh =
                std::max(h.surfaceToMesh, std::sqrt(tree.squared_distance(CgalK::Point_3(p.x, p.y, p.z))));
        }
    return h;
}

}  // namespace

json measureTubeSides(const knit::Scene& scene, const std::string& work) {
    json out;
    const double r = 1.0;  // ply radius (errors are reported in ply radii and yarn radii)
    const double plyToYarn = scene.plies().plyRadius / scene.yarnRadius();
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
    std::vector<dvec3> cylSeed(cylCurve.pointCount(), dvec3(0, 0, 1)),
        torusSeed(torusCurve.pointCount(), dvec3(0, 0, 1));
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
        const Timing t =
            timeRunsWithSetup([&] { fs::remove(path); }, [&] { es = knit::exportScene(scene, eo); }, 3, 10, 1.5);
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
        row["triangles_per_ply_vertex"] = double(es.triangles) / double(scene.plies().curves.pointCount());
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

}  // namespace sve
