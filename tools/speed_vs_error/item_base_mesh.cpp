// item_base_mesh.cpp — item 4: base-mesh resolution. The stockinette bound to procedural cylinders
// and spheres of increasing resolution, every mapped yarn vertex against the exact point above
// the analytic surface; speed of the UV grid, the binding and its evaluation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "items.hpp"
#include "knit/base_mesh.hpp"
#include "knit/binding.hpp"
#include "knit/generator.hpp"
#include "knit/stitch.hpp"
#include "knit/tiling.hpp"
#include "knit/uv_grid.hpp"

namespace sve {
namespace {

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

}  // namespace

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
            const Timing tv = timeRuns(
                [&] { knit::evaluateBinding(bound.binding, mesh.faces, mesh.positions, normals, mapped); }, 3, 7, 0.3);
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

}  // namespace sve
