// The scene flags of `knit build` and `knit render` (see scene_flags.hpp).
#include "scene_flags.hpp"

#include <cstdio>

#include "choice.hpp"
#include "strain_table_command.hpp"
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"

namespace knit::cli {

const char* const kSceneHelp = R"(Scene: a pattern (.pyp file, .json curves file, or built-in name) tiled over a
base mesh (.obj/.ply/.off/.gltf/.glb with UVs, or built-in name). Alignment: with --repeats U V, pattern
point (x, y) of tile (i, j) lands at uv ((x + i px)/(U px), (y + j py)/(V py)); the pattern's
origin is uv (0,0). Heights and radii scale with the period. Without --repeats the pattern keeps
its physical size (the mesh's area-weighted metres per UV unit). --gauge 22x30/10cm sets the size
of a stitch instead (a chart pattern knows its stitches and rows per period; other patterns: one
period is one stitch by one row).)";

namespace {

std::string commaList(const std::vector<std::string>& names) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    return list;
}

}  // namespace

void addSceneFlags(CLI::App& cmd, SceneFlags& f) {
    const Choices<Twist> twists = {{"S", Twist::S}, {"Z", Twist::Z}};
    cmd.add_option("--pattern", f.scene.pattern,
                   "Pattern file (.pyp, .json curves) or built-in: " + commaList(builtinPatternNames()))
        ->capture_default_str();
    cmd.add_option("--mesh", f.scene.mesh,
                   "Base mesh file (.obj, .ply, .off, .gltf, .glb; needs UVs; glTF v is flipped to OBJ convention) or "
                   "built-in: " +
                       commaList(builtinMeshNames()))
        ->capture_default_str();
    cmd.add_option("--repeats", f.repeats, "Pattern periods across u in [0,1] and v in [0,1] (default: physical size)")
        ->expected(2);
    cmd.add_option("--gauge", f.gauge,
                   "Stitches x rows per length, e.g. 22x30/10cm (units mm, cm, m, in); instead of --repeats");
    cmd.add_option("--mesh-res", f.meshRes, "Quads per side of built-in meshes (default 32)")
        ->check(CLI::Range(1, 4096));
    cmd.add_option("--plies", f.scene.plies.count, "Plies per yarn")->capture_default_str()->check(CLI::Range(1, 16));
    cmd.add_option("--ply-pitch", f.scene.plies.pitch, "Length of one ply turn in metres (0: 6 yarn radii)")
        ->capture_default_str();
    cmd.add_option("--ply-radius", f.scene.plies.plyRadius, "Ply radius in metres (0: touching plies filling the yarn)")
        ->capture_default_str();
    cmd.add_option("--ply-center-radius", f.scene.plies.centerRadius,
                   "Distance of ply centres from the yarn centre (0: auto)")
        ->capture_default_str();
    addChoice(cmd, "--twist", f.scene.plies.twist, twists, "Ply twist direction")
        ->default_str(wordOf(twists, f.scene.plies.twist));
    cmd.add_option("--samples-per-turn", f.scene.plies.samplesPerTurn, "Centreline samples per ply turn")
        ->capture_default_str();
    cmd.add_option("--clamp-tolerance", f.scene.bind.clampTolerance,
                   "Points outside the UV region within this many yarn radii are clamped onto the closest triangle; "
                   "farther ones are cut")
        ->capture_default_str();
    cmd.add_option("--weld-tolerance", f.scene.bind.weldTolerance,
                   "Cut ends meeting again across a seam within this many yarn radii are welded")
        ->capture_default_str();
    cmd.add_flag("--no-weld", f.noWeld, "Do not weld yarn ends across UV seams");
    cmd.add_option("--max-memory", f.maxMemory,
                   "Memory budget (8G, 512M, ...; default min(4G, half the physical memory)): steps estimated to need "
                   "more are refused");
    cmd.add_option(
           "--deform", f.deform,
           "How yarns follow a strained surface: none (mapped with it, stretching like rubber) or strain (they "
           "slide and bend as the pattern's strain table says; without --strain-table the pattern's table from "
           "the cache, made on first use). "
           "Default: strain where the pattern's table is at hand (--strain-table, cached, or made in under a "
           "minute: cell vertices x samples <= 32 x 729), else none with a note naming the command that makes it "
           "(docs/deformation.md)")
        ->check(CLI::IsMember({"none", "strain"}));
    cmd.add_option(
        "--strain-table", f.strainTable,
        "Strain table of the pattern: a file made by `knit strain-table` (T.npy) or a MADYPG sxsasy/ folder");
    cmd.add_flag(
        "-q,--quiet", f.quiet,
        "Quiet: print nothing but errors and warnings (no progress on stderr, no summary or report on stdout)");
}

