// animate_command.hpp — `knit animate`: bind once on the rest pose, evaluate every frame of a
// mesh sequence, write a point cache (.pc2 / .mdd + topology .obj), one animated .glb or one file per frame.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "knit/animation.hpp"
#include "knit/export.hpp"
#include "scene_flags.hpp"

namespace knit::cli {

struct AnimateCommand {
    CLI::App* command = nullptr;  // set by addAnimateCommand
    SceneFlags scene;
    ExportOptions exportOptions;  // -o: out.pc2, out.mdd or a pattern such as out_%04d.glb
    std::string frames;           // --frames: printf pattern or folder
    std::string rest;             // --rest: the rest pose (default: the first frame)
    std::string bound;            // --bound: a bound scene file (`knit bind`) instead of binding
    FrameRange range;             // --first --last --step
    double fps = 24;              // --fps: MDD frame times
    bool linear = false;          // --linear: animated .glb weights blend (LINEAR) instead of STEP
    bool noStats = false;         // --no-stats: no maxStretch / minYarnDistance in the report
    std::string report;           // --report path; empty = none
    int threads = 0;              // --threads: worker threads (0: every core)
};

void addAnimateCommand(CLI::App& app, AnimateCommand& animate);

// Runs the animation; prints a summary on stdout, progress on stderr. Throws knit::Error.
int runAnimate(const AnimateCommand& animate);

}  // namespace knit::cli
