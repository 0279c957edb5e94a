// python/src/scene.cpp — knit.Scene (the built pipeline), knit.Binding, build_scene and the
// per-frame evaluation on new vertex positions.
#include <chrono>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "frame_plies.hpp"
#include "ply_options.hpp"

namespace knitpy {

namespace {

using namespace pybind11::literals;
using ScenePtr = std::shared_ptr<knit::Scene>;

// build_scene's keyword arguments besides the pattern and the mesh.
struct SceneArgs {
    py::object repeats;  // None or (U, V)
    PlyArgs plies;
    bool buildPlies = true;
    int resU = 32, resV = 32;
    double clampTolerance = 0.01, weldTolerance = 0.25;
    bool weld = true;
    std::string maxMemory;  // "" = the default budget, else as --max-memory ("8G")
};

knit::SceneOptions toSceneOptions(const SceneArgs& a) {
    knit::SceneOptions o;
    if (!a.repeats.is_none()) {
        const auto r = a.repeats.cast<std::pair<double, double>>();
        o.placement.repeats = {r.first, r.second};
    }
    o.meshOptions.resU = a.resU;
    o.meshOptions.resV = a.resV;
    o.bind.clampTolerance = a.clampTolerance;
    o.bind.weldTolerance = a.weldTolerance;
    o.bind.weld = a.weld;
    o.buildPlies = a.buildPlies;
    if (!a.maxMemory.empty()) o.budget = knit::MemoryBudget(knit::parseMemorySize(a.maxMemory));
    o.plies = toPlyOptions(a.plies, o.plies.yarnRadius);  // the pipeline sets yarnRadius
    return o;
}

// Runs the pipeline; `pattern` / `mesh` are names or files (str) or Pattern / Mesh objects.
ScenePtr buildScene(const py::object& pattern, const py::object& mesh, const SceneArgs& args) {
    knit::SceneOptions options = toSceneOptions(args);
    const bool inMemory = !py::isinstance<py::str>(pattern) || !py::isinstance<py::str>(mesh);
    if (!inMemory) {
        options.pattern = pattern.cast<std::string>();
        options.mesh = mesh.cast<std::string>();
        py::gil_scoped_release release;
        return std::make_shared<knit::Scene>(knit::buildScene(options));
    }
    knit::Pattern p = py::isinstance<py::str>(pattern) ? knit::loadPatternFileOrName(pattern.cast<std::string>())
                                                       : pattern.cast<knit::Pattern>();
    knit::BaseMesh b = py::isinstance<py::str>(mesh)
                           ? knit::loadMeshFileOrName(mesh.cast<std::string>(), options.meshOptions)
                           : mesh.cast<knit::BaseMesh>();
    py::gil_scoped_release release;
    return std::make_shared<knit::Scene>(knit::buildScene(std::move(p), std::move(b), options));
}

// New vertex positions (same connectivity as the scene's mesh) as dvec3s; throws naming the count.
std::vector<glm::dvec3> framePositions(const knit::Scene& scene, const py::array& positions) {
    std::vector<glm::dvec3> p = toVec3(positions, "positions");
    if (p.size() != scene.mesh().positions.size())
        throw knit::Error("positions: expected " + std::to_string(scene.mesh().positions.size()) +
                          " rows (the scene's mesh vertices), got " + std::to_string(p.size()));
    return p;
}

// The yarns on a new pose: normals of the posed mesh, then the binding's gather.
knit::MappedYarns evaluatePose(const knit::Scene& scene, const std::vector<glm::dvec3>& positions) {
    const std::vector<glm::dvec3> normals = knit::vertexNormals(positions, scene.mesh().faces);
    knit::MappedYarns yarns;
    knit::evaluateBinding(scene.binding(), scene.mesh().faces, positions, normals, yarns);
    return yarns;
}

py::dict sceneStatsDict(const knit::Scene& scene) {
    const knit::SceneStats s = knit::sceneStats(scene);
    py::dict d("cells"_a = s.cells, "tiles"_a = s.tiles, "yarns"_a = s.yarns, "yarn_vertices"_a = s.yarnVertices,
               "ply_vertices"_a = s.plyVertices, "closed_loops"_a = s.bind.closedLoops, "open_ends"_a = s.bind.openEnds,
               "cut_vertices"_a = s.bind.cutVertices, "clamped_vertices"_a = s.bind.clampedVertices,
               "welded_ends"_a = s.bind.weldedEnds, "total_seconds"_a = s.totalSeconds);
    py::dict stages;
    for (const knit::StageTime& t : s.stageTimes) stages[py::str(t.stage)] = t.seconds;
    d["stage_seconds"] = stages;
    return d;
}

void registerBinding(py::module_& m) {
    py::class_<knit::Binding>(m, "Binding",
                              "Per yarn vertex: triangle, barycentrics (b1, b2), height; made once on the rest mesh.")
        .def_property_readonly(
            "face", [](py::object self) { return viewScalars(self.cast<const knit::Binding&>().face, self); })
        .def_property_readonly(
            "bary", [](py::object self) { return viewVec2(self.cast<const knit::Binding&>().bary, self); },
            "(n, 2) float64: (b1, b2); b0 = 1 - b1 - b2")
        .def_property_readonly(
            "height", [](py::object self) { return viewScalars(self.cast<const knit::Binding&>().height, self); })
        .def_property_readonly(
            "offsets", [](py::object self) { return viewScalars(self.cast<const knit::Binding&>().offsets, self); })
        .def_property_readonly(
            "closed", [](py::object self) { return viewScalars(self.cast<const knit::Binding&>().closed, self); })
        .def_property_readonly("vertex_count", &knit::Binding::vertexCount)
        .def_property_readonly("yarn_count", &knit::Binding::yarnCount);
}

void registerSceneClass(py::module_& m) {
    py::class_<knit::Scene, ScenePtr>(m, "Scene",
                                      "The built pipeline (read-only): pattern, mesh, binding, yarns, plies.")
        .def_property_readonly("pattern", &knit::Scene::pattern, py::return_value_policy::reference_internal)
        .def_property_readonly("mesh", &knit::Scene::mesh, py::return_value_policy::reference_internal)
        .def_property_readonly("binding", &knit::Scene::binding, py::return_value_policy::reference_internal)
        .def_property_readonly("yarns", &knit::Scene::yarns, py::return_value_policy::reference_internal,
                               "the yarns evaluated on the rest mesh")
        .def_property_readonly("plies", &knit::Scene::plies, py::return_value_policy::reference_internal,
                               "empty unless built with build_plies=True")
        .def_property_readonly(
            "normals", [](py::object self) { return viewVec3(self.cast<const knit::Scene&>().normals(), self); },
            "(n, 3) rest-pose vertex normals of the mesh")
        .def_property_readonly("yarn_radius", &knit::Scene::yarnRadius, "object space (metres)")
        .def_property_readonly("ply_radius",
                               [](const knit::Scene& s) { return knit::resolvePlyOptions(s.plyOptions()).plyRadius; })
        .def_property_readonly(
            "repeats",
            [](const knit::Scene& s) { return py::make_tuple(s.placement().repeats.x, s.placement().repeats.y); })
        .def_property_readonly("stats", &sceneStatsDict, "counts and stage times (the `knit build` report's numbers)")
        .def(
            "evaluate",
            [](const knit::Scene& s, const py::array& positions) {
                const auto p = framePositions(s, positions);
                py::gil_scoped_release release;
                return evaluatePose(s, p);
            },
            "positions"_a,
            "The yarns on new vertex positions (n, 3) float32/float64 of the scene's mesh (same "
            "connectivity): normals of the posed mesh, then the binding. Returns Yarns. Raises knit.Error.")
        .def(
            "evaluate_plies",
            [](const knit::Scene& s, const py::array& positions, bool restLayout) {
                const auto p = framePositions(s, positions);
                if (restLayout && s.plies().curves.curveCount() == 0 && s.yarns().curves.pointCount() > 0)
                    throw knit::Error("evaluate_plies: rest_layout needs a scene built with build_plies=True");
                py::gil_scoped_release release;
                const knit::MappedYarns yarns = evaluatePose(s, p);
                return restLayout ? pliesWithRestLayout(yarns, s.plyOptions(), s.plies())
                                  : knit::makePlies(yarns, s.plyOptions());
            },
            "positions"_a, "rest_layout"_a = true,
            "The plies on new vertex positions, with the scene's ply options (evaluate, then the ply "
            "stage). rest_layout=True keeps the rest plies' point counts and offsets (a stretched yarn's "
            "centreline is re-sampled by arc length to its rest count), for animation caches and meshes; "
            "False runs make_plies, whose point count follows the yarn length.")
        .def("__repr__", [](const knit::Scene& s) {
            return "<knit.Scene '" + s.pattern().name + "' on '" + s.mesh().name +
                   "': " + std::to_string(s.yarns().curves.curveCount()) + " yarns, " +
                   std::to_string(s.yarns().curves.pointCount()) + " yarn points>";
        });
}

// For tools/python_evaluate_timing.py: the seconds of `repeats` Scene.evaluate calls made in C++
// (vertexNormals + evaluateBinding into a fresh MappedYarns, as Scene.evaluate does).
double evaluateSecondsInCpp(const knit::Scene& s, const py::array& positions, int repeats) {
    const auto p = framePositions(s, positions);
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < repeats; ++i) {
        const knit::MappedYarns y = evaluatePose(s, p);
        if (y.curves.points.empty() && !s.yarns().curves.points.empty()) throw knit::Error("evaluate: no points");
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void registerScene(py::module_& m) {
    registerBinding(m);
    registerSceneClass(m);
    m.def(
        "build_scene",
        [](const py::object& pattern, const py::object& mesh, const py::object& repeats, int plies, double plyPitch,
           const std::string& twist, double plyRadius, double centerRadius, int samplesPerTurn, bool buildPlies,
           int resU, int resV, double clampTolerance, bool weld, double weldTolerance, const std::string& maxMemory) {
            SceneArgs a{repeats,       {plies, plyPitch, twist, plyRadius, centerRadius, samplesPerTurn},
                        buildPlies,    resU,
                        resV,          clampTolerance,
                        weldTolerance, weld,
                        maxMemory};
            return buildScene(pattern, mesh, a);
        },
        "pattern"_a = "stockinette", "mesh"_a = "drape", "repeats"_a = py::none(), "plies"_a = 2, "ply_pitch"_a = 0.0,
        "twist"_a = "S", "ply_radius"_a = 0.0, "center_radius"_a = 0.0, "samples_per_turn"_a = 12,
        "build_plies"_a = true, "res_u"_a = 32, "res_v"_a = 32, "clamp_tolerance"_a = 0.01, "weld"_a = true,
        "weld_tolerance"_a = 0.25, "max_memory"_a = "",
        "Runs the pipeline: load pattern -> load mesh -> placement -> UV grid -> tiling -> stitch -> "
        "binding -> evaluation -> plies. pattern / mesh: a file or built-in name, or a Pattern / Mesh. "
        "repeats: (U, V) pattern periods across the UV square, None = the pattern's physical size. "
        "plies: plies per yarn; ply_pitch 0 = 6 yarn radii; twist 'S' or 'Z'. max_memory: the memory budget "
        "as a size ('8G', '512M'; '' = min(4 GiB, half the physical memory)), as --max-memory: a step whose "
        "estimated size is over it raises knit.Error before allocating. Raises knit.Error.");
    m.def("_evaluate_seconds_in_cpp", &evaluateSecondsInCpp, "scene"_a, "positions"_a, "repeats"_a = 1,
          "Timing aid: seconds of `repeats` evaluations made in C++ (what Scene.evaluate runs).");
}

}  // namespace knitpy
