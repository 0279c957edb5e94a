// python/src/module.cpp — the extension `knit._knit`: knit.Error and the parts of the API.
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "knit/error.hpp"
#include "knit/output_file.hpp"
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
        {"the mesh resolution", "res_u, res_v"},
        {"the float limit", "max_float"},
        {"the sx range", "sx_range"},
        {"the sa range", "sa_range"},
        {"the sy range", "sy_range"},
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

std::string withKeywords(const std::string& words) { return knit::spellSettings(words, keywords()); }

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
            // The message with this module's keywords; `words` keeps the library's message, for a
            // front end on top of the module with its own spelling (spell_settings).
            pybind11::object error = pybind11::reinterpret_borrow<pybind11::object>(knitpy::knitError->ptr())(
                knitpy::withKeywords(e.what()));
            error.attr("words") = std::string(e.what());
            PyErr_SetObject(knitpy::knitError->ptr(), error.ptr());
        }
    });
    m.def(
        "spell_settings",
        [](const std::string& words, const std::vector<std::pair<std::string, std::string>>& spellings) {
            std::vector<knit::SettingSpelling> s;
            for (const auto& [w, spelling] : spellings) s.push_back({w, spelling});
            return knit::spellSettings(words, s);
        },
        pybind11::arg("words"), pybind11::arg("spellings"),
        "A library message (knit.Error.words) with a front end's spelling of each setting after its first "
        "mention: spellings is [(words, spelling)], e.g. [('the repeats', 'Repeats')]. knit.Error's own "
        "message is this with the module's keywords.");
    m.def(
        "remove_stale_temporaries", [](const std::string& folder) { return knit::removeStaleTemporaries(folder); },
        pybind11::arg("folder"),
        "Removes the temporaries killed runs left in folder ('' = the working folder): hidden "
        "'.NAME.PID.N.tmp' files and '.knit-staging.PID.N.tmp' folders of this user whose process is gone and "
        "whose lock nobody holds. Every knit writer does this before writing into a folder; a writer of its "
        "own (the Blender add-on's bake) calls it. Returns how many it removed; never raises.");
    knitpy::registerPatternAndMesh(m);
    knitpy::registerCurves(m);
    knitpy::registerStrain(m);
    knitpy::registerScene(m);
    knitpy::registerExport(m);
    knitpy::registerBoundScene(m);
}
