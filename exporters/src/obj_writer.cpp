// obj_writer.cpp — Wavefront OBJ: curves as `l i j` segments, tube meshes as v/vn/vt/f.
#include "obj_writer.hpp"

#include <algorithm>
#include <sstream>

#include "io/atomic_file.hpp"
#include "chunks.hpp"
#include "formats.hpp"
#include "text_out.hpp"

namespace knit {

namespace {

void writeHeaderComment(impl::TextOut& t, const std::string& header) {
    // Each header line becomes an OBJ comment line.
    std::istringstream lines(header);
    std::string line;
    while (std::getline(lines, line)) t.str("# ").str(line).ch('\n');
}

// One `l i j` record between 0-based points i and j.
void writeSegment(impl::TextOut& t, uint32_t i, uint32_t j) {
    t.str("l ").num(uint64_t(i) + 1).ch(' ').num(uint64_t(j) + 1).ch('\n');
}

}  // namespace

namespace impl {

void writeObjPolylines(std::ostream& out, const Polylines& curves, const std::string& header) {
    impl::TextOut t(out);
    writeHeaderComment(t, header);
    // Step 1: every point as `v x y z` (shortest round-trip text of the double).
    for (const glm::dvec3& p : curves.points) {
        t.str("v ").num(p.x).ch(' ').num(p.y).ch(' ').num(p.z).ch('\n');
    }
    // Step 2: every curve (>= 2 points) as 2-index `l i j` segments, 1-based; a closed curve ends
    // with the segment back to its first vertex. Importers that keep only the first segment of a
    // longer `l` record (Blender 3.4) read every segment this way.
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const uint32_t b = curves.begin(c), e = curves.end(c);
        if (e - b < 2) continue;
        for (uint32_t i = b; i + 1 < e; ++i) writeSegment(t, i, i + 1);
        if (curves.isClosed(c)) writeSegment(t, e - 1, b);
    }
    t.flush();
}

void writeObjTubeHeader(std::ostream& out, const std::string& header) {
    TextOut t(out);
    writeHeaderComment(t, header);
    t.flush();
}

void writeObjTubeChunk(std::ostream& out, const TubeMesh& mesh, uint64_t vertexBase) {
    TextOut t(out);
    // Positions are written in world space: chunk origin (double) + float offset.
    for (const glm::vec3& p : mesh.positions) {
        t.str("v ")
            .num(mesh.origin.x + double(p.x))
            .ch(' ')
            .num(mesh.origin.y + double(p.y))
            .ch(' ')
            .num(mesh.origin.z + double(p.z))
            .ch('\n');
    }
    for (const glm::vec3& n : mesh.normals) t.str("vn ").num(n.x).ch(' ').num(n.y).ch(' ').num(n.z).ch('\n');
    for (const glm::vec2& uv : mesh.uvs) t.str("vt ").num(uv.x).ch(' ').num(uv.y).ch('\n');
    // Faces: v/vt/vn share one index per vertex (1-based, offset by the earlier chunks).
    for (const glm::uvec3& tri : mesh.triangles) {
        t.ch('f');
        for (int k = 0; k < 3; ++k) {
            const uint64_t i = vertexBase + tri[k] + 1;
            t.ch(' ').num(i).ch('/').num(i).ch('/').num(i);
        }
        t.ch('\n');
    }
    t.flush();
}

void exportObj(const FormatJob& job) {
    const Polylines& curves = *job.input.curves;
    AtomicFile file(job.options.path, true);
    if (!job.tubes) {
        // Curves: the whole polyline set (already in memory as the scene) in one pass.
        writeObjPolylines(file.stream(), curves, job.header);
        job.stats.curves = curves.curveCount();
        job.stats.vertices = curves.pointCount();
        job.stats.chunks = 1;
    } else {
        // Tubes: streamed chunk by chunk, indices continue across chunks.
        writeObjTubeHeader(file.stream(), job.header);
        const std::vector<Chunk> chunks = planTubeChunks(curves, job.tube, job.options.chunkVertices);
        uint64_t base = 0;
        forEachTubeChunk(curves, job.input.radius, job.tube, chunks, [&](size_t, const TubeMesh& mesh) {
            writeObjTubeChunk(file.stream(), mesh, base);
            base += mesh.vertexCount();
            job.stats.triangles += mesh.triangles.size();
            job.stats.maxChunkVertices = std::max(job.stats.maxChunkVertices, mesh.vertexCount());
        });
        job.stats.curves = curves.curveCount();
        job.stats.vertices = base;
        job.stats.chunks = chunks.size();
    }
    file.commit();
    job.stats.bytes = file.bytesWritten();
}

}  // namespace impl
}  // namespace knit
