// rest_pose.cpp — the rest-pose scene and frame scenes of the animation commands.
#include "rest_pose.hpp"

namespace knit::cli {

Scene bindRestPose(SceneOptions options, const std::string& restMesh) {
    options.mesh = restMesh;
    options.buildPlies = false;
    return buildScene(options);
}

Scene frameScene(const Animator& animator, const BaseMesh& frameMesh, const AnimationFrame& frame) {
    SceneParts parts;
    parts.mesh = frameMesh;
    parts.normals = frame.meshNormals;
    parts.yarnRadius = animator.rest().yarnRadius();
    parts.grid = animator.rest().grid();
    parts.binding = animator.rest().binding();
    parts.yarns = frame.yarns;
    // The chart's colours stay with their stitches: the yarn points keep the rest layout (the
    // plies carry theirs from the animator's ply layout).
    if (parts.yarns.colour.empty()) parts.yarns.colour = animator.rest().yarns().colour;
    if (animator.options().plies) parts.plies = frame.plies;
    return Scene::fromParts(std::move(parts));
}

}  // namespace knit::cli
