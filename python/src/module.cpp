// python/src/module.cpp — the extension `knit._knit`: knit.Error and the parts of the API.
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "knit/error.hpp"
#include "knit/setting_spelling.hpp"

namespace knitpy {
namespace {

// Library messages name settings in words ("raise the ply pitch", knit/setting_spelling.hpp); a
// Python user gets this module's keyword after them ("raise the ply pitch (ply_pitch)"). Settings
// the module has no keyword for stay in words.
const std::vector<knit::SettingSpelling>& keywords() {
    static const std::vector<knit::SettingSpelling> k = {
        {"the repeats", "repeats"},
        {"the clamp tolerance", "clamp_tolerance"},
        {"the weld tolerance", "weld_tolerance"},
        {"the number of plies", "plies"},
        {"the ply radius", "ply_radius"},
        {"the ply centre radius", "center_radius"},
        {"the ply pitch", "ply_pitch"},
        {"the samples per turn", "samples_per_turn"},
        {"the twist direction", "twist"},
        {"the memory budget", "max_memory"},
        {"what to export", "what"},
        {"the number of tube sides", "sides"},
        {"Draco compression", "draco"},
        {"mesh quantization", "quantize"},
        {"meshopt compression", "meshopt"},
    };
    return k;
}

pybind11::exception<knit::Error>* knitError = nullptr;

}  // namespace
}  // namespace knitpy

PYBIND11_MODULE(_knit, m) {
    m.doc() = "libknit: knitted fabric at ply level on a UV-mapped triangle mesh (pattern -> scene -> "
              "binding -> evaluate -> plies -> export). Arrays are numpy; lengths are metres.";
    // knit::Error (bad files, meshes, options) arrives as knit.Error with the library's message,
    // settings followed by this module's keywords (keywords() above). The local translator is tried
    // before the one register_exception installs.
    knitpy::knitError = &pybind11::register_exception<knit::Error>(m, "Error", PyExc_Exception);
    pybind11::register_local_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const knit::Error& e) {
            (*knitpy::knitError)(knit::spellSettings(e.what(), knitpy::keywords()).c_str());
        }
    });
    knitpy::registerPatternAndMesh(m);
    knitpy::registerCurves(m);
    knitpy::registerScene(m);
    knitpy::registerExport(m);
    knitpy::registerBoundScene(m);
}
