// python/src/bindings.hpp — the parts of the module, one registration function per file.
#pragma once
#include <pybind11/pybind11.h>

#include <string>

namespace knitpy {

namespace py = pybind11;

// What a `pattern` argument may be, for castArg's messages.
inline constexpr const char* kPatternArg = "a pattern name or file (str) or a knit.Pattern";

// `value` (the argument `keyword`) as T, or a TypeError in the caller's words: "pattern: expected a
// pattern name or file (str) or a knit.Pattern, got int" (pybind11's own cast failure is a
// RuntimeError naming none of them).
template <class T>
T castArg(const py::handle& value, const char* keyword, const char* expected) {
    try {
        return value.cast<T>();
    } catch (const py::cast_error&) {
        throw py::type_error(std::string(keyword) + ": expected " + expected + ", got " +
                             std::string(py::str(py::type::handle_of(value).attr("__name__"))));
    }
}

// A library message with this module's keyword after each setting it names ("the float limit
// (max_float)"), as knit.Error's message (module.cpp).
std::string withKeywords(const std::string& words);

void registerPatternAndMesh(py::module_& m);  // pattern_mesh.cpp: Pattern, Mesh, loaders
void registerCurves(py::module_& m);          // curves.cpp: Curves, Yarns, Plies, make_plies
void registerScene(py::module_& m);           // scene.cpp: Scene, Binding, build_scene, evaluate
void registerExport(py::module_& m);          // export.cpp: export_scene
void registerStrain(py::module_& m);          // strain.cpp: StrainTable, strain_table, load_strain_table
void registerBoundScene(py::module_& m);      // bound_scene.cpp: bound scene files, frame numbers

}  // namespace knitpy
