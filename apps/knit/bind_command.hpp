// bind_command.hpp — `knit bind`: bind the scene on its rest mesh once and save it as a bound
// scene file (knit/bound_scene.hpp) that `knit animate --bound` loads on any machine.
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "scene_flags.hpp"

namespace knit::cli {

struct BindCommand {
    CLI::App* command = nullptr;  // set by addBindCommand
    SceneFlags scene;             // --mesh is the rest pose
    std::string output = "garment.knitbind";
};

void addBindCommand(CLI::App& app, BindCommand& bind);

// Binds, writes the file, prints a summary on stdout. Throws knit::Error.
int runBind(const BindCommand& bind);

// --bound FILE: the scene flags that the file fixes are refused beside it (the file holds the
// pattern, placement, binding and ply settings it was bound with); throws knit::Error naming the flag.
void refuseSceneFlagsWithBound(const CLI::App& command);

}  // namespace knit::cli
