// python/src/module.cpp — the extension `knit._knit`: knit.Error and the parts of the API.
#include <cctype>
#include <string>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "knit/error.hpp"

namespace knitpy {
namespace {

// The library's messages may name a setting by the command line's flag ("raise --ply-pitch");
// a Python user knows it by its keyword argument, or, for a setting the module does not expose,
// by its name in words. Other flags (of commands the module does not have) stay as they are.
struct Spelling {
    const char* flag;
    const char* keyword;
};
constexpr Spelling kSpellings[] = {
    {"--plies", "plies"},
    {"--ply-pitch", "ply_pitch"},
    {"--ply-radius", "ply_radius"},
    {"--ply-center-radius", "center_radius"},
    {"--samples-per-turn", "samples_per_turn"},
    {"--twist", "twist"},
    {"--repeats", "repeats"},
    {"--mesh", "mesh"},
    {"--clamp-tolerance", "clamp_tolerance"},
    {"--weld-tolerance", "weld_tolerance"},
    {"--max-memory", "max_memory"},
    {"--export", "what"},
    {"--sides", "sides"},
    {"--draco", "draco"},
    {"--quantize", "quantize"},
    {"--meshopt", "meshopt"},
    {"--yarn-colors", "yarn_colors"},
    {"--chunk-vertices", "the vertices per export chunk"},
    {"--draco-bits", "the Draco quantization bits"},
    {"--draco-level", "the Draco compression level"},
    {"--gauge", "a gauge"},
};

bool flagChar(char c) { return std::islower(static_cast<unsigned char>(c)) || c == '-'; }

// `message` with every whole flag of kSpellings replaced by its keyword.
std::string pythonSpelling(const std::string& message) {
    std::string out;
    out.reserve(message.size());
    size_t i = 0;
    while (i < message.size()) {
        const bool starts = message.compare(i, 2, "--") == 0 && (i == 0 || !flagChar(message[i - 1]));
        if (!starts) {
            out += message[i++];
            continue;
        }
        size_t end = i + 2;
        while (end < message.size() && flagChar(message[end])) ++end;
        const std::string flag = message.substr(i, end - i);
        const char* keyword = nullptr;
        for (const Spelling& s : kSpellings)
            if (flag == s.flag) keyword = s.keyword;
        out += keyword ? std::string(keyword) : flag;
        i = end;
    }
    return out;
}

pybind11::exception<knit::Error>* knitError = nullptr;

}  // namespace
}  // namespace knitpy

PYBIND11_MODULE(_knit, m) {
    m.doc() = "libknit: knitted fabric at ply level on a UV-mapped triangle mesh (pattern -> scene -> "
              "binding -> evaluate -> plies -> export). Arrays are numpy; lengths are metres.";
    // knit::Error (bad files, meshes, options) arrives as knit.Error with the library's message,
    // settings spelled as this module's keywords (pythonSpelling). The local translator is tried
    // before the one register_exception installs.
    knitpy::knitError = &pybind11::register_exception<knit::Error>(m, "Error", PyExc_Exception);
    pybind11::register_local_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const knit::Error& e) {
            (*knitpy::knitError)(knitpy::pythonSpelling(e.what()).c_str());
        }
    });
    knitpy::registerPatternAndMesh(m);
    knitpy::registerCurves(m);
    knitpy::registerScene(m);
    knitpy::registerExport(m);
}
