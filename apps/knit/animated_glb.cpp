// animated_glb.cpp — the animated .glb sink of `knit animate`: the first frame's curves (LINES)
// or tubes (TRIANGLES) as the topology (with the chart's colours as COLOR_0), then one morph
// target per frame.
#include "animated_glb.hpp"

#include <string>

#include "knit/error.hpp"
#include "knit/morph_gltf.hpp"
#include "knit/sweep.hpp"
#include "util/platform.hpp"

namespace knit::cli {
namespace {

// What the file holds: ply or yarn curves, as lines or as swept tubes.
struct GlbContent {
    bool plies = true;
    bool tubes = false;
    double radius = 0;
    TubeOptions tube;
    const std::vector<glm::vec3>* colours = nullptr;  // per curve point (the chart's), or none
};

GlbContent contentOf(const Animator& animator, const ExportOptions& o) {
    GlbContent c;
    c.tubes = o.what == ExportWhat::Tubes;
    c.plies = animator.options().plies && !(c.tubes && o.tubesOf == TubeSource::Yarns);
    c.radius = c.plies ? animator.plyOptions().plyRadius : animator.rest().yarnRadius();
    c.tube.sides = o.sides;
    c.tube.caps = o.caps;
    // The chart's colours: per ply point of the constant ply layout, or per rest yarn point.
    const std::vector<glm::vec3>& colours = c.plies ? animator.plyTopology().colour : animator.rest().yarns().colour;
    if (!colours.empty()) c.colours = &colours;
    c.tube.pointColours = c.colours;
    return c;
}

const Polylines& curvesOf(const AnimationFrame& f, const GlbContent& c) {
    return c.plies ? f.plies.curves : f.yarns.curves;
}

// Step: the vertex and index counts of the file, from the constant curve layout.
void countGeometry(const Polylines& layout, const GlbContent& c, size_t& vertices, size_t& indices) {
    vertices = indices = 0;
    for (size_t k = 0; k < layout.curveCount(); ++k) {
        if (c.tubes) {
            vertices += tubeVertexCount(layout.size(k), layout.isClosed(k), c.tube);
            indices += 3 * tubeTriangleCount(layout.size(k), layout.isClosed(k), c.tube);
        } else {
            vertices += layout.size(k);
            indices += 2 * size_t(layout.segmentCount(k));
        }
    }
}

class AnimatedGlbSink : public FrameSink {
public:
    AnimatedGlbSink(const ExportOptions& o, const GlbContent& c, size_t frames, const MorphGlbOptions& m)
        : path_(o.path), content_(c), frames_(frames), morph_(m) {}

    void write(int, const BaseMesh&, const AnimationFrame& frame) override {
        const Polylines& curves = curvesOf(frame, content_);
        if (content_.tubes) {
            // Tubes: swept per frame around the same curves (constant vertex layout).
            TubeOptions t = content_.tube;
            if (!content_.plies && frame.yarns.normals.size() == curves.pointCount())
                t.seedNormals = &frame.yarns.normals;
            const glm::dvec3 origin = curves.points.empty() ? glm::dvec3(0.0) : curves.points.front();
            sweepTubes(curves, content_.radius, t, 0, curves.curveCount(), origin, tubes_);
            positions_.resize(tubes_.vertexCount());
            for (size_t i = 0; i < positions_.size(); ++i) positions_[i] = origin + glm::dvec3(tubes_.positions[i]);
        }
        if (!writer_) writer_ = std::make_unique<MorphGlbWriter>(path_, topology(curves), frames_, morph_);
        if (content_.tubes) writer_->writeFrame(positions_, &tubes_.normals);
        else writer_->writeFrame(curves.points);
    }
    void commit() override { writer_->commit(); }

private:
    MorphTopology topology(const Polylines& curves) const {
        MorphTopology t;
        t.triangles = content_.tubes;
        if (content_.tubes) {
            t.positions = positions_;
            t.normals = tubes_.normals;
            t.indices.reserve(tubes_.triangles.size() * 3);
            for (const glm::uvec3& f : tubes_.triangles) t.indices.insert(t.indices.end(), {f.x, f.y, f.z});
        } else {
            t.positions = curves.points;
            t.indices = segmentIndices(curves.offsets, curves.closed);
            t.radius = content_.radius;
            if (content_.colours) t.colours = *content_.colours;
        }
        if (content_.tubes) t.colours = tubes_.colours;
        return t;
    }

    std::string path_;
    GlbContent content_;
    size_t frames_;
    MorphGlbOptions morph_;
    std::unique_ptr<MorphGlbWriter> writer_;
    TubeMesh tubes_;                     // tubes: this frame's sweep, reused
    std::vector<glm::dvec3> positions_;  // tubes: this frame's vertices in double
};

}  // namespace

bool isAnimatedGlb(const std::string& path, bool hasFramePattern) {
    return !hasFramePattern && util::lowerExtension(path) == "glb";
}

void checkAnimatedGlbOptions(const ExportOptions& o) {
    if (o.draco || o.quantize || o.meshopt)
        throw Error("-o '" + o.path +
                    "': an animated .glb holds plain float morph targets; --draco, --quantize and --meshopt need "
                    "per-frame files (e.g. out_%04d.glb)");
}

std::unique_ptr<FrameSink> makeAnimatedGlbSink(const Animator& animator, size_t frames, const ExportOptions& options,
                                               const AnimatedGlbOptions& glb, const MemoryBudget& budget) {
    const GlbContent content = contentOf(animator, options);
    const Polylines& layout = content.plies ? animator.plyTopology().curves : animator.rest().yarns().curves;
    size_t vertices = 0, indices = 0;
    countGeometry(layout, content, vertices, indices);
    budget.require(morphGlbBytes(vertices, indices, frames, content.tubes),
                   "an animated .glb of " + std::to_string(frames) + " frames x " + std::to_string(vertices) +
                       (content.tubes ? " tube" : " curve") + " vertices (one morph target per frame)",
                   "the frame count (--step, --first / --last; a point cache, -o out.pc2, streams its frames instead)");
    MorphGlbOptions m;
    m.fps = glb.fps;
    m.linear = glb.linear;
    return std::make_unique<AnimatedGlbSink>(options, content, frames, m);
}

}  // namespace knit::cli
