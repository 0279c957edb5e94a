// python/src/pattern_mesh.cpp — knit.Pattern and knit.Mesh: loading them (file or built-in name)
// and making a mesh from numpy arrays.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "knit/base_mesh.hpp"
#include "knit/chart.hpp"
#include "knit/chart_cache.hpp"
#include "knit/chart_topology.hpp"
#include "knit/chart_warnings.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"

namespace knitpy {

namespace {

using namespace pybind11::literals;

// A mesh from arrays: positions (n, 3), faces (m, 3); UVs (k, 2) with face_uvs (m, 3), or
// per-vertex UVs (n, 2) when face_uvs is None. Checked by validateMesh.
knit::BaseMesh meshFromArrays(const py::array& positions, const py::array& faces, const py::object& uvs,
                              const py::object& faceUvs, const std::string& name) {
    knit::BaseMesh mesh;
    mesh.name = name;
    mesh.positions = toVec3(positions, "positions");
    mesh.faces = toUvec3(faces, "faces");
    if (!uvs.is_none()) mesh.uvs = toVec2(uvs.cast<py::array>(), "uvs");
    if (!faceUvs.is_none()) mesh.faceUvs = toUvec3(faceUvs.cast<py::array>(), "face_uvs");
    else if (!uvs.is_none()) mesh.faceUvs = mesh.faces;  // per-vertex UVs
    knit::validateMesh(mesh);
    return mesh;
}

// Chart text (the format of docs/charts.md) to a relaxed pattern, through the chart cache.
knit::Pattern chartPattern(const std::string& text, const std::string& name, double yarnRadius) {
    if (!(yarnRadius > 0) || !std::isfinite(yarnRadius)) throw knit::Error("yarn_radius must be positive");
    knit::ChartPatternOptions options;
    options.radius = yarnRadius;
    return knit::cachedChartPattern(text, name, options);
}

// The floats of a chart (stranded colourwork, slipped stitches): one dict each, in the
// knitter's numbering (row 1 = the bottom row, column 1 = the leftmost), as `knit chart --report`.
py::list chartFloats(const std::string& text, const std::string& name, int maxFloat) {
    if (maxFloat < 1) throw knit::Error("max_float must be at least 1");
    const knit::Chart chart = knit::parseChart(text, name);
    const knit::ChartCell cell = knit::chartToCell(chart);
    py::list out;
    for (const knit::ChartFloat& f : cell.floats) {
        py::dict d;
        d["row"] = f.row + 1;
        d["line"] = chart.rowLine[size_t(f.row)];
        d["columns"] = py::make_tuple(f.firstColumn + 1, (f.firstColumn + f.columns - 1) % chart.width + 1);
        d["stitches"] = f.columns;
        d["colour"] = f.colour ? std::string(1, f.colour) : std::string();
        d["side"] = f.front ? "front" : "back";
        d["carried"] = f.carried;
        d["too_long"] = f.columns > maxFloat;
        out.append(d);
    }
    return out;
}

// The chart's warnings (knit/chart_warnings.hpp: floats longer than maxFloat, rows stacked) as
// `knit chart` prints them, "NAME:LINE: ..." with this module's keywords; the package's
// chart_pattern and load_pattern warn with each (knit.ChartWarning).
std::vector<std::string> chartWarnings(const std::string& text, const std::string& name, int maxFloat, bool keywords) {
    if (maxFloat < 1) throw knit::Error("max_float must be at least 1");
    const knit::Chart chart = knit::parseChart(text, name);
    std::vector<std::string> out;
    for (const knit::ChartWarning& w : knit::chartWarnings(chart, knit::chartToCell(chart), maxFloat))
        // This module's keyword after the float limit ("(max_float)"), or the library's words alone
        // for a front end with its own spelling (the Blender add-on, as knit.Error.words).
        out.push_back(keywords ? withKeywords(knit::chartWarningMessage(chart, w))
                               : knit::chartWarningMessage(chart, w));
    return out;
}

void registerChart(py::module_& m) {
    m.def("chart_pattern", &chartPattern, "text"_a, "name"_a = "<chart text>", "yarn_radius"_a = 0.001,
          "A stitch chart given as text (docs/charts.md: k p yo k2tog ssk ... sl tuck ktbl, cables, a colour "
          "block, `stranded`) relaxed into a Pattern, cached like chart files. A chart file or chart:NAME goes "
          "to load_pattern. Raises knit.Error naming NAME:LINE:COLUMN.",
          py::call_guard<py::gil_scoped_release>());
    m.def("chart_floats", &chartFloats, "text"_a, "name"_a = "<chart text>", "max_float"_a = 5,
          "The chart's floats as dicts (row, line, columns, stitches, colour, side, too_long: longer than "
          "max_float stitches). Raises knit.Error for a bad chart.");
    m.def("chart_warnings", &chartWarnings, "text"_a, "name"_a = "<chart text>", "max_float"_a = 5, "keywords"_a = true,
          "The chart's warnings as `knit chart` prints them ('NAME:LINE: row R: the float ...', 'NAME: intarsia: "
          "... knitted 4 rows tall ...'): floats longer than max_float stitches, an intarsia repeat knitted taller "
          "than drawn. chart_pattern and load_pattern warn with each (knit.ChartWarning). keywords=False gives the "
          "library's words without this module's keyword after the float limit (for a front end with its own "
          "spelling, as knit.Error.words). Raises knit.Error for a bad chart.",
          py::call_guard<py::gil_scoped_release>());
    m.def(
        "chart_text",
        [](const std::string& fileOrName) -> py::object {
            const std::optional<std::string> text = knit::chartTextOf(fileOrName);
            return text ? py::object(py::str(*text)) : py::object(py::none());
        },
        "file_or_name"_a,
        "The chart text load_pattern relaxes for a chart:NAME or a .chart/.txt file (for chart_warnings), None "
        "for any other pattern. Raises knit.Error for a chart file that cannot be read.");
    m.def("builtin_charts", &knit::builtinChartNames, "The chart:NAME patterns load_pattern accepts.");
}

void registerPattern(py::module_& m) {
    py::class_<knit::Pattern>(m, "Pattern",
                              "One periodic pattern cell (metres): points, periodic edges, period, radius.")
        .def_readonly("name", &knit::Pattern::name)
        .def_readonly("px", &knit::Pattern::px, "period along x (pattern x -> u)")
        .def_readonly("py", &knit::Pattern::py, "period along y (pattern y -> v)")
        .def_readonly("radius", &knit::Pattern::radius, "yarn radius")
        .def_property_readonly(
            "points", [](py::object self) { return viewVec3(self.cast<const knit::Pattern&>().points, self); },
            "(n, 3) float64 read-only view: x, y in the plane, z = height")
        .def_property_readonly("edge_count", [](const knit::Pattern& p) { return p.edges.size(); })
        .def("__repr__", [](const knit::Pattern& p) {
            return "<knit.Pattern '" + p.name + "' " + std::to_string(p.points.size()) + " points>";
        });
    m.def("load_pattern", &knit::loadPatternFileOrName, "file_or_name"_a,
          "Loads a pattern: a .pyp / .json file or a built-in name (builtin_patterns()). Raises knit.Error.",
          py::call_guard<py::gil_scoped_release>());
    m.def("builtin_patterns", &knit::builtinPatternNames, "Names load_pattern accepts besides files.");
    registerChart(m);
}

void registerMesh(py::module_& m) {
    py::class_<knit::BaseMesh>(m, "Mesh",
                               "A triangle mesh with UVs. Positions and UVs are indexed separately (faces / face_uvs), "
                               "like OBJ v / vt: a position with several UVs is a seam.")
        .def(py::init(&meshFromArrays), "positions"_a, "faces"_a, "uvs"_a = py::none(), "face_uvs"_a = py::none(),
             "name"_a = "arrays",
             "A mesh from numpy arrays: positions (n, 3) float32/float64, faces (m, 3) integers, "
             "uvs (k, 2) with face_uvs (m, 3), or per-vertex uvs (n, 2) without face_uvs. Raises knit.Error.")
        .def_readonly("name", &knit::BaseMesh::name)
        .def_property_readonly(
            "positions", [](py::object self) { return viewVec3(self.cast<const knit::BaseMesh&>().positions, self); },
            "(n, 3) float64 read-only view")
        .def_property_readonly(
            "faces", [](py::object self) { return viewUvec3(self.cast<const knit::BaseMesh&>().faces, self); },
            "(m, 3) uint32 read-only view")
        .def_property_readonly(
            "uvs", [](py::object self) { return viewVec2(self.cast<const knit::BaseMesh&>().uvs, self); },
            "(k, 2) float64 read-only view")
        .def_property_readonly(
            "face_uvs", [](py::object self) { return viewUvec3(self.cast<const knit::BaseMesh&>().faceUvs, self); },
            "(m, 3) uint32 read-only view")
        .def("__repr__", [](const knit::BaseMesh& b) {
            return "<knit.Mesh '" + b.name + "' " + std::to_string(b.positions.size()) + " vertices, " +
                   std::to_string(b.faces.size()) + " triangles>";
        });
    m.def(
        "load_mesh",
        [](const std::string& fileOrName, int resU, int resV) {
            knit::ProceduralMeshOptions o;
            o.resU = resU;
            o.resV = resV;
            return knit::loadMeshFileOrName(fileOrName, o);
        },
        "file_or_name"_a, "res_u"_a = 32, "res_v"_a = 32,
        "Loads a mesh: .obj / .ply / .off / .gltf / .glb with UVs, or a built-in name "
        "(builtin_meshes(); res_u x res_v quads). Raises knit.Error.",
        py::call_guard<py::gil_scoped_release>());
    m.def("builtin_meshes", &knit::builtinMeshNames, "Names load_mesh accepts besides files.");
    m.def(
        "vertex_normals",
        [](const py::array& positions, const py::array& faces) {
            const auto p = toVec3(positions, "positions");
            const auto f = toUvec3(faces, "faces");
            requireIndicesBelow(f, p.size(), "faces", "positions");
            std::vector<glm::dvec3> n;
            {
                py::gil_scoped_release release;
                n = knit::vertexNormals(p, f);
            }
            py::array_t<double> out({py::ssize_t(n.size()), py::ssize_t(3)});
            if (!n.empty()) std::copy(&n[0].x, &n[0].x + 3 * n.size(), out.mutable_data());
            return out;
        },
        "positions"_a, "faces"_a, "Angle-weighted vertex normals (n, 3) on the 3D topology.");
    m.def(
        "uv_to_metre_scale",
        [](const knit::BaseMesh& mesh) {
            const glm::dvec2 s = knit::uvToMetreScale(mesh);
            return py::make_tuple(s.x, s.y);
        },
        "mesh"_a, "Metres per UV unit along u and v (area-weighted).");
}

}  // namespace

void registerPatternAndMesh(py::module_& m) {
    registerPattern(m);
    registerMesh(m);
}

}  // namespace knitpy
