// knit/animation.hpp — bind once on the rest pose, evaluate every frame of a mesh sequence.
//
// A cloth simulation exported as a mesh sequence (same connectivity and UVs in every frame) is
// read frame by frame (FrameSequence); the yarns are bound once on the rest pose (a Scene) and
// an Animator evaluates them on each frame's positions. What is fixed at bind time, so that the
// output has the same points in the same order on every frame (point caches stay valid) and
// nothing swims, flips or pops:
//  * the binding (triangle, barycentrics, height per yarn vertex);
//  * the resampling of every yarn centreline: which points are kept and how many pieces each
//    segment is split into (ResampleLayout), decided on the rest pose;
//  * the ply twist phase: theta = +-2 pi s / pitch with s the rest arc length of the resampled
//    centreline and the rest pitch (closed yarns: a whole number of turns at rest), so the twist
//    moves with the yarn material when the yarn stretches;
//  * the frame seed: each yarn's first ply frame on the rest pose, with the frame of the
//    triangle its first point is bound to. Per frame, that triangle's rotation since the rest
//    pose carries the rest frame along and it is parallel-transported (minimal rotation) onto
//    the frame's first tangent, then along the yarn by rotation-minimizing frames: plies turn
//    with the surface and do not flip where the yarn's tangent passes through the surface normal
//    (the old per-frame seed, the projected surface normal, is undefined there). Transported
//    from the rest pose, not the previous frame, so a frame's plies do not depend on the frames
//    before it: frame k equals a single evaluation on mesh k (`knit build --rest REST --mesh
//    FRAME_k`).
// Per frame only: vertex normals, the binding evaluation, resampling with the fixed layout, the
// frames and the helices, and the frame statistics; all into buffers reused across frames.
// The one animation path: `knit animate`, `knit build --rest`, the Python module's
// Scene.evaluate / evaluate_plies and the Blender add-on all evaluate through an Animator.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "knit/array_view.hpp"
#include "knit/base_mesh.hpp"
#include "knit/budget.hpp"
#include "knit/frames.hpp"
#include "knit/plies.hpp"
#include "knit/scene.hpp"

namespace knit {

// ---------------------------------------------------------------------------------------------
// Frame sequences (src/frame_sequence.cpp)

// Which frame numbers to read; -1 = from the files found (the smallest / largest number).
struct FrameRange {
    int first = -1;
    int last = -1;
    int step = 1;
    // A single animated glTF / GLB as the sequence: samples per second (0: the animation's
    // keyframe times). Frame numbers are 1, 2, ... in sample order.
    double fps = 0;
};

struct FrameFile {
    int number = 0;  // the frame number (from the file name)
    std::string path;
};

// A glTF / GLB with morph-target and / or skinned animation (src/gltf_animation.cpp), sampled
// as meshes with the file's constant connectivity and UVs. At a time t: the animation's channels
// (translation, rotation (slerp), scale, weights; LINEAR, STEP or CUBICSPLINE; clamped outside
// their keys) set the nodes' transforms and morph weights; each triangle primitive's POSITION
// plus its weighted morph-target POSITION deltas is skinned (JOINTS_n / WEIGHTS_n, the joints'
// world matrices times the inverse bind matrices, linear blend) or, without a skin, moved by its
// node's world transform. The rest pose is the un-animated file (loadMesh). Throws knit::Error
// naming the file and element (no animation, bad accessors, an out-of-range joint).
class GltfAnimation {
public:
    // Samples: the sorted union of the keyframe times of animation `animation`, or with
    // fps > 0 the times k / fps from 0 up to its last key.
    explicit GltfAnimation(const std::string& path, double fps = 0, size_t animation = 0);
    // The same from a .gltf / .glb held in memory (external files refused: no base folder);
    // `name` names it in messages.
    static std::unique_ptr<GltfAnimation> fromBytes(const std::string& bytes, const std::string& name, double fps = 0,
                                                    size_t animation = 0);
    ~GltfAnimation();
    GltfAnimation(const GltfAnimation&) = delete;
    GltfAnimation& operator=(const GltfAnimation&) = delete;

