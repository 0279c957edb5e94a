// python/src/module.cpp — the extension `knit._knit`: knit.Error and the parts of the API.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "knit/error.hpp"

PYBIND11_MODULE(_knit, m) {
    m.doc() = "libknit: knitted fabric at ply level on a UV-mapped triangle mesh (pattern -> scene -> "
              "binding -> evaluate -> plies -> export). Arrays are numpy; lengths are metres.";
    // knit::Error (bad files, meshes, options) arrives as knit.Error with the library's message.
    pybind11::register_exception<knit::Error>(m, "Error", PyExc_Exception);
    knitpy::registerPatternAndMesh(m);
    knitpy::registerCurves(m);
    knitpy::registerScene(m);
    knitpy::registerExport(m);
}
