// python/src/bindings.hpp — the parts of the module, one registration function per file.
#pragma once
#include <pybind11/pybind11.h>

namespace knitpy {

namespace py = pybind11;

void registerPatternAndMesh(py::module_& m);  // pattern_mesh.cpp: Pattern, Mesh, loaders
void registerCurves(py::module_& m);          // curves.cpp: Curves, Yarns, Plies, make_plies
void registerScene(py::module_& m);           // scene.cpp: Scene, Binding, build_scene, evaluate
void registerExport(py::module_& m);          // export.cpp: export_scene
void registerStrain(py::module_& m);          // strain.cpp: StrainTable, strain_table, load_strain_table
void registerBoundScene(py::module_& m);      // bound_scene.cpp: bound scene files, frame numbers

}  // namespace knitpy