namespace {

// The deform mode and its table (knit::decideDeform: the same rule as Python's and Blender's
// default), and a line on stderr saying which mode runs and why.
void resolveDeform(const SceneFlags& f, SceneOptions& o) {
    const DeformChoice choice =
        f.deform == "none" ? DeformChoice::None : (f.deform == "strain" ? DeformChoice::Strain : DeformChoice::Auto);
    if (choice == DeformChoice::None) return;  // asked for: no note
    std::shared_ptr<const StrainTable> given;
    if (!f.strainTable.empty()) given = std::make_shared<const StrainTable>(loadStrainTable(f.strainTable));
    const Pattern pattern = given ? Pattern{} : loadPatternFileOrName(o.pattern);
    StrainTableStats stats;
    const DeformDecision d = decideDeform(
        pattern, choice, given, [&] { return makeTableWithProgress(pattern, StrainTableOptions{}, f.quiet, stats); });
    o.deform = d.deform;
    if (f.quiet || given) return;
    const CachedStrainTable& c = d.cached;
    switch (d.deform.reason) {
        case DeformReason::Cached:
            std::fprintf(stderr, "knit: deform: strain (the pattern's strain table from the cache: %s)\n",
                         c.path.c_str());
            break;
        case DeformReason::Made:
            if (!c.path.empty())
                std::fprintf(stderr,
                             "knit: deform: strain (made the pattern's strain table in %.1f s and cached it: %s; later "
                             "runs read it)\n",
                             c.seconds, c.path.c_str());
            else
                std::fprintf(stderr,
                             "knit: deform: strain (made the pattern's strain table in %.1f s; no cache folder to keep "
                             "it: `knit strain-table --pattern %s -o T.npy` makes one to reuse with --strain-table "
                             "T.npy)\n",
                             c.seconds, o.pattern.c_str());
            break;
        case DeformReason::TooSlowToMake:
            std::fprintf(stderr,
                         "knit: deform: none (yarns follow the surface geometrically): the pattern has no strain table "
                         "yet and making one takes about %.0f s; `knit strain-table --pattern %s -o T.npy` makes it "
                         "(then --strain-table T.npy), or --deform strain makes and caches it on this run\n",
                         d.deform.tableSeconds, o.pattern.c_str());
            break;
        case DeformReason::CannotMake:
            std::fprintf(stderr,
                         "knit: deform: none (yarns follow the surface geometrically): no strain table can be made "
                         "for this pattern (%s)\n",
                         d.whyNot.c_str());
            break;
        default: break;
    }
}

}  // namespace

SceneOptions resolveScene(const SceneFlags& f) {
    SceneOptions o = f.scene;
    if (!f.repeats.empty()) o.placement.repeats = {f.repeats[0], f.repeats[1]};
    if (!f.gauge.empty()) {
        if (!f.repeats.empty()) throw Error("--gauge and --repeats are mutually exclusive (a gauge sets the repeats)");
        o.placement.gauge = parseGauge(f.gauge);
    }
    if (f.meshRes > 0) o.meshOptions.resU = o.meshOptions.resV = f.meshRes;
    o.bind.weld = !f.noWeld;
    if (!f.maxMemory.empty()) o.budget = MemoryBudget(parseMemorySize(f.maxMemory));
    resolveDeform(f, o);
    if (!f.quiet)
        o.progress = [](const std::string& stage, int index, int total) {
            std::fprintf(stderr, "[%d/%d] %s\n", index + 1, total, stage.c_str());
        };
    return o;
}

}  // namespace knit::cli
