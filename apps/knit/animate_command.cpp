// `knit animate`: frames -> bind the rest pose once -> per frame: read, evaluate, write ->
// commit the outputs -> report. Per-frame outputs are written as they come; a point cache is
// streamed into a temporary file renamed at the end, so an error or SIGINT / SIGTERM leaves no
// partial cache.
#include "animate_command.hpp"

#include "animated_glb.hpp"
#include "bind_command.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "export_flags.hpp"
#include "frame_sink.hpp"
#include "interrupt.hpp"
#include "knit/bound_scene.hpp"
#include "knit/cache.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/output_transaction.hpp"
#include "path_collisions.hpp"
#include "report.hpp"
#include "rest_pose.hpp"
#include "util/platform.hpp"

namespace knit::cli {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

bool hasFramePattern(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const size_t p = name.find('%');
    return p != std::string::npos && name.find('d', p) != std::string::npos;
}

// A per-frame output pattern split around its one integer conversion (%d, %04d) in the file
// name; false when the name holds another '%' or a second conversion (snprintf over such a name
// would read arguments that were never passed), or a width beyond 9 digits.
bool splitFramePattern(const std::string& path, std::string& head, std::string& spec, std::string& tail) {
    const std::filesystem::path p(path);
    const std::string name = p.filename().string();
    const size_t at = name.find('%');
    if (at == std::string::npos) return false;
    size_t end = at + 1;
    while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
    if (end >= name.size() || name[end] != 'd' || end - at - 1 > 2 || name.find('%', end) != std::string::npos)
        return false;
    head = (p.parent_path() / name.substr(0, at)).string();
    spec = name.substr(at, end + 1 - at);
    tail = name.substr(end + 1);
    return true;
}

std::string framePath(const std::string& pattern, int number) {
    std::string head, spec, tail;
    if (!splitFramePattern(pattern, head, spec, tail)) return pattern;  // refused by checkOutput before
    char digits[32];
    std::snprintf(digits, sizeof digits, spec.c_str(), number);
    return head + digits + tail;
}

// The constant topology written beside a point cache: same stem, .obj.
std::string topologyPathOf(const std::string& cache) {
    return std::filesystem::path(cache).replace_extension(".obj").string();
}

// The points a cache holds: the ply curves, or the yarn centrelines with --export yarns.
const Polylines& cacheCurves(const AnimationFrame& f, bool plies) { return plies ? f.plies.curves : f.yarns.curves; }

class CacheSink : public FrameSink {
public:
    CacheSink(const std::string& path, const Animator& animator, const FrameSequence& seq, double fps, int step)
        : topologyPath_(topologyPathOf(path)), plies_(animator.options().plies) {
        CacheFormat format = CacheFormat::Pc2;
        cacheFormatOf(path, format);
        topologyHeader_ = cacheTopologyHeader(format, seq.frame(0).number, seq.frames().back().number, step, fps);
        CacheInfo info;
        // (the binding's vertex count: the yarns' points, without evaluating a loaded scene's rest yarns)
        info.points = plies_ ? animator.plyPointCount() : animator.rest().binding().vertexCount();
        info.frames = seq.size();
        info.startFrame = seq.frame(0).number;
        info.step = step;  // PC2: the chunks of a farm run record their frame range (knit cache merge)
        info.fps = fps;
        cache_ = std::make_unique<PointCacheWriter>(path, info);
    }
    void write(int, const BaseMesh&, const AnimationFrame& frame) override {
        const Polylines& c = cacheCurves(frame, plies_);
        if (first_.curveCount() == 0) first_ = c;  // the topology, with the first frame's points
        cache_->writeFrame(c.points);
    }
    void commit() override {
        writeSegmentObj(topologyPath_, first_, topologyHeader_);
        cache_->commit();
    }

private:
    std::string topologyPath_, topologyHeader_;
    bool plies_;
    std::unique_ptr<PointCacheWriter> cache_;
    Polylines first_;
};

class FilesSink : public FrameSink {
public:
    FilesSink(const Animator& animator, const ExportOptions& options) : animator_(animator), options_(options) {}
    void write(int number, const BaseMesh& mesh, const AnimationFrame& frame) override {
        ExportOptions o = options_;
        o.path = framePath(options_.path, number);
        exportScene(frameScene(animator_, mesh, frame), o);
    }
    void commit() override {}

private:
    const Animator& animator_;
    ExportOptions options_;
};

// Step: the output kind from -o, refused before any work when unsupported.
void checkOutput(const ExportOptions& o) {
    CacheFormat format;
    if (cacheFormatOf(o.path, format)) {
        if (o.what == ExportWhat::Tubes)
            throw Error("-o '" + o.path +
                        "': point caches hold curve points; --export tubes needs per-frame files (e.g. out_%04d.glb)");
        requireWritableFolder(o.path, "point cache");
        return;
    }
    if (isAnimatedGlb(o.path, hasFramePattern(o.path))) {
        validateExportOptions(o);
        checkAnimatedGlbOptions(o);
        requireWritableFolder(o.path, "animated glTF");
        return;
    }
    std::string head, spec, tail;
    if (hasFramePattern(o.path) && !splitFramePattern(o.path, head, spec, tail))
        throw Error("-o '" + o.path +
                    "': a per-frame pattern holds one integer conversion in its file name (%d, or %04d for four "
                    "digits; a width of at most 2 digits) and no other '%'");
    if (!hasFramePattern(o.path))
        throw Error("-o '" + o.path +
                    "': give a point cache (out.pc2, out.mdd), one animated out.glb or a per-frame pattern such as "
                    "out_%04d." +
                    (util::lowerExtension(o.path).empty() ? std::string("glb") : util::lowerExtension(o.path)));
    validateExportOptions(o);
    requireWritableFolder(o.path);
}

// Step: outputs that would overwrite an input (a frame, --frames, --rest, --pattern) or each
// other (-o, the cache's topology .obj, a .gltf's buffer, --report), by file identity. The
// output kind is picked as runAnimate picks its sink; per-frame outputs are checked against the
// input frame of the same number and the other inputs.
void refuseAnimateCollisions(const AnimateCommand& a, const FrameSequence& seq) {
    const std::string& out = a.exportOptions.path;
    const std::vector<NamedPath> inputs = {
        {"--frames", a.frames}, {"--rest", a.rest}, {"--pattern", a.scene.scene.pattern}, {"--bound", a.bound}};
    CacheFormat format;
    const bool cache = cacheFormatOf(out, format);
    if (cache || !hasFramePattern(out)) {  // a point cache and its topology, or one animated .glb
        const std::string topology = cache ? topologyPathOf(out) : "";
        std::vector<NamedPath> frames = inputs;
        for (const FrameFile& f : seq.frames()) frames.push_back({"frame " + std::to_string(f.number), f.path});
        refuseCollidingPaths(frames,
                             {{"-o", out}, {"the point cache's topology file", topology}, {"--report", a.report}});
        return;
    }
    for (const FrameFile& f : seq.frames()) {
        const std::string frame = "frame " + std::to_string(f.number), file = framePath(out, f.number);
        std::vector<NamedPath> in = inputs;
        in.push_back({frame, f.path});
        refuseCollidingPaths(in, {{"-o (" + frame + ")", file},
                                  {"the glTF buffer of -o (" + frame + ")", gltfBufferOf(file)},
                                  {"--report", a.report}});
    }
}

struct FrameRecord {
    int number = 0;
    double seconds = 0;
    FrameStats stats;
    DeformStats deform;
};

struct StageTotals {
    double read = 0, write = 0;
    AnimationStageTimes evaluate;
    void add(const AnimationStageTimes& t) {
        evaluate.normals += t.normals;
        evaluate.evaluate += t.evaluate;
        evaluate.resample += t.resample;
        evaluate.plies += t.plies;
        evaluate.stats += t.stats;
    }
};

nlohmann::json distanceJson(double d) { return std::isfinite(d) ? nlohmann::json(d) : nlohmann::json(nullptr); }

nlohmann::json animateReport(double bindSeconds, const std::vector<FrameRecord>& frames, const StageTotals& s,
                             const Animator& animator) {
    const bool stats = animator.options().stats;
    std::vector<double> t;
    t.reserve(frames.size());
    for (const FrameRecord& f : frames) t.push_back(f.seconds);
    std::sort(t.begin(), t.end());
    nlohmann::json report = {{"bindSeconds", bindSeconds},
                             {"frameSeconds", {{"min", t.front()}, {"median", t[t.size() / 2]}, {"max", t.back()}}},
                             {"stageSeconds",
                              {{"read", s.read},
                               {"normals", s.evaluate.normals},
                               {"evaluate", s.evaluate.evaluate},
                               {"resample", s.evaluate.resample},
                               {"plies", s.evaluate.plies},
                               {"stats", s.evaluate.stats},
                               {"write", s.write}}},
                             {"peakMemoryBytes", util::peakResidentBytes()},
                             {"yarnVertices", animator.rest().binding().vertexCount()},
                             {"plyVertices", animator.plyPointCount()},
                             {"yarnRadius", animator.rest().yarnRadius()}};
    nlohmann::json& list = report["frames"] = nlohmann::json::array();
    for (const FrameRecord& f : frames) {
        list.push_back({{"frame", f.number}, {"seconds", f.seconds}});
        if (stats) {
            list.back()["maxStretch"] = f.stats.maxStretch;
            list.back()["minYarnDistance"] = distanceJson(f.stats.minYarnDistance);
            list.back()["yarnLengthRatio"] = f.stats.yarnLengthRatio;
        }
        if (animator.rest().deformer())
            list.back()["clampedFraction"] = f.deform.total ? double(f.deform.clamped) / double(f.deform.total) : 0.0;
    }
    if (const auto& d = animator.rest().deformer()) {
        const StrainTable& t = d->table();
        report["deform"] = {{"mode", "strain"},
                            {"strain_table", t.source},
                            {"samples", {t.axes[0].size(), t.axes[1].size(), t.axes[2].size()}}};
    } else {
        report["deform"] = {{"mode", "none"}};
    }
    const bool bound = animator.rest().animatorState() != nullptr;  // loaded from a bound scene file
    report["deform"]["why"] = bound ? "as bound (knit bind): " + deformWhy(animator.rest().deformOptions())
                                    : deformWhy(animator.rest().deformOptions());
    return report;
}

// Step: every frame read, evaluated and written; the per-frame records.
std::vector<FrameRecord> runFrames(const FrameSequence& seq, const Animator& animator, FrameSink& sink,
                                   StageTotals& totals, bool quiet, const InterruptGuard& interrupt) {
    AnimationFrame frame;
    std::vector<FrameRecord> records;
    for (size_t i = 0; i < seq.size(); ++i) {
        interrupt.check();
        const auto t0 = Clock::now();
        const BaseMesh mesh = seq.load(i, animator.rest().mesh());
        totals.read += since(t0);
        AnimationStageTimes times;
        animator.evaluate(mesh.positions, frame, &times);
        totals.add(times);
        const auto t1 = Clock::now();
        sink.write(seq.frame(i).number, mesh, frame);
        totals.write += since(t1);
        records.push_back({seq.frame(i).number, since(t0), frame.stats, frame.deform});
        if (!quiet && animator.options().stats)
            std::fprintf(
                stderr,
                "frame %d (%zu/%zu): %.3f s, max stretch %.4g, min yarn distance %.4g, yarn length ratio %.4g\n",
                seq.frame(i).number, i + 1, seq.size(), records.back().seconds, frame.stats.maxStretch,
                frame.stats.minYarnDistance, frame.stats.yarnLengthRatio);
        else if (!quiet)
            std::fprintf(stderr, "frame %d (%zu/%zu): %.3f s\n", seq.frame(i).number, i + 1, seq.size(),
                         records.back().seconds);
    }
    interrupt.check();
    return records;
}

}  // namespace

