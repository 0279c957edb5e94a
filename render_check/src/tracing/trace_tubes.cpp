// Tubes mode: the exporter's swept tube meshes (knit::sweepTubes) with the flat end caps replaced
// by tessellated hemispheres, wound outward and traced watertight; entering hits by facet normal.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "knit/sweep.hpp"
#include "trace_geometry.hpp"
#include "trace_segments.hpp"
#include "util/math.hpp"

namespace knit {
namespace {

// The hemisphere caps' latitude step is this quarter turn over the latitude count. It is the float
// nearest 1.5707963, one ulp below float(pi / 2): kept so the cap vertices stay as they were.
constexpr float kQuarterTurn = 1.5707963f;

// Tubes: entering hits by the facet normal (triangles are wound outward, see outwardTubes), at
// least kTubeMinHitDistance from the origin: the tube is a closed polyhedron, so its first
// entering facet is where a ray enters it. (Deciding by the centreline normal instead let grazing
// rays pass through the tube wherever the facet and centreline normals disagree: up to half the
// polygon angle plus the ring tilt at joints.) The triangle a spawned ray leaves is also ignored:
// the facets of rings tilted at joints deviate from the centreline normal by more than the polygon
// angle, so the offset along that normal alone does not always clear the facet plane.
constexpr float kTubeMinHitDistance = 1e-4f;  // ply radii (spawned rays start >= 1e-3 away)

struct TubeData {
    std::vector<glm::vec3> positions;  // padded by one element for Embree's 16-byte loads
    std::vector<glm::uvec3> triangles;
    std::vector<uint32_t> segmentOfTriangle;
    size_t bytes() const {
        return positions.size() * sizeof(glm::vec3) + triangles.size() * sizeof(glm::uvec3) +
               segmentOfTriangle.size() * sizeof(uint32_t);
    }
};

// The ply curves as polylines (the points the other modes use), with the PlyGeometry curve of each.
struct PlyPolylines {
    Polylines curves;
    std::vector<uint32_t> sourceCurve;
};

PlyPolylines plyPolylines(const PlyGeometry& pg) {
    PlyPolylines out;
    for (size_t k = 0; k + 1 < pg.curveSegments.size(); ++k) {
        const uint32_t s0 = pg.curveSegments[k], s1 = pg.curveSegments[k + 1];
        if (s0 == s1) continue;
        const bool closed = pg.hasLeft(s0);
        std::vector<glm::dvec3> p;
        for (uint32_t s = s0; s < s1; ++s) p.push_back(pg.toWorld(glm::vec3(pg.points[pg.segments[s]])));
        if (!closed) p.push_back(pg.toWorld(glm::vec3(pg.points[pg.segments[s1 - 1] + 1])));
        out.curves.addCurve(p.data(), p.size(), closed);
        out.sourceCurve.push_back(static_cast<uint32_t>(k));
    }
    return out;
}

// The swept mesh in scene units, every triangle wound outward (facet normal on the side of its
// vertex normals), so the entry filter can trust the facet normal.
TubeData outwardTubes(const PlyGeometry& pg, const TubeMesh& mesh) {
    TubeData t;
    t.positions.reserve(mesh.positions.size() + 1);
    const float inv = static_cast<float>(1.0 / pg.unit);  // metres relative to origin -> scene units
    for (const glm::vec3& q : mesh.positions) t.positions.push_back(q * inv);
    t.triangles = mesh.triangles;
    if (mesh.curveOfVertex.size() != mesh.positions.size() || mesh.normals.size() != mesh.positions.size())
        throw Error("cannot render: the swept tubes have no curve index or normal per vertex");
    for (glm::uvec3& tri : t.triangles) {
        const glm::vec3 f =
            glm::cross(t.positions[tri.y] - t.positions[tri.x], t.positions[tri.z] - t.positions[tri.x]);
        if (glm::dot(f, mesh.normals[tri.x] + mesh.normals[tri.y] + mesh.normals[tri.z]) < 0) std::swap(tri.y, tri.z);
    }
    return t;
}

float pointSegmentDistance2(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 d = b - a;
    const float dd = glm::dot(d, d);
    const float t = dd > 0 ? std::clamp(glm::dot(p - a, d) / dd, 0.f, 1.f) : 0.f;
    const glm::vec3 q = a + t * d - p;
    return glm::dot(q, q);
}

// The segment in [a, b) nearest to p, and its squared distance bd.
uint32_t nearestSegment(const PlyGeometry& pg, const glm::vec3& p, uint32_t a, uint32_t b, float& bd) {
    uint32_t bs = a;
    bd = std::numeric_limits<float>::max();
    for (uint32_t s = a; s < b; ++s) {
        const uint32_t j = pg.segments[s];
        const float d = pointSegmentDistance2(p, glm::vec3(pg.points[j]), glm::vec3(pg.points[j + 1]));
        if (d < bd) bd = d, bs = s;
    }
    return bs;
}

// The ply segment of each triangle: nearest segment of its curve to the centroid (window search
// along the curve, full scan when the window loses it).
void assignSegments(const PlyGeometry& pg, const TubeMesh& mesh, const std::vector<uint32_t>& sourceCurve, float radius,
                    TubeData& t) {
    t.segmentOfTriangle.resize(t.triangles.size());
    uint32_t lastCurve = UINT32_MAX, lastSeg = 0;
    for (size_t i = 0; i < t.triangles.size(); ++i) {
        const glm::uvec3 tri = t.triangles[i];
        const uint32_t c = sourceCurve.at(mesh.curveOfVertex[tri.x]);
        const glm::vec3 cen = (t.positions[tri.x] + t.positions[tri.y] + t.positions[tri.z]) / 3.f;
        const uint32_t s0 = pg.curveSegments[c], s1 = pg.curveSegments[c + 1];
        float bd;
        uint32_t bs;
        if (c == lastCurve) {
            bs = nearestSegment(pg, cen, std::max(s0, lastSeg > s0 + 4 ? lastSeg - 4 : s0), std::min(s1, lastSeg + 5),
                                bd);
            if (bd > 4.f * radius * radius) bs = nearestSegment(pg, cen, s0, s1, bd);
        } else {
            bs = nearestSegment(pg, cen, s0, s1, bd);
        }
        lastCurve = c, lastSeg = bs;
        t.segmentOfTriangle[i] = bs;
    }
}

// One hemisphere of `radius` on the ring of ringSize vertices starting at `ring` (the ring's last
// vertex repeats its first), towards +axis from centre; its triangles belong to segment seg.
void addHemisphere(TubeData& t, uint32_t ring, uint32_t ringSize, uint32_t latitudes, const glm::vec3& centre,
                   const glm::vec3& axis, float radius, uint32_t seg) {
    auto addTriangle = [&](glm::uvec3 tri) {  // wound outward (away from the centre)
        const glm::vec3 f =
            glm::cross(t.positions[tri.y] - t.positions[tri.x], t.positions[tri.z] - t.positions[tri.x]);
        const glm::vec3 mid = (t.positions[tri.x] + t.positions[tri.y] + t.positions[tri.z]) / 3.f;
        if (glm::dot(f, mid - centre) < 0) std::swap(tri.y, tri.z);
        t.triangles.push_back(tri);
        t.segmentOfTriangle.push_back(seg);
    };
    uint32_t prev = ring;  // latitude 0 = the end ring itself
    for (uint32_t l = 1; l <= latitudes; ++l) {
        const float phi = kQuarterTurn * float(l) / float(latitudes);
        const uint32_t cur = static_cast<uint32_t>(t.positions.size());
        if (l < latitudes) {
            for (uint32_t q = 0; q < ringSize; ++q)
                t.positions.push_back(centre + std::cos(phi) * (t.positions[ring + q] - centre) +
                                      std::sin(phi) * radius * axis);
        } else {
            t.positions.push_back(centre + radius * axis);  // pole
        }
        for (uint32_t q = 0; q + 1 < ringSize; ++q) {
            if (l < latitudes) {
                addTriangle({prev + q, prev + q + 1, cur + q});
                addTriangle({prev + q + 1, cur + q + 1, cur + q});
            } else {
                addTriangle({prev + q, prev + q + 1, cur});
            }
        }
        prev = cur;
    }
}

// Hemispherical caps on open ends, built on the end rings (sweep.hpp layout: an open curve of n
// points has n rings of sides + 1 vertices, the last repeating the first).
void addEndCaps(const PlyGeometry& pg, const PlyPolylines& lines, const TubeMesh& mesh, const TubeOptions& to,
                float radius, TubeData& t) {
    const uint32_t ringSize = static_cast<uint32_t>(to.sides) + 1,
                   latitudes = static_cast<uint32_t>(std::max(2, to.sides / 4));
    size_t firstVertex = 0;
    for (size_t c = 0; c < lines.curves.curveCount(); ++c) {
        const uint32_t n = static_cast<uint32_t>(lines.curves.size(c));
        const bool closed = lines.curves.isClosed(c);
        const size_t count = tubeVertexCount(n, closed, to);
        if (firstVertex + count > mesh.positions.size() || mesh.curveOfVertex[firstVertex] != c)
            throw Error("cannot render: the swept tubes are not one ring of vertices per ply sample (internal error)");
        const uint32_t k = lines.sourceCurve[c];
        const uint32_t s0 = pg.curveSegments[k], s1 = pg.curveSegments[k + 1];
        for (int end = 0; end < 2 && !closed; ++end) {
            const uint32_t ring = static_cast<uint32_t>(firstVertex) + (end ? (n - 1) * ringSize : 0);
            const uint32_t seg = end ? s1 - 1 : s0;
            const uint32_t j = pg.segments[seg];
            const glm::vec3 centre(pg.points[end ? j + 1 : j]);
            const glm::vec3 axis = safeNormalize(end ? glm::vec3(pg.points[j + 1]) - glm::vec3(pg.points[j])
                                                     : glm::vec3(pg.points[j]) - glm::vec3(pg.points[j + 1]));
            addHemisphere(t, ring, ringSize, latitudes, centre, axis, radius, seg);
        }
        firstVertex += count;
    }
}

// The curves of one tube radius (scene units; a curve's points carry its radius).
PlyPolylines curvesOfRadius(const PlyGeometry& pg, const PlyPolylines& all, float radius) {
    PlyPolylines out;
    for (size_t c = 0; c < all.curves.curveCount(); ++c) {
        const uint32_t k = all.sourceCurve[c];
        if (pg.points[pg.segments[pg.curveSegments[k]]].w != radius) continue;
        out.curves.addCurve(all.curves.points.data() + all.curves.begin(c), all.curves.size(c), all.curves.isClosed(c));
        out.sourceCurve.push_back(k);
    }
    return out;
}

TubeData buildTubes(const PlyGeometry& pg, int sides) {
    const PlyPolylines all = plyPolylines(pg);
    std::vector<float> radii;  // the plies', and a view's yarn-level curves' (the bundle's)
    for (size_t c = 0; c < all.curves.curveCount(); ++c) {
        const float r = pg.points[pg.segments[pg.curveSegments[all.sourceCurve[c]]]].w;
        if (std::find(radii.begin(), radii.end(), r) == radii.end()) radii.push_back(r);
    }
    TubeData t;
    for (const float radius : radii) {
        const PlyPolylines lines = curvesOfRadius(pg, all, radius);
        // Step 1: the curves as polylines -> sweepTubes, without the exporter's flat end caps
        // (replaced by hemispheres in step 4: round ends like Embree's round curves and the grid
        // cells, so the three modes model the same solid).
        TubeOptions to;
        to.sides = sides;
        to.caps = false;
        const TubeMesh mesh = sweepTubes(lines.curves, pg.unit * radius, to, 0, lines.curves.curveCount(), pg.origin);
        // Step 2: scene units, outward winding.
        TubeData g = outwardTubes(pg, mesh);
        // Step 3: the ply segment of each triangle.
        assignSegments(pg, mesh, lines.sourceCurve, radius, g);
        // Step 4: hemispherical caps on open ends.
        addEndCaps(pg, lines, mesh, to, radius, g);
        // Step 5: after the tubes of the other radii.
        const uint32_t base = static_cast<uint32_t>(t.positions.size());
        t.positions.insert(t.positions.end(), g.positions.begin(), g.positions.end());
        for (const glm::uvec3& tri : g.triangles) t.triangles.push_back(tri + base);
        t.segmentOfTriangle.insert(t.segmentOfTriangle.end(), g.segmentOfTriangle.begin(), g.segmentOfTriangle.end());
    }
    t.positions.emplace_back(0.f);  // padding
    return t;
}

void tubeEntryFilter(const RTCFilterFunctionNArguments* a) {
    const TubeData& tubes = *static_cast<const TubeData*>(a->geometryUserPtr);
    const HitContext* ctx = reinterpret_cast<const HitContext*>(a->context);
    for (unsigned i = 0; i < a->N; ++i) {
        if (a->valid[i] != -1) continue;
        const uint32_t prim = RTCHitN_primID(a->hit, a->N, i);
        if (prim == ctx->ignore) {
            a->valid[i] = 0;
            continue;
        }
        // A watertight test also reports the facet a ray starts exactly on (t = 0): not an entry.
        if (RTCRayN_tfar(a->ray, a->N, i) <= kTubeMinHitDistance) {
            a->valid[i] = 0;
            continue;
        }
        const glm::vec3 dir(RTCRayN_dir_x(a->ray, a->N, i), RTCRayN_dir_y(a->ray, a->N, i),
                            RTCRayN_dir_z(a->ray, a->N, i));
        const glm::uvec3 tri = tubes.triangles[prim];
        const glm::vec3& v0 = tubes.positions[tri.x];
        const glm::vec3 f = glm::cross(tubes.positions[tri.y] - v0, tubes.positions[tri.z] - v0);
        if (glm::dot(dir, f) >= 0) a->valid[i] = 0;
    }
}

class TubeGeometry final : public TraceGeometry {
public:
    TubeGeometry(const PlyGeometry& plies, int sides) {
        if (sides < 3) throw Error("cannot render: tube sides must be >= 3");
        tubes_ = buildTubes(plies, sides);
        inscribed_ = std::cos(float(util::kPi) / float(std::max(3, sides)));
    }

