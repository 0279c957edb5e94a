// gltf_curves.cpp — curve chunks: LINE_STRIP primitives with POSITION and _RADIUS (gltf_builder.hpp).
#include "gltf_builder.hpp"

#include "export_budget.hpp"

#include <algorithm>
#include <limits>

namespace knit::impl {

CurveChunkSource::CurveChunkSource(const ExportInput& input, const ExportOptions& options) : input_(input) {
    const size_t maxPoints = options.chunkVertices;
    const std::string& path = options.path;
    if (input.curves) {
        chunks_ = planCurveChunks(*input.curves, maxPoints);
        return;
    }
    const PlyGenerator& g = *input.plies;
    size_t acc = 0, total = 0, largest = 0;
    yarnStart_.push_back(0);
    for (size_t y = 0; y < g.yarnCount(); ++y) {
        const size_t e = g.estimatePoints(y);
        // One yarn's plies are one batch with 32-bit offsets: refuse absurd ones up front.
        if (e > size_t(1) << 31)
            throw Error("cannot export '" + path + "': yarn " + std::to_string(y) + " would have at least " +
                        std::to_string(e) +
                        " ply points (more than 2^31); increase the ply pitch or lower the "
                        "samples per turn");
        if (acc > 0 && acc + e > maxPoints) {
            yarnStart_.push_back(y);
            acc = 0;
        }
        acc += e;
        total += e;
        largest = std::max(largest, acc);
    }
    if (g.yarnCount() > 0) yarnStart_.push_back(g.yarnCount());
    checkStreamedPlyBudget(total, largest, options);
}

// Produces chunk k and converts it: origin = centre of its points' bounding box.
void CurveChunkSource::fill(size_t k, CurveChunk& chunk) const {
    const Polylines* curves = input_.curves;
    const std::vector<glm::vec3>* colours = input_.colours;
    size_t first = 0, last = 0;
    if (curves) {
        first = chunks_[k].firstCurve;
        last = chunks_[k].lastCurve;
    } else {
        input_.plies->generate(yarnStart_[k], yarnStart_[k + 1], chunk.generated, chunk.scratch,
                               false);  // curves only: no radial directions
        curves = &chunk.generated.curves;
        colours = chunk.generated.colour.empty() ? nullptr : &chunk.generated.colour;
        last = curves->curveCount();
    }
    const Chunk range{first, last, 0, 0};
    chunk.origin = last > first ? chunkOrigin(*curves, range) : glm::dvec3(0.0);
    chunk.pos.clear();
    chunk.colour.clear();
    chunk.runs.clear();
    chunk.points = 0;
    for (size_t c = first; c < last; ++c) {
        const uint32_t n = curves->size(c);
        if (n < 2) continue;
        CurveChunk::Run run;
        run.first = uint32_t(chunk.pos.size());
        const glm::dvec3* p = curves->points.data() + curves->begin(c);
        glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
        for (uint32_t i = 0; i < n; ++i) {
            const glm::vec3 q(p[i] - chunk.origin);
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
            chunk.pos.push_back(q);
            if (colours) chunk.colour.push_back(linearRgba8((*colours)[curves->begin(c) + i]));
        }
        if (curves->isClosed(c)) chunk.pos.push_back(chunk.pos[run.first]);
        if (colours && curves->isClosed(c)) chunk.colour.push_back(chunk.colour[run.first]);
        run.count = uint32_t(chunk.pos.size() - run.first);
        run.lo = lo;
        run.hi = hi;
        chunk.runs.push_back(run);
        chunk.points += n;
    }
}

// Curves: chunks are produced (sliced from the input, or generated plies) and converted to
// float32 in parallel, and appended to the buffers in chunk order (a TBB pipeline), so the
// writing overlaps the work of the next chunks and at most `tokens` chunks are in memory.
void GltfBuilder::writeCurves() {
    const CurveChunkSource& source = *curves_;
    if (job_.input.curves)  // known sizes: fail before anything is written
        for (const Chunk& c : source.chunks()) checkChunkFits((c.vertices + (c.lastCurve - c.firstCurve)) * 16 + 64);
    orderedChunks<CurveChunk>(
        source.count(), [&](size_t k, CurveChunk& chunk) { source.fill(k, chunk); },
        [&](size_t k, const CurveChunk& chunk) { writeCurveChunk(k, chunk); });
}

// One chunk's node: a POSITION view (stride 12) holding every curve's points and a _RADIUS
// view (stride 4) as long as the longest curve, shared by the curves' accessors; one
// non-indexed LINE_STRIP primitive per curve.
void GltfBuilder::writeCurveChunk(size_t k, const CurveChunk& chunk) {
    if (chunk.runs.empty()) return;
    uint32_t longest = 0;
    for (const CurveChunk::Run& r : chunk.runs) longest = std::max(longest, r.count);
    if (radius_.size() < longest) radius_.resize(longest, float(job_.input.radius));
    sink_.reserve(chunk.pos.size() * 16 + uint64_t(longest) * 4 + 16);
    const int posView = addView(chunk.pos.data(), chunk.pos.size() * 12, 12, kArrayBuffer);
    const int radView = addView(radius_.data(), uint64_t(longest) * 4, 4, kArrayBuffer);
    const int colView =
        chunk.colour.empty() ? -1 : addView(chunk.colour.data(), chunk.colour.size() * 4, 4, kArrayBuffer);
    tinygltf::Mesh mesh;
    mesh.name = "curves " + std::to_string(k);
    for (const CurveChunk::Run& r : chunk.runs) {
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_LINE_STRIP;
        prim.material = 0;
        const int pos = addAccessor(posView, size_t(r.first) * 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                    r.count, false);
        model_.accessors[size_t(pos)].minValues = {double(r.lo.x), double(r.lo.y), double(r.lo.z)};
        model_.accessors[size_t(pos)].maxValues = {double(r.hi.x), double(r.hi.y), double(r.hi.z)};
        prim.attributes["POSITION"] = pos;
        prim.attributes["_RADIUS"] =
            addAccessor(radView, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, r.count, false);
        if (colView >= 0)
            prim.attributes["COLOR_0"] = addAccessor(
                colView, size_t(r.first) * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, r.count, true);
        mesh.primitives.push_back(std::move(prim));
    }
    addChunkMesh(k, chunk.origin, std::move(mesh), {});
    job_.stats.curves += chunk.runs.size();
    job_.stats.vertices += chunk.points;
    job_.stats.maxChunkVertices = std::max(job_.stats.maxChunkVertices, chunk.points);
}

}  // namespace knit::impl
