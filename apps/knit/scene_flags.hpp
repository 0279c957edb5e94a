// scene_flags.hpp — the scene flags `knit build` and `knit render` share (pattern, mesh,
// placement, plies, binding) and how they become knit::SceneOptions.
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "knit/scene.hpp"

namespace knit::cli {

// How a pattern lands on the mesh: the footer of `knit --help`, `knit build --help` and
// `knit render --help`.
extern const char* const kSceneHelp;

// What the flags fill in; resolveScene turns it into the scene options.
struct SceneFlags {
    SceneOptions scene;
    std::vector<double> repeats;  // empty, or U V
    std::string gauge;            // empty, or STITCHES x ROWS / LENGTH
    int meshRes = 0;              // 0: the built-in meshes' default
    bool noWeld = false;
    bool quiet = false;
    std::string maxMemory;    // empty: MemoryBudget's default
    std::string deform;       // empty (knit::decideDeform's Auto), "none" or "strain"
    std::string strainTable;  // empty, or a table file / MADYPG sxsasy/ folder
};

// Registers --pattern --mesh --repeats --gauge --mesh-res --plies --ply-pitch --ply-radius
// --ply-center-radius --twist --samples-per-turn --clamp-tolerance --weld-tolerance --no-weld
// --max-memory --deform --strain-table -q.
void addSceneFlags(CLI::App& command, SceneFlags& flags);

// The scene options the parsed flags ask for (with stage progress on stderr unless --quiet).
SceneOptions resolveScene(const SceneFlags& flags);

}  // namespace knit::cli
