// `knit bind`: the scene bound on the rest mesh (as `knit animate` binds it) -> a bound scene file.
#include "bind_command.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "knit/bound_scene.hpp"
#include "knit/error.hpp"
#include "knit/output_file.hpp"
#include "path_collisions.hpp"
#include "report.hpp"
#include "rest_pose.hpp"

namespace knit::cli {
namespace {

// The settings the scene is bound with, for provenance (the file itself holds their results).
nlohmann::json settingsJson(const SceneOptions& o, const Scene& rest) {
    nlohmann::json j = {
        {"writer", "knit bind"},
        {"pattern", o.pattern},
        {"mesh", o.mesh},
        {"repeats", {o.placement.repeats.x, o.placement.repeats.y}},
        {"plies",
         {{"count", o.plies.count},
          {"pitch", o.plies.pitch},
          {"plyRadius", o.plies.plyRadius},
          {"centerRadius", o.plies.centerRadius},
          {"twist", o.plies.twist == Twist::S ? "S" : "Z"},
          {"samplesPerTurn", o.plies.samplesPerTurn}}},
        {"bind",
         {{"clampTolerance", o.bind.clampTolerance}, {"weldTolerance", o.bind.weldTolerance}, {"weld", o.bind.weld}}}};
    j["deform"] = {{"mode", rest.deformer() ? "strain" : "none"}, {"why", deformWhy(rest.deformOptions())}};
    if (rest.deformer()) j["deform"]["strain_table"] = rest.deformer()->table().source;
    if (o.placement.gauge)
        j["gauge"] = {{"stitches", o.placement.gauge->stitches},
                      {"rows", o.placement.gauge->rows},
                      {"length", o.placement.gauge->length}};
    return j;
}

// The scene flags a bound scene file fixes.
const char* const kBoundSceneFlags[] = {"--pattern",
                                        "--mesh",
                                        "--repeats",
                                        "--gauge",
                                        "--mesh-res",
                                        "--plies",
                                        "--ply-pitch",
                                        "--ply-radius",
                                        "--ply-center-radius",
                                        "--twist",
                                        "--samples-per-turn",
                                        "--clamp-tolerance",
                                        "--weld-tolerance",
                                        "--no-weld",
                                        "--deform",
                                        "--strain-table",
                                        "--rest"};

}  // namespace

void addBindCommand(CLI::App& app, BindCommand& b) {
    b.command = app.add_subcommand(
        "bind", "Bind the scene on its rest mesh once and save it (a bound scene file for `animate --bound`)");
    addSceneFlags(*b.command, b.scene);
    b.command->add_option("-o,--output", b.output, "The bound scene file to write")->capture_default_str();
    b.command->footer(kSceneHelp);
}

int runBind(const BindCommand& b) {
    // Step 1: fail before long work.
    requireWritableFolder(b.output, "bound scene");
    refuseCollidingPaths({{"--mesh", b.scene.scene.mesh}, {"--pattern", b.scene.scene.pattern}}, {{"-o", b.output}});
    // After the collisions (an output onto an input is the more useful message).
    refuseOtherFormatName("-o", b.output, "a bound scene", ".knitbind");
    // Step 2: bind on the rest mesh, as `knit animate` does, with the deformation it would use
    // (--deform, --strain-table, else the default: knit::decideDeform through resolveScene). The
    // file records it, with a strain table whole, so `animate --bound` deforms as `animate` does.
    const auto t0 = std::chrono::steady_clock::now();
    const SceneOptions options = resolveScene(b.scene);
    const Scene rest = bindRestPose(options, options.mesh);
    printWarnings(rest);
    const double bindSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Step 3: the file.
    BoundSceneInfo info;
    info.settings = settingsJson(options, rest).dump();
    writeBoundScene(b.output, rest, info, options.budget);
    if (b.scene.quiet) return 0;  // -q: only errors and warnings
    const std::string deform =
        rest.deformer() ? "strain, its table embedded: " + rest.deformer()->table().source : std::string("none");
    std::printf("bound %zu yarn vertices of %zu yarns on %zu triangles in %.3f s (deform: %s): wrote %s (%ju bytes)\n",
                rest.binding().vertexCount(), rest.binding().yarnCount(), rest.mesh().faceCount(), bindSeconds,
                deform.c_str(), b.output.c_str(), static_cast<uintmax_t>(std::filesystem::file_size(b.output)));
    return 0;
}

void refuseSceneFlagsWithBound(const CLI::App& command) {
    for (const char* flag : kBoundSceneFlags)
        if (command.get_option_no_throw(flag) != nullptr && command.count(flag) > 0)
            throw Error(std::string(flag) +
                        " cannot be given with --bound: the bound scene file holds the scene it was bound with");
}

}  // namespace knit::cli
