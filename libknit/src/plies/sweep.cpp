// sweep.cpp — tube meshes swept around curves with rotation-minimizing frames.
//
// Layout (per curve with n >= 2 points; curves with fewer points produce nothing):
//  * Rings: one ring per curve point, centred on the point, in the plane perpendicular to the
//    frame tangent (frames.hpp: the averaged tangent at joints), oriented by the RMF normal N and
//    binormal B = T x N. Ring vertex j (0..sides) sits at angle phi_j = 2 pi j / sides:
//      position = P + r (cos phi_j N + sin phi_j B),  normal = cos phi_j N + sin phi_j B.
//    Vertex j = sides repeats vertex 0 (same position, normal, tangent) with u = 1: the texture
//    seam column, so u runs 0..1 around without wrapping back inside a triangle.
//  * Closed curves get n + 1 rings: ring n repeats ring 0 (identical position/normal) with
//    v = length / radius, so v increases monotonically along the loop; open curves get n rings.
//    Consecutive rings share vertices between segments (no per-segment duplication).
//  * UV: u = j / sides around; v = arc length from the curve start / radius (radius units).
//  * TANGENT (glTF: xyz along increasing u of TEXCOORD_0, w the bitangent sign): on a ring,
//    xyz = dP/du normalized = -sin phi_j N + cos phi_j B (around the tube), w = +1: then
//    w * cross(normal, tangent) = T, the direction of increasing v (along the curve).
//  * Caps (open curves, options.caps): per end one centre vertex plus `sides` rim vertices with
//    normal -T (start) / +T (end), planar disc uv (0.5 + 0.5 cos, 0.5 + 0.5 sin), so dP/du = N and
//    dP/dv = B: tangent (N, -1) at the start cap (cross(-T, N) = -B), (N, +1) at the end cap.
//  * Triangles wind counter-clockwise seen from outside (geometric normal = vertex normal).
// Positions are float32 offsets from `origin` (computed in double, then rounded once).
#include "knit/sweep.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "knit/frames.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"