    // Watertight triangle tests, or a ray through an edge shared by two facets can slip between
    // them (seen from 1e4 ply radii away).
    RTCSceneFlags sceneFlags() const override { return RTC_SCENE_FLAG_ROBUST; }
    RTCGeometry newGeometry(RTCDevice device) override {
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, tubes_.positions.data(), 0,
                                   sizeof(glm::vec3), tubes_.positions.size() - 1);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tubes_.triangles.data(), 0,
                                   sizeof(glm::uvec3), tubes_.triangles.size());
        rtcSetGeometryUserData(geom, &tubes_);
        rtcSetGeometryIntersectFilterFunction(geom, tubeEntryFilter);
        rtcSetGeometryOccludedFilterFunction(geom, tubeEntryFilter);
        return geom;
    }
    uint32_t segmentOf(uint32_t primID, const HitContext&) const override { return tubes_.segmentOfTriangle[primID]; }
    uint32_t ignoredPrimitive(const TraceHit& from) const override { return from.primID; }
    float inscribedRadius() const override { return inscribed_; }
    int64_t bytes() const override { return static_cast<int64_t>(tubes_.bytes()); }
    size_t primitiveCount() const override { return tubes_.triangles.size(); }

private:
    TubeData tubes_;
    float inscribed_ = 1.f;  // of the tube polygon, in ply radii
};

}  // namespace

std::unique_ptr<TraceGeometry> makeTubeGeometry(const PlyGeometry& plies, int sides) {
    return std::make_unique<TubeGeometry>(plies, sides);
}

}  // namespace knit