void addAnimateCommand(CLI::App& app, AnimateCommand& a) {
    a.exportOptions.path = "knit-anim.pc2";
    a.command = app.add_subcommand("animate", "Bind once on the rest pose; evaluate every frame of a mesh sequence");
    a.command
        ->add_option(
            "--frames", a.frames,
            "Mesh sequence: printf pattern (frames/frame_%04d.obj), folder of numbered meshes, or one glTF/GLB "
            "with morph-target or skinned animation (sampled at its keyframes, or at --fps)")
        ->required();
    a.command->add_option("--rest", a.rest, "Rest pose mesh that is bound (default: the first frame)");
    a.command->add_option("--bound", a.bound,
                          "Bound scene file (`knit bind`): load it instead of binding (no scene flags besides "
                          "--max-memory and -q)");
    // Frame numbers come from file names (digits, no sign): a negative one would read as "not set".
    a.command->add_option("--first", a.range.first, "First frame number (default: the smallest found)")
        ->check(CLI::Range(0, std::numeric_limits<int>::max()));
    a.command->add_option("--last", a.range.last, "Last frame number (default: the largest found)")
        ->check(CLI::Range(0, std::numeric_limits<int>::max()));
    a.command->add_option("--step", a.range.step, "Frame number step")->capture_default_str();
    a.command
        ->add_option("--fps", a.fps,
                     "Frames per second (MDD and animated .glb frame times; glTF input: sample at this rate)")
        ->capture_default_str();
    a.command->add_flag("--linear", a.linear,
                        "Animated .glb: LINEAR interpolation of the frame weights (a blend) instead of STEP");
    a.command->add_flag(
        "--no-stats", a.noStats,
        "Leave the per-frame maxStretch / minYarnDistance out of --report (they are computed only for a report; "
        "the distance search costs more than a frame's plies)");
    addSceneFlags(*a.command, a.scene);
    addExportFlags(*a.command, a.exportOptions);
    a.command
        ->add_option(
            "-o,--output", a.exportOptions.path,
            "out.pc2 / out.mdd (+ topology out.obj), one animated out.glb (morph targets) or a per-frame pattern "
            "out_%04d.glb|.obj|.bcc|.pbrt")
        ->capture_default_str();
    a.command->add_option("--report", a.report,
                          "Write a JSON report (bind and frame times, per-frame stretch and yarn distance)");
    a.command
        ->add_option("--threads", a.threads,
                     "Worker threads (0: every core; 1 per task when a farm or knit.distributed runs several "
                     "chunks on one machine)")
        ->capture_default_str()
        ->check(CLI::Range(0, 4096));
    a.command->footer(kSceneHelp);
}

