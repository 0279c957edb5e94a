// python/src/ply_options.hpp — knit.PlyOptions-style keyword arguments -> knit::PlyOptions.
#pragma once
#include <string>

#include "knit/plies.hpp"

namespace knitpy {

// The ply keyword arguments shared by build_scene, Scene.plies and make_plies.
struct PlyArgs {
    int count = 2;
    double pitch = 0;         // 0: 6 yarn radii
    std::string twist = "S";  // "S" or "Z"
    double plyRadius = 0;     // 0: touching plies that fill the yarn
    double centerRadius = 0;
    int samplesPerTurn = 12;
};

// Throws knit::Error naming the argument for a twist other than "S" / "Z"; the rest is checked
// by knit::resolvePlyOptions where the options are used.
knit::PlyOptions toPlyOptions(const PlyArgs& args, double yarnRadius);

}  // namespace knitpy
