// rest_pose.hpp — what `knit animate` and `knit build --rest` share: the scene bound on the rest
// pose (no plies: the Animator makes them per frame) and an evaluated frame as a Scene to export.
#pragma once
#include <string>

#include "knit/animation.hpp"
#include "knit/scene.hpp"

namespace knit::cli {

// The scene of `options` bound on `restMesh` (a mesh file), without plies.
Scene bindRestPose(SceneOptions options, const std::string& restMesh);

// An evaluated frame (its mesh, yarns and plies) as a Scene for exportScene: the same curves
// `knit animate` writes for that frame.
Scene frameScene(const Animator& animator, const BaseMesh& frameMesh, const AnimationFrame& frame);

}  // namespace knit::cli
