// ply_writer.cpp — binary little-endian PLY: curves as vertices + edges, tubes as triangle meshes.
//
// Curves: element vertex (double x y z), element edge (int vertex1 vertex2): consecutive points,
// plus last -> first for closed curves. Tubes: element vertex (double x y z in world space,
// float nx ny nz, float s t), element face (list uchar uint vertex_indices); streamed per chunk.
// Yarn colours (ExportInput::colours): vertex properties uchar red green blue, sRGB-encoded as PLY
// readers (Blender, MeshLab) expect.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include "io/atomic_file.hpp"
#include "chunks.hpp"
#include "formats.hpp"
#include "knit/error.hpp"
#include "util/math.hpp"

namespace knit::impl {

namespace {

// Little-endian byte packing into a reusable block.
class Packer {
public:
    template <class T>
    void put(T v) {
        const size_t at = bytes_.size();
        bytes_.resize(at + sizeof(T));
        std::memcpy(bytes_.data() + at, &v, sizeof(T));
    }
    void flushTo(std::ostream& out) {
        out.write(bytes_.data(), std::streamsize(bytes_.size()));
        bytes_.clear();
    }
    size_t size() const { return bytes_.size(); }

private:
    std::vector<char> bytes_;
};

// A linear colour as the three sRGB bytes of a PLY vertex.
void putColour(Packer& pack, const glm::vec3& c) {
    for (int k = 0; k < 3; ++k)
        pack.put(uint8_t(std::lround(util::linearToSrgb(std::clamp(double(c[k]), 0.0, 1.0)) * 255.0)));
}

const char* kColourProperties = "property uchar red\nproperty uchar green\nproperty uchar blue\n";

bool littleEndianHost() {
    const uint16_t one = 1;
    char b;
    std::memcpy(&b, &one, 1);
    return b == 1;
}

}  // namespace

void exportPly(const FormatJob& job) {
    if (!littleEndianHost()) throw Error("cannot export: PLY writer needs a little-endian host");
    const Polylines& curves = *job.input.curves;
    const std::vector<glm::vec3>* colours = job.input.colours;
    AtomicFile file(job.options.path, true);
    std::ostream& out = file.stream();
    Packer pack;
    if (!job.tubes) {
        // Step 1 (curves): count edges, header, vertices, edges.
        uint64_t edges = 0;
        for (size_t c = 0; c < curves.curveCount(); ++c) edges += curves.segmentCount(c);
        std::ostringstream h;
        h << "ply\nformat binary_little_endian 1.0\ncomment " << job.header << "\nelement vertex "
          << curves.pointCount() << "\nproperty double x\nproperty double y\nproperty double z\n"
          << (colours ? kColourProperties : "") << "element edge " << edges
          << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
        out << h.str();
        for (size_t i = 0; i < curves.points.size(); ++i) {
            const glm::dvec3& p = curves.points[i];
            pack.put(p.x);
            pack.put(p.y);
            pack.put(p.z);
            if (colours) putColour(pack, (*colours)[i]);
            if (pack.size() > (1u << 20)) pack.flushTo(out);
        }
        for (size_t c = 0; c < curves.curveCount(); ++c) {
            const uint32_t b = curves.begin(c), n = curves.size(c), segs = curves.segmentCount(c);
            for (uint32_t s = 0; s < segs; ++s) {
                pack.put(int32_t(b + s));
                pack.put(int32_t(b + (s + 1) % n));
            }
            if (pack.size() > (1u << 20)) pack.flushTo(out);
        }
        pack.flushTo(out);
        job.stats.curves = curves.curveCount();
        job.stats.vertices = curves.pointCount();
        job.stats.chunks = 1;
    } else {
        // Step 1 (tubes): counts from the chunk plan (the header needs them first), then stream.
        const std::vector<Chunk> chunks = planTubeChunks(curves, job.tube, job.options.chunkVertices);
        uint64_t vertices = 0, triangles = 0;
        for (const Chunk& k : chunks) {
            vertices += k.vertices;
            triangles += k.triangles;
        }
        if (vertices > 0xFFFFFFFFull)
            throw Error("cannot export '" + job.options.path + "': " + std::to_string(vertices) +
                        " tube vertices exceed PLY's 32-bit indices; use .glb");
        std::ostringstream h;
        h << "ply\nformat binary_little_endian 1.0\ncomment " << job.header << "\nelement vertex " << vertices
          << "\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\n"
             "property float nz\nproperty float s\nproperty float t\n"
          << (colours ? kColourProperties : "") << "element face " << triangles
          << "\nproperty list uchar uint vertex_indices\nend_header\n";
        out << h.str();
        // Vertices of all chunks first, then faces: two sweeps keep memory at one chunk.
        forEachTubeChunk(curves, job.input.radius, job.tube, chunks, [&](size_t, const TubeMesh& m) {
            for (size_t i = 0; i < m.vertexCount(); ++i) {
                pack.put(m.origin.x + double(m.positions[i].x));
                pack.put(m.origin.y + double(m.positions[i].y));
                pack.put(m.origin.z + double(m.positions[i].z));
                pack.put(m.normals[i].x);
                pack.put(m.normals[i].y);
                pack.put(m.normals[i].z);
                pack.put(m.uvs[i].x);
                pack.put(m.uvs[i].y);
                if (colours) putColour(pack, m.colours[i]);
                if (pack.size() > (1u << 20)) pack.flushTo(out);
            }
            pack.flushTo(out);
            job.stats.maxChunkVertices = std::max(job.stats.maxChunkVertices, m.vertexCount());
        });
        uint64_t base = 0;
        forEachTubeChunk(curves, job.input.radius, job.tube, chunks, [&](size_t, const TubeMesh& m) {
            for (const glm::uvec3& t : m.triangles) {
                pack.put(uint8_t(3));
                pack.put(uint32_t(base + t.x));
                pack.put(uint32_t(base + t.y));
                pack.put(uint32_t(base + t.z));
                if (pack.size() > (1u << 20)) pack.flushTo(out);
            }
            pack.flushTo(out);
            base += m.vertexCount();
        });
        job.stats.curves = curves.curveCount();
        job.stats.vertices = vertices;
        job.stats.triangles = triangles;
        job.stats.chunks = chunks.size();
    }
    file.commit();
    job.stats.bytes = file.bytesWritten();
}

}  // namespace knit::impl
