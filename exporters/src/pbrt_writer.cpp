// pbrt_writer.cpp — pbrt-v4 scene fragment (for `Include`): curves or tube meshes.
//
// Curves: one `Shape "curve"` per curve, "string type" "cylinder", "string basis" "bezier",
// "integer degree" 3, "float width" = 2 x radius. pbrt has no Catmull-Rom basis, so each
// Catmull-Rom segment p1 -> p2 (neighbours p0, p3) becomes the cubic Bezier
//   b0 = p1, b1 = p1 + (p2 - p0) / 6, b2 = p2 - (p3 - p1) / 6, b3 = p2,
// consecutive segments sharing b3 / b0, so a curve of s segments has 3 s + 1 control points.
// Open ends use the phantom points p[-1] = 2 p[0] - p[1] and p[n] = 2 p[n-1] - p[n-2] (the
// end tangent equals the chord); closed curves wrap (s = n segments, ending at the first point).
// Tubes: one `Shape "trianglemesh"` per chunk with P (world space), N, uv and indices.
// Coordinates are written as shortest round-trip decimal text.
// Yarn colours (ExportInput::colours): pbrt-v4 has no per-vertex colour on curves or meshes and
// no per-shape material overrides, so each curve gets its own attribute block with
// `Material "diffuse" "rgb reflectance"` of the colour at its first point (linear RGB; a colour
// change within one curve, a duplicate stitch, is not represented). Tube meshes carry none.
#include <algorithm>

#include "io/atomic_file.hpp"
#include "chunks.hpp"
#include "formats.hpp"
#include "text_out.hpp"

namespace knit::impl {

namespace {

void point(TextOut& t, const glm::dvec3& p) { t.num(p.x).ch(' ').num(p.y).ch(' ').num(p.z).ch(' '); }

void writeCurve(TextOut& t, const Polylines& curves, size_t c, double width) {
    const uint32_t b = curves.begin(c), n = curves.size(c);
    const bool closed = curves.isClosed(c);
    auto at = [&](int64_t i) -> glm::dvec3 {
        if (closed) return curves.points[b + size_t(((i % n) + n) % n)];
        if (i < 0) return 2.0 * curves.points[b] - curves.points[b + 1];
        if (i >= int64_t(n)) return 2.0 * curves.points[b + n - 1] - curves.points[b + n - 2];
        return curves.points[b + size_t(i)];
    };
    const int64_t segments = closed ? n : n - 1;
    t.str("Shape \"curve\" \"string type\" \"cylinder\" \"string basis\" \"bezier\" \"integer degree\" 3 "
          "\"float width\" ")
        .num(width)
        .str("\n  \"point3 P\" [ ");
    point(t, at(0));
    for (int64_t s = 0; s < segments; ++s) {
        const glm::dvec3 p0 = at(s - 1), p1 = at(s), p2 = at(s + 1), p3 = at(s + 2);
        point(t, p1 + (p2 - p0) / 6.0);
        point(t, p2 - (p3 - p1) / 6.0);
        point(t, p2);
    }
    t.str("]\n");
}

}  // namespace

void exportPbrt(const FormatJob& job) {
    const Polylines& curves = *job.input.curves;
    AtomicFile file(job.options.path, false);
    TextOut t(file.stream());
    t.str("# ").str(job.header).str("\n# pbrt-v4 scene fragment: Include it inside WorldBegin, after a Material.\n");
    t.str("AttributeBegin\n");
    if (!job.tubes) {
        const double width = 2.0 * job.input.radius;
        for (size_t c = 0; c < curves.curveCount(); ++c) {
            if (curves.size(c) < 2) continue;
            if (job.input.colours) {
                const glm::vec3& k = (*job.input.colours)[curves.begin(c)];
                t.str("AttributeBegin\n  Material \"diffuse\" \"rgb reflectance\" [ ")
                    .num(k.r)
                    .ch(' ')
                    .num(k.g)
                    .ch(' ')
                    .num(k.b)
                    .str(" ]\n");
            }
            writeCurve(t, curves, c, width);
            if (job.input.colours) t.str("AttributeEnd\n");
            ++job.stats.curves;
            job.stats.vertices += curves.size(c);
        }
        job.stats.chunks = 1;
    } else {
        const std::vector<Chunk> chunks = planTubeChunks(curves, job.tube, job.options.chunkVertices);
        forEachTubeChunk(curves, job.input.radius, job.tube, chunks, [&](size_t, const TubeMesh& m) {
            if (m.vertexCount() == 0) return;
            t.str("Shape \"trianglemesh\"\n  \"point3 P\" [ ");
            for (const glm::vec3& p : m.positions) point(t, m.origin + glm::dvec3(p));
            t.str("]\n  \"normal N\" [ ");
            for (const glm::vec3& n : m.normals) t.num(n.x).ch(' ').num(n.y).ch(' ').num(n.z).ch(' ');
            t.str("]\n  \"point2 uv\" [ ");
            for (const glm::vec2& uv : m.uvs) t.num(uv.x).ch(' ').num(uv.y).ch(' ');
            t.str("]\n  \"integer indices\" [ ");
            for (const glm::uvec3& tri : m.triangles) t.num(tri.x).ch(' ').num(tri.y).ch(' ').num(tri.z).ch(' ');
            t.str("]\n");
            job.stats.vertices += m.vertexCount();
            job.stats.triangles += m.triangles.size();
            job.stats.maxChunkVertices = std::max(job.stats.maxChunkVertices, m.vertexCount());
        });
        job.stats.curves = curves.curveCount();
        job.stats.chunks = chunks.size();
    }
    t.str("AttributeEnd\n");
    t.flush();
    file.commit();
    job.stats.bytes = file.bytesWritten();
}

}  // namespace knit::impl
