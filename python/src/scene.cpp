// python/src/scene.cpp — knit.Scene (the built pipeline), knit.Binding, build_scene and the
// per-frame evaluation on new vertex positions, through the library's Animator (the path
// `knit animate` takes: layout, twist phase and frame seeds fixed when the scene is bound).
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>
#include <mutex>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "memory_budget_arg.hpp"
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
    std::string maxMemory;    // "" = the default budget, else a size ("8G")
    std::string deform = "";  // "", "none" or "strain"
    py::object strainTable;   // None, a path or a StrainTable
};

// deform / strain_table as the CLI's --deform / --strain-table (knit::decideDeform, the one rule):
// a table given means strain unless deform is "none"; "strain" without one uses the pattern's
// cached table (made on first use); "" (the default) does so where the table is cached or made in
// seconds, else none (Scene.stats["deform_why"] says so and names knit.strain_table).
void resolveDeform(const SceneArgs& a, const py::object& pattern, knit::SceneOptions& o) {
    if (a.deform != "" && a.deform != "none" && a.deform != "strain")
        throw knit::Error("deform must be 'none', 'strain' or '' (strain where the table is at hand), got '" +
                          a.deform + "'");
    const knit::DeformChoice choice = a.deform == "none"     ? knit::DeformChoice::None
                                      : a.deform == "strain" ? knit::DeformChoice::Strain
                                                             : knit::DeformChoice::Auto;
    if (choice == knit::DeformChoice::None) return;
    std::shared_ptr<const knit::StrainTable> given;
    if (!a.strainTable.is_none())
        given =
            py::isinstance<py::str>(a.strainTable)
                ? std::make_shared<const knit::StrainTable>(knit::loadStrainTable(a.strainTable.cast<std::string>()))
                : std::shared_ptr<const knit::StrainTable>(castArg<std::shared_ptr<knit::StrainTable>>(
                      a.strainTable, "strain_table", "None, a .npy file (str) or a knit.StrainTable"));
    const knit::Pattern p = given || !py::isinstance<py::str>(pattern)
                                ? (given ? knit::Pattern{} : castArg<knit::Pattern>(pattern, "pattern", kPatternArg))
                                : knit::loadPatternFileOrName(pattern.cast<std::string>());
    py::gil_scoped_release release;
    o.deform = knit::decideDeform(p, choice, given).deform;
}

// Why the scene deforms as it does, in Python's words (Scene.stats["deform_why"]).
std::string deformWhy(const knit::DeformOptions& d) {
    char buf[200];
    switch (d.reason) {
        case knit::DeformReason::TableGiven: return "strain_table given";
        case knit::DeformReason::Cached: return "the pattern's strain table was in the cache";
        case knit::DeformReason::Made:
            std::snprintf(buf, sizeof buf, "the pattern's strain table was made now (%.1f s) and cached",
                          d.tableSeconds);
            return buf;
        case knit::DeformReason::TooSlowToMake:
            std::snprintf(buf, sizeof buf,
                          "no strain table at hand and making one takes about %.0f s: knit.strain_table(pattern, path) "
                          "makes it (then strain_table=path), or deform='strain' makes and caches it",
                          d.tableSeconds);
            return buf;
        case knit::DeformReason::CannotMake:
            return "the pattern cannot have a strain table (its yarns cannot be relaxed)";
        case knit::DeformReason::Asked: break;
    }
    return d.mode == knit::DeformMode::Strain ? "deform='strain'" : "deform='none'";
}

knit::SceneOptions toSceneOptions(const SceneArgs& a) {
    knit::SceneOptions o;
    if (!a.repeats.is_none()) {
        std::pair<double, double> r;
        try {
            r = a.repeats.cast<std::pair<double, double>>();
        } catch (const py::cast_error&) {
            throw py::type_error("repeats: expected None or a pair (U, V) of numbers, got " +
                                 std::string(py::repr(a.repeats)));
        }
        o.placement.repeats = {r.first, r.second};
    }
    o.meshOptions.resU = a.resU;
    o.meshOptions.resV = a.resV;
    o.bind.clampTolerance = a.clampTolerance;
    o.bind.weldTolerance = a.weldTolerance;
    o.bind.weld = a.weld;
    o.buildPlies = a.buildPlies;
    o.budget = memoryBudgetArg(a.maxMemory);
    o.plies = toPlyOptions(a.plies, o.plies.yarnRadius);  // the pipeline sets yarnRadius
    return o;
}

