// fit_command.hpp — `knit fit`: fit the ply material to a front-lit and a back-lit photograph of
// the fabric; writes the material JSON (`knit render --material` reads it) and a report with the
// fitted renders beside it.
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "knit/fit.hpp"
#include "scene_flags.hpp"
#include "view_flags.hpp"

namespace knit::cli {

struct FitCommand {
    CLI::App* command = nullptr;  // set by addFitCommand
    SceneFlags scene;
    FitOptions fit;
    std::string front, back, mask;  // photographs (PNG sRGB / EXR linear) and optional mask
    std::string output;             // -o: material JSON
    std::string fitList = "kR,kTT,body-albedo";
    std::vector<std::string> bounds;    // --bound NAME=LO:HI
    std::string report;                 // --report path; empty = none
    ViewFlags view;                     // --eye --target --up (--fov is the render's)
    int viewWidth = 0, viewHeight = 0;  // unused: the photographs fix the image size
};

// Registers the subcommand: the scene flags and the render flags of `knit render` (without the
// image-size, light and output flags: the photographs fix the size, both lights are rendered).
void addFitCommand(CLI::App& app, FitCommand& fit);

// Reads the photographs, builds the scene, fits, writes the material (and the report). Exit 0 also
// when the fit is poor (a warning on stderr says so); throws knit::Error on bad input.
int runFit(const FitCommand& fit);

}  // namespace knit::cli