int runAnimate(const AnimateCommand& a) {
    // Step 1: fail before long work: outputs, the sequence and its files.
    std::optional<tbb::global_control> threads;
    if (a.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(a.threads));
    checkOutput(a.exportOptions);
    checkReportPath(a.report);
    // NaN passes CLI11's range checks; a point cache ignores the rate, but a rate of 0, -24 or NaN is a typo.
    if (!(a.fps >= 1e-3 && a.fps <= 1e6)) {
        char got[32];
        std::snprintf(got, sizeof got, "%g", a.fps);
        throw Error(std::string("--fps must be a frame rate of 0.001 to 1e6 frames per second, got ") + got);
    }
    FrameRange range = a.range;
    if (a.command != nullptr && a.command->count("--fps") > 0) range.fps = a.fps;  // glTF input: sample at --fps
    const FrameSequence seq(a.frames, range);
    refuseAnimateCollisions(a, seq);
    // Step 2: bind once on the rest pose, or load the scene bound by `knit bind`.
    if (!a.bound.empty() && a.command != nullptr) refuseSceneFlagsWithBound(*a.command);
    const auto t0 = Clock::now();
    SceneFlags flags = a.scene;
    // A bound scene file carries its deformation (and strain table): nothing is decided here.
    if (!a.bound.empty()) flags.deform = "none";
    const SceneOptions sceneOptions = resolveScene(flags);
    const Scene rest = a.bound.empty() ? bindRestPose(sceneOptions, a.rest.empty() ? seq.frame(0).path : a.rest)
                                       : readBoundScene(a.bound, sceneOptions.budget).scene;
    printWarnings(rest);
    // The rest pose sets every frame's curves, radii and ply pitch: refuse an empty output or
    // radii beyond float32 now (each frame's coordinates are range-checked as its mesh is read).
    checkSceneExport(rest, a.exportOptions);
    AnimatorOptions ao;
    ao.budget = sceneOptions.budget;
    ao.plies = a.exportOptions.what != ExportWhat::Yarns;
    // The statistics go into the report only: without one they are not computed (the distance
    // search costs more than a frame's plies).
    ao.stats = !a.noStats && !a.report.empty();
    ao.budget = sceneOptions.budget;  // --max-memory: the plies per frame
    const Animator animator(rest, ao);
    const double bindSeconds = since(t0);
    // Step 3: the frames, streamed into staged outputs (existing files stay unchanged until the end).
    OutputTransaction outputs;
    const ExportOptions staged = stagedExport(a.exportOptions, sceneOptions.budget, outputs);
    // SIGINT / SIGTERM from here on set a flag the frame loop checks, so the run unwinds (and the
    // staging folder goes) with "interrupted by signal N". Installed after the staging folder is
    // registered (that installs the handler removing temporaries, which this one then replaces and
    // restores) and before the sink creates the first temporary file: a signal seen while that
    // file exists always takes this path (before, the guard came only with the frame loop, after
    // the cache file was created, and a signal in between ended the run by the signal).
    const InterruptGuard interrupt;
    CacheFormat format;
    std::unique_ptr<FrameSink> sink;
    if (cacheFormatOf(staged.path, format))
        sink = std::make_unique<CacheSink>(staged.path, animator, seq, a.fps, range.step);
    else if (isAnimatedGlb(staged.path, hasFramePattern(staged.path)))
        sink = makeAnimatedGlbSink(animator, seq.size(), staged, {a.fps, a.linear}, sceneOptions.budget);
    else sink = std::make_unique<FilesSink>(animator, staged);
    StageTotals totals;
    const std::vector<FrameRecord> frames =
        outputs.run([&] { return runFrames(seq, animator, *sink, totals, a.scene.quiet, interrupt); });
    outputs.run([&] { sink->commit(); });
    // Step 4: the report; then every output is committed together; the summary.
    if (!a.report.empty())
        outputs.run(
            [&] { writeReport(outputs.stage(a.report), animateReport(bindSeconds, frames, totals, animator)); });
    outputs.run([&] {
        interrupt.check();  // a signal during the last writes: nothing is committed
        outputs.commit();
    });
    if (a.scene.quiet) return 0;  // -q: only errors and warnings
    std::printf("animated %zu frames (%zu yarn vertices, %zu ply vertices per frame): %s %.3f s, wrote %s\n",
                frames.size(), rest.binding().vertexCount(), animator.plyPointCount(),
                a.bound.empty() ? "bind" : "load", bindSeconds, a.exportOptions.path.c_str());
    return 0;
}

}  // namespace knit::cli
