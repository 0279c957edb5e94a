// The export flags of `knit build` (see export_flags.hpp).
#include "export_flags.hpp"

#include "choice.hpp"

namespace knit::cli {

void addExportFlags(CLI::App& command, ExportOptions& options) {
    // Enum options as checked words (shown as TEXT:{...}); any case is read as the listed spelling.
    const Choices<ExportWhat> what = {
        {"yarns", ExportWhat::Yarns}, {"plies", ExportWhat::Plies}, {"tubes", ExportWhat::Tubes}};
    const Choices<TubeSource> tubesOf = {
        {"auto", TubeSource::Auto}, {"plies", TubeSource::Plies}, {"yarns", TubeSource::Yarns}};
    addChoice(command, "--export", options.what, what,
              "What to write: yarn centrelines, ply curves, or swept tube meshes", Spelling::AnyCase)
        ->default_str(wordOf(what, options.what))
        ->group("Export");
    addChoice(command, "--tubes-of", options.tubesOf, tubesOf,
              "Curves swept by --export tubes (auto: plies when built, else yarns)", Spelling::AnyCase)
        ->default_str(wordOf(tubesOf, options.tubesOf))
        ->group("Export");
    command.add_option("--sides", options.sides, "Tube ring vertices")
        ->check(CLI::Range(3, 1024))
        ->capture_default_str()
        ->group("Export");
    command
        .add_flag_function(
            "--no-caps", [&options](int64_t) { options.caps = false; }, "Leave open tube ends open")
        ->group("Export");
    CLI::Option* draco =
        command.add_flag("--draco", options.draco, "KHR_draco_mesh_compression for tube meshes (.glb/.gltf)")
            ->group("Export");
    command.add_option("--draco-bits", options.dracoBits, "Draco position quantization bits")
        ->check(CLI::Range(1, 30))
        ->capture_default_str()
        ->needs(draco)
        ->group("Export");
    command.add_option("--draco-level", options.dracoLevel, "Draco compression level (0 fast .. 10 small)")
        ->check(CLI::Range(0, 10))
        ->capture_default_str()
        ->needs(draco)
        ->group("Export");
    command
        .add_flag("--quantize", options.quantize,
                  "KHR_mesh_quantization: int16 positions/normals/tangents for tube meshes (.glb/.gltf)")
        ->excludes(draco)
        ->group("Export");
    command
        .add_flag("--meshopt", options.meshopt,
                  "EXT_meshopt_compression of tube meshes (.glb/.gltf; with --quantize: smallest files)")
        ->excludes(draco)
        ->group("Export");
    command.add_flag("--yarn-colors", options.yarnColors, "COLOR_0 per yarn on tube meshes (glTF)")->group("Export");
    command
        .add_option("--chunk-vertices", options.chunkVertices,
                    "Streaming chunk size: tube vertices (or curve points) per chunk / glTF node; "
                    "0 = auto (1048576, 262144 with --draco, 65535 with --quantize/--meshopt)")
        ->check(CLI::Range(size_t(0), size_t(1) << 31))
        ->capture_default_str()
        ->group("Export");
    command.add_flag("--pretty-json", options.prettyJson, "Indent the glTF JSON")->group("Export");
}

ExportOptions stagedExport(const ExportOptions& flags, const MemoryBudget& budget, OutputTransaction& outputs) {
    ExportOptions o = flags;
    o.path = outputs.stage(flags.path);
    o.budget = budget;
    return o;
}

}  // namespace knit::cli