    const std::vector<double>& times() const;
    // The mesh at times()[i] (welded and UV-mapped like loadMesh of the file).
    BaseMesh sample(size_t i, const MeshLoadOptions& options = {}) const;

private:
    struct State;
    GltfAnimation(std::unique_ptr<State> state, double fps, size_t animation);
    std::unique_ptr<State> state_;
};

// True when `source` names one glTF / GLB file (not a pattern or folder): an animation.
bool isGltfAnimationSource(const std::string& source);

// The frames of a mesh sequence: a printf pattern with one integer conversion
// (`frames/frame_%04d.obj`) or a folder of numbered mesh files (.obj .ply .off .gltf .glb; the
// number is the last run of digits of the file name; one extension per folder), or one animated
// glTF / GLB file (GltfAnimation; frames 1..samples, range.fps). Every number
// first, first + step, ... up to last must exist: a missing one is an error naming the frame
// and the file. Throws knit::Error (bad pattern, empty folder, no frames in the range).
class FrameSequence {
public:
    explicit FrameSequence(const std::string& patternOrFolder, const FrameRange& range = {});

    size_t size() const { return frames_.size(); }
    const FrameFile& frame(size_t i) const { return frames_[i]; }
    const std::vector<FrameFile>& frames() const { return frames_; }

    // Reads frame i and checks it against the rest mesh (checkFrame); errors name the frame:
    // "frame 37 ('frames/frame_0037.obj'): ...".
    BaseMesh load(size_t i, const BaseMesh& rest) const;

private:
    std::vector<FrameFile> frames_;
    std::shared_ptr<const GltfAnimation> animation_;  // one animated glTF: frame k = sample k - 1
};

// Checks that `frame` has the rest mesh's connectivity and UVs: the same vertex, face and UV
// counts, the same face indices, the same UV indices and UV coordinates (exactly, as the
// files store them). Throws knit::Error "<name>: <what> (rest <a>, frame <b>)" naming the
// first differing element, e.g. "face 12 has vertices (3, 4, 9) but the rest mesh (3, 4, 8)".
void checkFrame(const BaseMesh& rest, const BaseMesh& frame, const std::string& name);

// ---------------------------------------------------------------------------------------------
// Evaluation per frame (src/animator.cpp, src/animation_stats.cpp)

struct AnimatorOptions {
    // Sweep the plies per frame (false: the yarns only, the binding evaluated; with stats false
    // too, no resampling at bind time or per frame).
    bool plies = true;
    bool stats = true;    // compute FrameStats per frame
    bool radial = false;  // with plies: also each ply point's radial direction (Plies::radial; a renderer needs it)
    // The arithmetic of the plies' frame transport per frame (FrameOptions::precision). Double
    // (the default) gives makePlies' frames bit for bit (a bound scene at rest renders as the
    // fresh one); Float32 is ~10% faster per ply vertex with AVX2, the normals within ~4e-5 of
    // the double path's on 200,000-point yarns (docs/memory-limit.md, tenth pass).
    FramePrecision framePrecision = FramePrecision::Double;
    // Apply the rest scene's strain deformer (SceneOptions::deform) on every frame; false: the
    // geometric mapping even for a scene built with a strain table.
    bool deform = true;
    // minYarnDistance looks for other yarns up to this distance (yarn diameters); a frame with
    // none that close reports +infinity.
    double distanceCutoff = 2.0;
    // Points of one yarn count as "different yarns" for minYarnDistance when they are farther
    // apart along the rest yarn than this (yarn diameters): a loop pressed onto its own yarn.
    double sameYarnSeparation = 4.0;
    // The ply points per frame (and the bind-time layout behind them) are estimated from the rest
    // yarns and the ply options before anything is resampled and refused over this budget: a
    // scene bound without plies (build_scene(build_plies=False), the Blender add-on) has not been
    // estimated for them, and a tiny ply pitch made the first evaluate_plies take all memory.
    MemoryBudget budget;
};

struct FrameStats {
    // Largest ratio of a yarn segment's length (between binding vertices) to its rest length.
    double maxStretch = 1.0;
    // Smallest distance between centreline points of different yarns (distinct yarns, or points
    // of one yarn more than sameYarnSeparation apart along it), in yarn diameters, measured on
    // the resampled centrelines (spacing pitch / samplesPerTurn); +infinity when none is within
    // distanceCutoff.
    double minYarnDistance = 0.0;
    // Total yarn length (between binding vertices) over the rest scene's.
    double yarnLengthRatio = 1.0;
};

// Wall time of the per-frame stages of one evaluate call.
struct AnimationStageTimes {
    double normals = 0, evaluate = 0, resample = 0, plies = 0, stats = 0;
};

// Reusable scratch of the yarn distance search.
struct DistanceScratch {
    std::vector<uint32_t> bucketStart, keys;
    struct Point {
        float x, y, z;  // position relative to the frame's first centre point
        uint32_t item;  // centre point index
        uint32_t yarn;  // its yarn
        float arc;      // its rest arc length along the yarn
    };
    std::vector<Point> packed;
    // The previous frame's closest pair (centreline point indices): its distance on the next
    // frame bounds the search there.
    bool hasPair = false;
    std::array<uint32_t, 2> pair{};
};

// One evaluated frame: the buffers an Animator fills, reused from frame to frame.
struct AnimationFrame {
    std::vector<glm::dvec3> meshNormals;  // vertex normals of the frame's mesh
    MappedYarns yarns;                    // the binding evaluated on the frame
    Polylines centres;                    // resampled centrelines (fixed layout; with plies or stats)
    Plies plies;                          // fixed layout, yarn-major, ply-minor (no radial)
    FrameStats stats;
    DeformStats deform;  // strain-aware deformation (when the rest scene has a deformer)
    DistanceScratch distance;
};

class Animator {
public:
    // Bind-time work on the rest scene (its mesh, binding and yarns; plyOptions resolved here
    // unless only the yarns are evaluated):
    // the resampling layouts, rest arc lengths, pitches and twist phases, frame seeds, rest
    // segment lengths (adopted, not recomputed, from a scene loaded from a bound scene file:
    // Scene::animatorState, whose largest arrays stay in the file's memory map, shared with the
    // scene; such an Animator never asks for the rest yarns, which the loaded scene then does not
    // evaluate). Keeps a
    // reference to `rest`, which must outlive the Animator. Throws knit::Error for bad ply
    // options, more than 2^32-1 ply points or plies over options.budget.
    explicit Animator(const Scene& rest, const AnimatorOptions& options = {});