namespace knit {

size_t tubeVertexCount(uint32_t points, bool closed, const TubeOptions& options) {
    if (points < 2 || options.sides < 3) return 0;
    const size_t ring = size_t(options.sides) + 1;
    const size_t rings = closed ? size_t(points) + 1 : size_t(points);
    const size_t caps = (!closed && options.caps) ? 2 * ring : 0;
    return rings * ring + caps;
}

size_t tubeTriangleCount(uint32_t points, bool closed, const TubeOptions& options) {
    if (points < 2 || options.sides < 3) return 0;
    const size_t segments = closed ? size_t(points) : size_t(points) - 1;
    const size_t caps = (!closed && options.caps) ? 2 * size_t(options.sides) : 0;
    return segments * 2 * size_t(options.sides) + caps;
}

TubeCounts tubeCounts(const Polylines& curves, const TubeOptions& options) {
    TubeCounts c;
    for (size_t k = 0; k < curves.curveCount(); ++k) {
        const size_t v = tubeVertexCount(curves.size(k), curves.isClosed(k), options);
        c.vertices += double(v);
        c.triangles += double(tubeTriangleCount(curves.size(k), curves.isClosed(k), options));
        c.largestCurveVertices = std::max(c.largestCurveVertices, v);
    }
    return c;
}

double tubeMeshBytes(double vertices, double triangles) {
    // positions, normals (vec3), tangents (vec4), uvs (vec2), curveOfVertex; uvec3 triangles
    constexpr double kPerVertex = 12 + 12 + 16 + 8 + 4, kPerTriangle = 12;
    return vertices * kPerVertex + triangles * kPerTriangle;
}

namespace {

// Orthonormal (T, N) for one ring: the RMF frame, repaired if it is degenerate (a curve of
// coincident points has no tangent; keep the output finite and unit regardless).
void ringFrame(glm::dvec3 t, glm::dvec3 n, glm::dvec3& T, glm::dvec3& N) {
    if (!util::finiteUnit(t)) {
        const double l = glm::length(t);
        t = (std::isfinite(l) && l > 1e-300) ? t / l : glm::dvec3(0, 0, 1);
    }
    n = n - glm::dot(n, t) * t;
    const double ln = glm::length(n);
    N = (std::isfinite(ln) && ln > 1e-12) ? n / ln : util::anyPerpendicular(t);
    T = t;
}

struct CurveSlots {
    size_t vertex = 0;    // first vertex of the curve in the mesh
    size_t triangle = 0;  // first triangle
};

}  // namespace

TubeMesh sweepTubes(const Polylines& curves, double radius, const TubeOptions& options, size_t firstCurve,
                    size_t lastCurve, glm::dvec3 origin) {
    TubeMesh mesh;
    sweepTubes(curves, radius, options, firstCurve, lastCurve, origin, mesh);
    return mesh;
}

void sweepTubes(const Polylines& curves, double radius, const TubeOptions& options, size_t firstCurve, size_t lastCurve,
                glm::dvec3 origin, TubeMesh& mesh) {
    mesh.origin = origin;
    if (lastCurve > curves.curveCount()) lastCurve = curves.curveCount();
    if (firstCurve >= lastCurve || options.sides < 3) {
        mesh.positions.clear();
        mesh.normals.clear();
        mesh.tangents.clear();
        mesh.uvs.clear();
        mesh.triangles.clear();
        mesh.curveOfVertex.clear();
        mesh.colours.clear();
        return;
    }
    const int sides = options.sides;
    const size_t ringSize = size_t(sides) + 1;

    // Step 1: per-curve output slots (prefix sums of the counts), then allocate once.
    std::vector<CurveSlots> slots(lastCurve - firstCurve + 1);
    for (size_t c = firstCurve; c < lastCurve; ++c) {
        const uint32_t n = curves.size(c);
        const bool closed = curves.isClosed(c);
        slots[c - firstCurve + 1].vertex = slots[c - firstCurve].vertex + tubeVertexCount(n, closed, options);
        slots[c - firstCurve + 1].triangle = slots[c - firstCurve].triangle + tubeTriangleCount(n, closed, options);
    }
    const size_t nv = slots.back().vertex, nt = slots.back().triangle;
    mesh.positions.resize(nv);
    mesh.normals.resize(nv);
    mesh.tangents.resize(nv);
    mesh.uvs.resize(nv);
    mesh.curveOfVertex.resize(nv);
    mesh.colours.resize(options.pointColours ? nv : 0);
    mesh.triangles.resize(nt);

    // Step 2: the ring angle table (the seam column reuses angle 0 exactly).
    std::vector<float> cosA(ringSize), sinA(ringSize), uA(ringSize);
    for (size_t j = 0; j < ringSize; ++j) uA[j] = float(j) / float(sides);
    for (int j = 0; j < sides; ++j) {
        const double a = util::kTwoPi * double(j) / double(sides);
        cosA[j] = float(std::cos(a));
        sinA[j] = float(std::sin(a));
    }
    cosA[sides] = cosA[0];
    sinA[sides] = sinA[0];
    const float r = float(radius);
    const double invRadius = 1.0 / radius;

    // Step 3: per block of curves (in parallel; each curve writes only its own slots, so the
    // result does not depend on the thread count): RMF frames, rings, caps, triangles.
    tbb::parallel_for(
        tbb::blocked_range<size_t>(firstCurve, lastCurve, 8), [&](const tbb::blocked_range<size_t>& range) {
            // Frames of this block's curves (a local copy so each block runs independently).
            Polylines local;
            local.points.reserve(curves.end(range.end() - 1) - curves.begin(range.begin()));
            std::vector<glm::dvec3> seeds;
            for (size_t c = range.begin(); c < range.end(); ++c) {
                local.addCurve(curves.points.data() + curves.begin(c), curves.size(c), curves.isClosed(c));
                if (options.seedNormals)
                    seeds.insert(seeds.end(), options.seedNormals->begin() + curves.begin(c),
                                 options.seedNormals->begin() + curves.end(c));
            }
            const Frames frames = rotationMinimizingFrames(local, options.seedNormals ? &seeds : nullptr);

            for (size_t c = range.begin(); c < range.end(); ++c) {
                const size_t lc = c - range.begin();
                const uint32_t n = local.size(lc);
                if (n < 2) continue;
                const bool closed = local.isClosed(lc);
                const uint32_t b = local.begin(lc);
                const size_t rings = closed ? size_t(n) + 1 : size_t(n);
                const CurveSlots slot = slots[c - firstCurve];
                const uint32_t curveId = uint32_t(c);
                double s = 0.0;  // arc length
                glm::dvec3 prev = local.points[b];
                glm::dvec3 T0(0.0), N0(0.0), Tn(0.0), Nn(0.0);
                for (size_t i = 0; i < rings; ++i) {
                    const uint32_t k = b + uint32_t(i % n);
                    const glm::dvec3 p = local.points[k];
                    s += glm::length(p - prev);
                    prev = p;
                    glm::dvec3 T, N;
                    ringFrame(frames.tangent[k], frames.normal[k], T, N);
                    if (i == 0) T0 = T, N0 = N;
                    if (i + 1 == rings) Tn = T, Nn = N;
                    const glm::dvec3 B = glm::cross(T, N);
                    const glm::vec3 cf(p - origin), Nf(N), Bf(B);
                    const float v = float(s * invRadius);
                    const size_t base = slot.vertex + i * ringSize;
                    glm::vec3* pos = mesh.positions.data() + base;
                    glm::vec3* nor = mesh.normals.data() + base;
                    glm::vec4* tan = mesh.tangents.data() + base;
                    glm::vec2* uv = mesh.uvs.data() + base;
                    uint32_t* cv = mesh.curveOfVertex.data() + base;
                    for (size_t j = 0; j < ringSize; ++j) {
                        const glm::vec3 d = cosA[j] * Nf + sinA[j] * Bf;
                        nor[j] = d;
                        pos[j] = cf + r * d;
                        tan[j] = glm::vec4(-sinA[j] * Nf + cosA[j] * Bf, 1.0f);  // dP/du
                        uv[j] = glm::vec2(uA[j], v);
                        cv[j] = curveId;
                    }
                    if (options.pointColours)
                        std::fill_n(mesh.colours.data() + base, ringSize,
                                    (*options.pointColours)[curves.begin(c) + i % n]);
                }
                // Side triangles between consecutive rings: (a, b, c), (b, d, c), outward.
                glm::uvec3* tri = mesh.triangles.data() + slot.triangle;
                for (size_t i = 0; i + 1 < rings; ++i) {
                    const uint32_t r0 = uint32_t(slot.vertex + i * ringSize), r1 = uint32_t(r0 + ringSize);
                    for (uint32_t j = 0; j < uint32_t(sides); ++j) {
                        *tri++ = glm::uvec3(r0 + j, r0 + j + 1, r1 + j);
                        *tri++ = glm::uvec3(r0 + j + 1, r1 + j + 1, r1 + j);
                    }
                }
                if (closed || !options.caps) continue;
                // Caps: centre + rim with the axial normal, fan triangles facing outward.
                for (int end = 0; end < 2; ++end) {
                    const glm::dvec3 T = end == 0 ? T0 : Tn, N = end == 0 ? N0 : Nn;
                    const glm::dvec3 B = glm::cross(T, N);
                    const glm::dvec3 p = local.points[end == 0 ? b : b + n - 1];
                    const glm::vec3 cf(p - origin), Nf(N), Bf(B);
                    const glm::vec3 axial = glm::vec3(end == 0 ? -T : T);
                    const glm::vec4 tf(Nf, end == 0 ? -1.0f : 1.0f);  // dP/du = N, bitangent along B
                    const uint32_t centre = uint32_t(slot.vertex + rings * ringSize + size_t(end) * ringSize);
                    mesh.positions[centre] = cf;
                    mesh.normals[centre] = axial;
                    mesh.tangents[centre] = tf;
                    mesh.uvs[centre] = glm::vec2(0.5f, 0.5f);
                    mesh.curveOfVertex[centre] = curveId;
                    if (options.pointColours)
                        std::fill_n(mesh.colours.data() + centre, size_t(sides) + 1,
                                    (*options.pointColours)[curves.begin(c) + (end == 0 ? 0 : n - 1)]);
                    for (int j = 0; j < sides; ++j) {
                        const uint32_t vtx = centre + 1 + uint32_t(j);
                        const glm::vec3 d = cosA[j] * Nf + sinA[j] * Bf;
                        mesh.positions[vtx] = cf + r * d;
                        mesh.normals[vtx] = axial;
                        mesh.tangents[vtx] = tf;
                        mesh.uvs[vtx] = glm::vec2(0.5f + 0.5f * cosA[j], 0.5f + 0.5f * sinA[j]);
                        mesh.curveOfVertex[vtx] = curveId;
                        const uint32_t next = centre + 1 + uint32_t((j + 1) % sides);
                        *tri++ = end == 0 ? glm::uvec3(centre, next, vtx) : glm::uvec3(centre, vtx, next);
                    }
                }
            }
        });
}

}  // namespace knit