// Runs the pipeline; `pattern` / `mesh` are names or files (str) or Pattern / Mesh objects.
ScenePtr buildScene(const py::object& pattern, const py::object& mesh, const SceneArgs& args) {
    knit::SceneOptions options = toSceneOptions(args);
    resolveDeform(args, pattern, options);
    const bool inMemory = !py::isinstance<py::str>(pattern) || !py::isinstance<py::str>(mesh);
    if (!inMemory) {
        options.pattern = pattern.cast<std::string>();
        options.mesh = mesh.cast<std::string>();
        py::gil_scoped_release release;
        return std::make_shared<knit::Scene>(knit::buildScene(options));
    }
    knit::Pattern p = py::isinstance<py::str>(pattern) ? knit::loadPatternFileOrName(pattern.cast<std::string>())
                                                       : castArg<knit::Pattern>(pattern, "pattern", kPatternArg);
    knit::MeshLoadOptions load;
    load.budget = options.budget;
    knit::BaseMesh b = py::isinstance<py::str>(mesh)
                           ? knit::loadMeshFileOrName(mesh.cast<std::string>(), options.meshOptions, load)
                           : castArg<knit::BaseMesh>(mesh, "mesh", "a mesh name or file (str) or a knit.Mesh");
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

// The Animators a Scene evaluates new poses through (knit/animation.hpp), made on first use and
// kept with the Python Scene: one for the yarns alone (Scene.evaluate: the binding evaluated,
// nothing resampled) and one for the plies (Scene.evaluate_plies: the rest layout, twist phase
// and frame seeds of `knit animate`). An Animator keeps no state between evaluations (each call
// fills its own AnimationFrame), so evaluations from several Python threads run concurrently
// and give the sequential results bit for bit; a call holds a lock only to look its Animator up
// (and, the first time, while it is made).
class SceneAnimators {
public:
    explicit SceneAnimators(ScenePtr scene) : scene_(std::move(scene)) {}

    // The Animator for the yarns (plies false) or the plies; call without the GIL (making the
    // ply one resamples every rest yarn).
    const knit::Animator& get(bool plies, bool deform = true) {
        Slot& slot = plies ? (deform ? plies_ : pliesGeometric_) : (deform ? yarns_ : yarnsGeometric_);
        const std::lock_guard<std::mutex> lock(slot.mutex);
        if (!slot.animator) {
            knit::AnimatorOptions o;
            o.plies = plies;
            o.deform = deform;
            o.stats = false;  // the frame statistics are knit animate's report
            slot.animator = std::make_unique<knit::Animator>(*scene_, o);
        }
        return *slot.animator;
    }

private:
    struct Slot {
        std::mutex mutex;
        std::unique_ptr<const knit::Animator> animator;
    };
    ScenePtr scene_;                                        // the Animators refer to it: kept alive with them
    Slot yarns_, plies_, yarnsGeometric_, pliesGeometric_;  // with and without the strain deformer
};

// The SceneAnimators of a Python Scene, in its __dict__ (made on first call; the GIL held).
std::shared_ptr<SceneAnimators> animatorsOf(const py::object& self) {
    using Held = std::shared_ptr<SceneAnimators>;
    py::dict dict = self.attr("__dict__");
    if (!dict.contains("_animators"))
        dict["_animators"] = py::capsule(new Held(std::make_shared<SceneAnimators>(self.cast<ScenePtr>())),
                                         [](void* p) { delete static_cast<Held*>(p); });
    return *static_cast<Held*>(dict["_animators"].cast<py::capsule>().get_pointer());
}

// The last guard against returning non-finite data: the checked positions keep every step finite,
// and should a pose still give a non-finite point it is refused, naming the curve and the point.
void requireFiniteCurves(const knit::Polylines& curves, const char* what) {
    for (size_t c = 0; c < curves.curveCount(); ++c)
        for (uint32_t i = curves.begin(c); i < curves.end(c); ++i) {
            const glm::dvec3& q = curves.points[i];
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                throw knit::Error("positions: this pose gives a non-finite point (" + std::string(what) + " " +
                                  std::to_string(c) + ", point " + std::to_string(i - curves.begin(c)) +
                                  "); check the positions for collapsed or far-flung vertices");
        }
}

// The frame of `positions` evaluated by the scene's yarn or ply Animator (GIL released).
// deform: None (the scene's own mode), "none" (the geometric mapping) or "strain" (the scene must
// have been built with a strain table).
knit::AnimationFrame evaluateFrame(const py::object& self, const py::array& positions, bool plies,
                                   const py::object& deform = py::none()) {
    const knit::Scene& scene = self.cast<const knit::Scene&>();
    bool useDeformer = true;
    if (!deform.is_none()) {
        const std::string d = castArg<std::string>(deform, "deform", "None, 'none' or 'strain'");
        if (d != "none" && d != "strain") throw knit::Error("deform must be 'none' or 'strain', got '" + d + "'");
        if (d == "strain" && !scene.deformer())
            throw knit::Error("deform='strain' needs a scene built with a strain table (build_scene(..., "
                              "strain_table=...) or deform='strain')");
        useDeformer = d == "strain";
    }
    const auto p = framePositions(scene, positions);
    const std::shared_ptr<SceneAnimators> animators = animatorsOf(self);
    py::gil_scoped_release release;
    knit::AnimationFrame frame;
    animators->get(plies, useDeformer).evaluate(p, frame);
    if (plies) requireFiniteCurves(frame.plies.curves, "ply curve");
    else requireFiniteCurves(frame.yarns.curves, "yarn");
    return frame;
}

py::dict sceneStatsDict(const knit::Scene& scene) {
    const knit::SceneStats s = knit::sceneStats(scene);
    py::dict d("cells"_a = s.cells, "tiles"_a = s.tiles, "yarns"_a = s.yarns, "yarn_vertices"_a = s.yarnVertices,
               "ply_vertices"_a = s.plyVertices, "closed_loops"_a = s.bind.closedLoops, "open_ends"_a = s.bind.openEnds,
               "cut_vertices"_a = s.bind.cutVertices, "clamped_vertices"_a = s.bind.clampedVertices,
               "welded_ends"_a = s.bind.weldedEnds, "total_seconds"_a = s.totalSeconds,
               "deform"_a = scene.deformer() ? "strain" : "none", "deform_why"_a = deformWhy(scene.deformOptions()));
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
    // dynamic_attr: the Scene's Animators live in its __dict__ (animatorsOf).
    py::class_<knit::Scene, ScenePtr>(m, "Scene", py::dynamic_attr(),
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
            [](const py::object& self, const py::array& positions, const py::object& deform) {
                return std::move(evaluateFrame(self, positions, false, deform).yarns);
            },
            "positions"_a, "deform"_a = py::none(),
            "The yarns on new vertex positions (n, 3) float32/float64 of the scene's mesh (same "
            "connectivity): normals of the posed mesh, then the binding (the first steps of knit animate's "
            "frame). deform: None (the scene's mode), 'none' (the geometric mapping) or 'strain' (the strain "
            "table the scene was built with). Returns Yarns. Thread-safe: runs without the GIL, concurrently with "
            "other evaluations. "
            "Raises knit.Error.")
        .def(
            "evaluate_plies",
            [](const py::object& self, const py::array& positions) {
                return std::move(evaluateFrame(self, positions, true).plies);
            },
            "positions"_a,
            "The plies on new vertex positions, exactly as knit animate evaluates a frame of this scene: "
            "the layout of every yarn (point counts and order), its twist phase (from the rest arc "
            "length) and its first ply frame (carried by the bound triangle's rotation) are fixed when "
            "the scene is bound, so the point count is the same on every pose and nothing swims, flips "
            "or pops. The first call makes the scene's animator (resamples the rest yarns once). "
            "Thread-safe: runs without the GIL, concurrently with other evaluations. For the ply stage "
            "resampled afresh on one pose use make_plies(scene.evaluate(positions), ...). Raises knit.Error.")
        .def("__repr__", [](const knit::Scene& s) {
            return "<knit.Scene '" + s.pattern().name + "' on '" + s.mesh().name +
                   "': " + std::to_string(s.binding().yarnCount()) + " yarns, " +
                   std::to_string(s.binding().vertexCount()) + " yarn points>";  // a loaded scene's yarns stay lazy
        });
}

// For tools/python_timing.py: the seconds of `repeats` Scene.evaluate calls made in C++ (the
// scene's yarn Animator into a fresh AnimationFrame, as Scene.evaluate does).
double evaluateSecondsInCpp(const py::object& self, const py::array& positions, int repeats) {
    const knit::Scene& s = self.cast<const knit::Scene&>();
    const auto p = framePositions(s, positions);
    const std::shared_ptr<SceneAnimators> animators = animatorsOf(self);
    py::gil_scoped_release release;
    const knit::Animator& animator = animators->get(false);  // made before the clock starts
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < repeats; ++i) {
        knit::AnimationFrame frame;
        animator.evaluate(p, frame);
        if (frame.yarns.curves.points.empty() && !s.yarns().curves.points.empty())
            throw knit::Error("evaluate: no points");
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
           int resU, int resV, double clampTolerance, bool weld, double weldTolerance, const std::string& maxMemory,
           const std::string& deform, const py::object& strainTable) {
            SceneArgs a{repeats,       {plies, plyPitch, twist, plyRadius, centerRadius, samplesPerTurn},
                        buildPlies,    resU,
                        resV,          clampTolerance,
                        weldTolerance, weld,
                        maxMemory,     deform,
                        strainTable};
            return buildScene(pattern, mesh, a);
        },
        "pattern"_a = "stockinette", "mesh"_a = "drape", "repeats"_a = py::none(), "plies"_a = 2, "ply_pitch"_a = 0.0,
        "twist"_a = "S", "ply_radius"_a = 0.0, "center_radius"_a = 0.0, "samples_per_turn"_a = 12,
        "build_plies"_a = true, "res_u"_a = 32, "res_v"_a = 32, "clamp_tolerance"_a = 0.01, "weld"_a = true,
        "weld_tolerance"_a = 0.25, "max_memory"_a = "", "deform"_a = "", "strain_table"_a = py::none(),
        "Runs the pipeline: load pattern -> load mesh -> placement -> UV grid -> tiling -> stitch -> "
        "binding -> evaluation -> plies. pattern / mesh: a file or built-in name, or a Pattern / Mesh. "
        "repeats: (U, V) pattern periods across the UV square, None = the pattern's physical size. "
        "plies: plies per yarn; ply_pitch 0 = 6 yarn radii; twist 'S' or 'Z'. max_memory: the memory budget "
        "as a size ('8G', '512M'; '' = min(4 GiB, half the physical memory)): a step whose "
        "estimated size is over it raises knit.Error before allocating. deform: 'none', 'strain' or '' (the "
        "default: strain where the pattern's table is at hand: strain_table given, cached, or made in seconds; else "
        "none; stats['deform'] and stats['deform_why'] say which and why); strain_table: a path (T.npy or a MADYPG "
        "sxsasy/ folder) or a StrainTable; deform='strain' without one makes a table first. Raises knit.Error.");
    m.def("_evaluate_seconds_in_cpp", &evaluateSecondsInCpp, "scene"_a, "positions"_a, "repeats"_a = 1,
          "Timing aid: seconds of `repeats` evaluations made in C++ (what Scene.evaluate runs).");
}

}  // namespace knitpy
