// knit/morph_gltf.hpp — one animated GLB: a constant topology with one morph target per frame.
//
// Layout of the file (glTF 2.0, binary):
//   * scene 0 -> node "libknit" (translation = the local origin, the centre of the first frame's
//     bounds, so float32 keeps precision) with mesh 0: one primitive, LINES (curves: one segment
//     per index pair, a closed curve's closing segment included) or TRIANGLES (tube meshes), with
//     POSITION (the first frame, relative to the origin, exact float32 min / max), NORMAL for
//     triangles, `_RADIUS` for lines (constant), and UNSIGNED_SHORT / UNSIGNED_INT indices;
//   * one morph target per frame: POSITION deltas against the first frame (NORMAL deltas too for
//     triangles); mesh.weights all 0, so a client without animation shows the first frame;
//   * animation "frames": one sampler, input = frame times k / fps (k = 0 .. frames-1), output =
//     one-hot weights (frame k: weight 1 on target k), interpolation STEP (or LINEAR: a blend
//     between consecutive frames), and one channel, path "weights", on the mesh's node.
// The frames are kept in memory until commit() (a GLB's JSON chunk comes before its data), so
// callers check morphGlbBytes() against their memory budget first. The file is written through
// a temporary sibling renamed by commit(): an error leaves no partial file.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace knit {

struct MorphGlbOptions {
    double fps = 24;         // frame k at k / fps seconds (> 0)
    bool linear = false;     // LINEAR instead of STEP interpolation of the weights
    std::string extrasJson;  // material extras (JSON object text; empty: {"generator":"libknit"})
};

// The constant part of the animation, from the first frame.
struct MorphTopology {
    bool triangles = false;             // false: LINES (curve segments), true: TRIANGLES
    std::vector<glm::dvec3> positions;  // the first frame
    std::vector<glm::vec3> normals;     // triangles only: the first frame's unit normals
    std::vector<uint32_t> indices;      // 2 per segment, or 3 per triangle
    double radius = 0;                  // lines: the curves' radius (the _RADIUS attribute)
    std::vector<glm::vec3> colours;     // linear colour per vertex (COLOR_0, RGBA8); empty: none
};

// The size of the GLB (bytes, before writing) for `vertices` vertices, `indices` indices and
// `frames` frames: the base attributes, the indices, 12 bytes per vertex per frame (24 with
// normals), the frame times and frames^2 weights, and the JSON. The writer holds about this much
// in memory.
double morphGlbBytes(size_t vertices, size_t indices, size_t frames, bool normals);

// The segments of `points` curves laid out as in Polylines (offsets / closed) as LINES indices.
std::vector<uint32_t> segmentIndices(const std::vector<uint32_t>& offsets, const std::vector<uint8_t>& closed);

class MorphGlbWriter {
public:
    // Checks the path (extension .glb, writable folder), the frame count (>= 1) and the size
    // (under the GLB limit of 4 GiB); throws knit::Error naming the path.
    MorphGlbWriter(const std::string& path, MorphTopology base, size_t frames, const MorphGlbOptions& options);
    ~MorphGlbWriter();
    MorphGlbWriter(const MorphGlbWriter&) = delete;
    MorphGlbWriter& operator=(const MorphGlbWriter&) = delete;

    // Appends the next frame (the topology's vertex count; normals for triangles). Throws
    // knit::Error on a wrong count, a frame too many or a non-finite value.
    void writeFrame(const std::vector<glm::dvec3>& positions, const std::vector<glm::vec3>* normals = nullptr);
    // Writes the file and renames it onto the path; throws unless every frame was written.
    void commit();

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace knit