    // Evaluates the frame whose mesh positions are `positions` (rest connectivity; checked:
    // the count, and finiteness) into `out`. Thread-parallel; allocates only on the first call
    // with a given `out`. `times` (optional) receives the stage times. Keeps no state between
    // calls besides `out`: one Animator may evaluate several frames concurrently from several
    // threads, each into its own `out`, with the results of sequential calls bit for bit (what
    // the Python module's Scene.evaluate / evaluate_plies rely on).
    void evaluate(const std::vector<glm::dvec3>& positions, AnimationFrame& out,
                  AnimationStageTimes* times = nullptr) const;

    const Scene& rest() const { return rest_; }
    const AnimatorOptions& options() const { return options_; }
    // Resolved; an Animator of the yarns alone (no plies, no statistics) neither resolves nor
    // checks them (the yarns do not depend on them) and gives the scene's options as they are.
    const PlyOptions& plyOptions() const { return generator_ ? generator_->options() : rest_.plyOptions(); }
    size_t plyPointCount() const { return plyTopology_.curves.offsets.back(); }
    // The constant ply curves (offsets, closed flags, yarn and ply of each curve; no points).
    const Plies& plyTopology() const { return plyTopology_; }

private:
    void resample(AnimationFrame& out) const;
    void sweep(const std::vector<glm::dvec3>& positions, AnimationFrame& out) const;

    const Scene& rest_;
    AnimatorOptions options_;
    std::optional<PlyGenerator> generator_;  // on the rest yarns: options, spacing, ply phases (plies or stats)
    // The bind-time decisions (resampling layouts, rest arc lengths, pitches, twist phases, frame
    // seeds): the rest scene's stored ones (a bound scene file's) or computed here; plies or stats.
    // (It also holds the stretch references: the rest length of each yarn segment and of all.)
    std::shared_ptr<const AnimatorBindState> bind_;
    // With a stored state: the rest yarns' offsets and closed flags alone (from the binding), which
    // the generator reads (curve frames need the closed flags), so the rest yarns stay unevaluated.
    // Shared: the generator keeps a reference, which a copy of the Animator keeps valid.
    std::shared_ptr<const MappedYarns> restTopology_;
    std::vector<size_t> plyOfYarn_;  // first ply point of each yarn
    Plies plyTopology_;
};

// The statistics of a frame (what Animator::evaluate computes when options.stats is set):
// `restSegment` per yarn vertex, `restArc` per centre point, `restLength` per yarn, `yarnRadius`
// (a centre point's yarn is the curve of `centres` it lies on).
// (restSegment and restArc: a std::vector, or a loaded scene's arrays in its file's map.)
double maxYarnStretch(const Polylines& yarns, ArrayView<double> restSegment);
// Total length of the curves (closed ones with their closing segment); the same for any thread count.
double totalYarnLength(const Polylines& yarns);
double minYarnDistance(const Polylines& centres, ArrayView<double> restArc, const std::vector<double>& restLength,
                       double yarnRadius, const AnimatorOptions& options, DistanceScratch& scratch);

}  // namespace knit
