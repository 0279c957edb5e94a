// Embree scenes for the three geometry modes (curves, tubes, two-stage grid) and ray queries.
#include "trace_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <glm/geometric.hpp>
#include <glm/gtc/type_precision.hpp>
#include <glm/vec2.hpp>

#include "knit/error.hpp"
#include "knit/sweep.hpp"

namespace knit {

EmbreeDevice::EmbreeDevice(const char* config) {
    device_ = rtcNewDevice(config);
    if (!device_) throw Error("render: cannot create an Embree device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeDevice::monitor, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

bool EmbreeDevice::monitor(void* user, ssize_t bytes, bool) {
    static_cast<EmbreeDevice*>(user)->bytes_ += bytes;
    return true;
}

namespace {

// Ray context carrying the segment and position of a user-geometry (grid) hit.
struct HitContext {
    RTCIntersectContext base;
    uint32_t segment;
    float u;
    uint32_t ignore;  // tubes mode: the triangle a spawned ray leaves (or RTC_INVALID_GEOMETRY_ID)
};

// ---- two-stage grid cells -------------------------------------------------------------------
constexpr int kChunk = 8;        // segments per chunk box (8-bit box per chunk)
// Joints bent by more than 2 acos(kMinMitreCos) = 157 degrees are not mitred (the mitre would reach
// r / kMinMitreCos = 5 radii out): both segments are cut perpendicular to their own axis there and
// get the sphere beyond the cut, a round joint as in Embree's round curves (a flat cut alone left
// the outside of the joint open: rays passed into the ply through the missing wedge).
constexpr float kMinMitreCos = 0.2f;

struct GridRun {
    uint32_t firstSegment;
    uint32_t pointOffset;  // into qpoints: [prev], p0 .. p(count), [next]
    uint32_t chunkOffset;  // into chunk boxes (2 per chunk: lo, hi)
    uint16_t count;
    uint8_t hasPrev, hasNext;
};

struct GridCell {
    float lo[3], hi[3];    // primitive bounds
    float qo[3], qs[3];    // dequantization: p = qo + q * qs
    uint32_t firstRun, runCount;
};

struct GridData {
    std::vector<GridCell> cells;
    std::vector<GridRun> runs;
    std::vector<glm::u16vec3> qpoints;
    std::vector<glm::u8vec3> boxes;  // chunk boxes on the cell's grid coarsened 257x (8 bit)
    float radius = 0;
    size_t bytes() const {
        return cells.size() * sizeof(GridCell) + runs.size() * sizeof(GridRun) +
               qpoints.size() * sizeof(glm::u16vec3) + boxes.size() * sizeof(glm::u8vec3);
    }
};

glm::vec3 safeNormalize(const glm::vec3& v) {
    const float l = glm::length(v);
    return l > 0 ? v / l : glm::vec3(0.f);
}

// Directions a (incoming) and b (outgoing) bent too sharply to mitre.
bool sharpJoint(const glm::vec3& a, const glm::vec3& b) { return glm::length(a + b) < 2.f * kMinMitreCos; }


struct RayData {
    glm::vec3 org, dir, inv;
    float tnear;
};

bool boxHit(const RayData& r, const glm::vec3& lo, const glm::vec3& hi, float tfar) {
    const glm::vec3 t0 = (lo - r.org) * r.inv, t1 = (hi - r.org) * r.inv;
    const glm::vec3 tmin = glm::min(t0, t1), tmax = glm::max(t0, t1);
    const float a = std::max({tmin.x, tmin.y, tmin.z, r.tnear});
    const float b = std::min({tmax.x, tmax.y, tmax.z, tfar});
    return a <= b;
}

// The neighbours of a segment (for its joint planes), when it has them.
struct SegmentJoints {
    glm::vec3 prev{0.f}, next{0.f};
    bool hasPrev = false, hasNext = false;
};

// Entering hit of a ray with the ply segment p0 -> p1: the cylinder of `radius` trimmed by the
// joint planes (bisector with the neighbour, oriented along the ply), with round ends (the sphere
// beyond the end plane) at open ends and at joints too sharp to mitre (cut perpendicular there).
// On a hit closer than tfar, returns true with t, the outward normal ng and u along the segment.
bool hitPlySegment(const RayData& r, const glm::vec3& p0, const glm::vec3& p1, const SegmentJoints& joints,
                   float radius, float tfar, float& tHit, glm::vec3& ng, float& u) {
    const glm::vec3 d = p1 - p0;
    const float len = glm::length(d);
    if (len <= 0) return false;
    const glm::vec3 a = d / len;
    // Step 1: work from the ray point nearest the segment's middle (t = ts): from the far origin
    // itself, |op|^2 - (op.dp)^2 / A cancels catastrophically in float (a camera 3000 ply radii
    // away put hits up to 0.6 radii off the surface). Local t below are relative to ts.
    const float dd = glm::dot(r.dir, r.dir);
    const float ts = glm::dot(p0 + 0.5f * d - r.org, r.dir) / dd;
    const glm::vec3 oc = r.org + ts * r.dir - p0;
    const float tnear = r.tnear - ts;
    tfar -= ts;
    // Step 2: the infinite cylinder. The trimmed piece and its round ends lie inside it, so a ray
    // that misses it, enters it beyond tfar or leaves it before tnear misses the segment.
    const float so = glm::dot(oc, a), sd = glm::dot(r.dir, a);
    const glm::vec3 op = oc - so * a, dp = r.dir - sd * a;
    const float A = glm::dot(dp, dp), B = glm::dot(op, dp), C = glm::dot(op, op) - radius * radius;
    const bool lateral = A > 1e-12f * dd;
    float tEnter = 0;
    if (lateral) {
        const float tca = -B / A;
        const float dist2 = C + B * tca;  // |op + tca dp|^2 - r^2 = C - B^2 / A
        if (dist2 > 0) return false;
        const float half = std::sqrt(-dist2 / A);
        tEnter = tca - half;
        if (tEnter >= tfar || tca + half <= tnear) return false;
    } else if (C > 0) {
        return false;  // parallel to the axis, outside the cylinder
    }
    // Step 3: joint planes; round ends where there is no neighbour or the joint is too sharp.
    const glm::vec3 prevDir = joints.hasPrev ? safeNormalize(p0 - joints.prev) : a;
    const glm::vec3 nextDir = joints.hasNext ? safeNormalize(joints.next - p1) : a;
    const glm::vec3 m0 = prevDir + a, m1 = a + nextDir;
    const float l0 = glm::length(m0), l1 = glm::length(m1);
    const bool roundStart = !joints.hasPrev || l0 < 2.f * kMinMitreCos;
    const bool roundEnd = !joints.hasNext || l1 < 2.f * kMinMitreCos;
    const glm::vec3 n0 = roundStart ? a : m0 / l0, n1 = roundEnd ? a : m1 / l1;
    bool hit = false;
    // Step 4: lateral surface, the entering root only (a ray starting inside has no entering root
    // ahead), kept between the two joint planes.
    if (lateral && tEnter > tnear) {
        const glm::vec3 h = oc + tEnter * r.dir;
        if (glm::dot(h, n0) >= 0 && glm::dot(h - d, n1) <= 0) {
            const float s = glm::dot(h, a);
            ng = (h - s * a) / radius;
            u = std::clamp(s / len, 0.f, 1.f);
            tfar = tEnter, hit = true;
        }
    }
    // Step 5: round ends (as Embree's round curves): the sphere beyond the end plane.
    auto cap = [&](const glm::vec3& q, bool start) {  // q = local origin - sphere centre
        const float b = glm::dot(q, r.dir), cc = glm::dot(q, q) - radius * radius;
        const float disc = b * b - dd * cc;
        if (disc < 0) return;
        const float t = (-b - std::sqrt(disc)) / dd;  // entering root: behind a ray starting inside
        if (!(t > tnear && t < tfar)) return;
        const float s = glm::dot(oc + t * r.dir, a);
        if (start ? s > 0 : s < len) return;
        ng = (q + t * r.dir) / radius, u = start ? 0.f : 1.f, tfar = t, hit = true;
    };
    if (roundStart) cap(oc, true);
    if (roundEnd) cap(oc - d, false);
    if (hit) tHit = tfar + ts;
    return hit;
}

// Walks one cell; `anyHit` stops at the first hit. Returns true on a hit (closest in tfar).
bool traverseCell(const GridData& g, const GridCell& cell, const RayData& r, float& tfar, bool anyHit,
                  glm::vec3& ng, uint32_t& segment, float& u) {
    const glm::vec3 qo(cell.qo[0], cell.qo[1], cell.qo[2]), qs(cell.qs[0], cell.qs[1], cell.qs[2]);
    auto point = [&](uint32_t i) { return qo + glm::vec3(g.qpoints[i]) * qs; };
    const glm::vec3 bs = qs * 257.f;  // 8-bit box step
    bool hit = false;
    for (uint32_t ri = cell.firstRun; ri < cell.firstRun + cell.runCount; ++ri) {
        const GridRun& run = g.runs[ri];
        const uint32_t p0 = run.pointOffset + run.hasPrev;  // first point of the first segment
        const uint32_t chunks = (run.count + kChunk - 1) / kChunk;
        for (uint32_t c = 0; c < chunks; ++c) {
            const glm::vec3 lo = qo + glm::vec3(g.boxes[run.chunkOffset + 2 * c]) * bs;
            const glm::vec3 hi = qo + glm::vec3(g.boxes[run.chunkOffset + 2 * c + 1]) * bs;
            if (!boxHit(r, lo, hi, tfar)) continue;
            const uint32_t first = c * kChunk, last = std::min<uint32_t>(run.count, first + kChunk);
            for (uint32_t k = first; k < last; ++k) {
                SegmentJoints joints;
                joints.hasPrev = k > 0 || run.hasPrev, joints.hasNext = k + 1 < run.count || run.hasNext;
                if (joints.hasPrev) joints.prev = point(p0 + k - 1);
                if (joints.hasNext) joints.next = point(p0 + k + 2);
                glm::vec3 n(0.f);
                float uu = 0, t = 0;
                if (hitPlySegment(r, point(p0 + k), point(p0 + k + 1), joints, g.radius, tfar, t, n, uu)) {
                    tfar = t, ng = n, u = uu, segment = run.firstSegment + k, hit = true;
                    if (anyHit) return true;
                }
            }
        }
    }
    return hit;
}

void gridBounds(const RTCBoundsFunctionArguments* args) {
    const GridData& g = *static_cast<const GridData*>(args->geometryUserPtr);
    const GridCell& c = g.cells[args->primID];
    args->bounds_o->lower_x = c.lo[0], args->bounds_o->lower_y = c.lo[1], args->bounds_o->lower_z = c.lo[2];
    args->bounds_o->upper_x = c.hi[0], args->bounds_o->upper_y = c.hi[1], args->bounds_o->upper_z = c.hi[2];
}

RayData rayData(float ox, float oy, float oz, float dx, float dy, float dz, float tnear) {
    RayData r;
    r.org = glm::vec3(ox, oy, oz);
    r.dir = glm::vec3(dx, dy, dz);
    r.inv = 1.f / r.dir;  // +-inf for zero components is what the slab test wants
    r.tnear = tnear;
    return r;
}

void gridIntersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const GridData& g = *static_cast<const GridData*>(args->geometryUserPtr);
    RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);  // rtcIntersect1: N == 1
    const RayData r = rayData(rh->ray.org_x, rh->ray.org_y, rh->ray.org_z, rh->ray.dir_x, rh->ray.dir_y,
                              rh->ray.dir_z, rh->ray.tnear);
    float tfar = rh->ray.tfar, u = 0;
    glm::vec3 ng;
    uint32_t seg = 0;
    if (!traverseCell(g, g.cells[args->primID], r, tfar, false, ng, seg, u)) return;
    rh->ray.tfar = tfar;
    rh->hit.Ng_x = ng.x, rh->hit.Ng_y = ng.y, rh->hit.Ng_z = ng.z;
    rh->hit.u = u, rh->hit.v = 0;
    rh->hit.primID = args->primID;
    rh->hit.geomID = args->geomID;
    rh->hit.instID[0] = args->context->instID[0];
    HitContext* ctx = reinterpret_cast<HitContext*>(args->context);
    ctx->segment = seg;
    ctx->u = u;
}

void gridOccluded(const RTCOccludedFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const GridData& g = *static_cast<const GridData*>(args->geometryUserPtr);
    RTCRay* ray = reinterpret_cast<RTCRay*>(args->ray);
    const RayData r = rayData(ray->org_x, ray->org_y, ray->org_z, ray->dir_x, ray->dir_y, ray->dir_z, ray->tnear);
    float tfar = ray->tfar, u;
    glm::vec3 ng;
    uint32_t seg;
    if (traverseCell(g, g.cells[args->primID], r, tfar, true, ng, seg, u)) ray->tfar = -std::numeric_limits<float>::infinity();
}

GridData buildGrid(const PlyGeometry& pg, const std::vector<int64_t>& cellOf) {
    GridData g;
    g.radius = pg.radius;
    const float r = pg.radius;
    // Step 1: runs of consecutive segments of one curve in one cell, grouped by cell (ordered).
    struct Run { uint32_t first, count; };
    std::map<int64_t, std::vector<Run>> byCell;
    for (uint32_t s = 0; s < pg.segmentCount(); ++s) {
        std::vector<Run>& runs = byCell[cellOf[s]];
        if (!runs.empty()) {
            Run& last = runs.back();
            if (last.first + last.count == s && pg.curveOfSegment[s] == pg.curveOfSegment[last.first] &&
                last.count < 65535) {
                ++last.count;
                continue;
            }
        }
        runs.push_back({s, 1});
    }
    // Step 2: per cell, bounds, quantization frame, quantized points and chunk boxes.
    auto pt = [&](uint32_t i) { return glm::vec3(pg.points[i]); };
    auto segExtent = [&](uint32_t s) {
        // Mitred ends reach r / cos(half bend angle) from the joint.
        const uint32_t i = pg.segments[s];
        const glm::vec3 dir = safeNormalize(pt(i + 1) - pt(i));
        float e = r;
        // (From the half bend angle directly, so a joint near the mitre limit is covered whichever
        // way the quantized points of the cell decide it.)
        if (pg.hasLeft(s)) e = std::max(e, r / std::max(kMinMitreCos, 0.5f * glm::length(safeNormalize(pt(i) - pt(i - 1)) + dir)));
        if (pg.hasRight(s)) e = std::max(e, r / std::max(kMinMitreCos, 0.5f * glm::length(dir + safeNormalize(pt(i + 2) - pt(i + 1)))));
        return e * 1.001f;
    };
    for (const auto& [key, runs] : byCell) {
        GridCell cell;
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        glm::vec3 qlo = lo, qhi = hi;
        for (const Run& run : runs)
            for (uint32_t s = run.first; s < run.first + run.count; ++s) {
                const uint32_t i = pg.segments[s];
                const float e = segExtent(s);
                for (uint32_t j : {i, i + 1}) {
                    lo = glm::min(lo, pt(j) - e), hi = glm::max(hi, pt(j) + e);
                }
                if (pg.hasLeft(s)) qlo = glm::min(qlo, pt(i - 1)), qhi = glm::max(qhi, pt(i - 1));
                if (pg.hasRight(s)) qlo = glm::min(qlo, pt(i + 2)), qhi = glm::max(qhi, pt(i + 2));
            }
        qlo = glm::min(qlo, lo), qhi = glm::max(qhi, hi);
        const glm::vec3 scale = glm::max(qhi - qlo, glm::vec3(1e-30f)) / 65535.f;
        for (int k = 0; k < 3; ++k) cell.lo[k] = lo[k], cell.hi[k] = hi[k], cell.qo[k] = qlo[k], cell.qs[k] = scale[k];
        auto quant = [&](const glm::vec3& p) {
            const glm::vec3 q = glm::round((p - qlo) / scale);
            return glm::u16vec3(glm::clamp(q, glm::vec3(0.f), glm::vec3(65535.f)));
        };
        auto quant8 = [&](const glm::vec3& p, bool up) {  // conservative: floor for lo, ceil for hi
            glm::vec3 q = (p - qlo) / (scale * 257.f);
            q = up ? glm::ceil(q) : glm::floor(q);
            return glm::u8vec3(glm::clamp(q, glm::vec3(0.f), glm::vec3(255.f)));
        };
        cell.firstRun = static_cast<uint32_t>(g.runs.size());
        cell.runCount = static_cast<uint32_t>(runs.size());
        for (const Run& run : runs) {
            GridRun gr;
            gr.firstSegment = run.first;
            gr.count = static_cast<uint16_t>(run.count);
            gr.hasPrev = pg.hasLeft(run.first);
            gr.hasNext = pg.hasRight(run.first + run.count - 1);
            gr.pointOffset = static_cast<uint32_t>(g.qpoints.size());
            gr.chunkOffset = static_cast<uint32_t>(g.boxes.size());
            const uint32_t i0 = pg.segments[run.first];
            if (gr.hasPrev) g.qpoints.push_back(quant(pt(i0 - 1)));
            for (uint32_t k = 0; k <= run.count; ++k) g.qpoints.push_back(quant(pt(i0 + k)));
            if (gr.hasNext) g.qpoints.push_back(quant(pt(i0 + run.count + 1)));
            for (uint32_t c = 0; c < run.count; c += kChunk) {
                glm::vec3 blo(std::numeric_limits<float>::max()), bhi(-std::numeric_limits<float>::max());
                for (uint32_t s = run.first + c; s < std::min(run.first + run.count, run.first + c + kChunk); ++s) {
                    const float e = segExtent(s);
                    for (uint32_t j : {pg.segments[s], pg.segments[s] + 1})
                        blo = glm::min(blo, pt(j) - e), bhi = glm::max(bhi, pt(j) + e);
                }
                g.boxes.push_back(quant8(blo, false));
                g.boxes.push_back(quant8(bhi, true));
            }
            g.runs.push_back(gr);
        }
        g.cells.push_back(cell);
    }
    return g;
}

// ---- tubes -----------------------------------------------------------------------------------
struct TubeData {
    std::vector<glm::vec3> positions;  // padded by one element for Embree's 16-byte loads
    std::vector<glm::uvec3> triangles;
    std::vector<uint32_t> segmentOfTriangle;
    size_t bytes() const {
        return positions.size() * sizeof(glm::vec3) + triangles.size() * sizeof(glm::uvec3) +
               segmentOfTriangle.size() * sizeof(uint32_t);
    }
};

float pointSegmentDistance2(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 d = b - a;
    const float dd = glm::dot(d, d);
    const float t = dd > 0 ? std::clamp(glm::dot(p - a, d) / dd, 0.f, 1.f) : 0.f;
    const glm::vec3 q = a + t * d - p;
    return glm::dot(q, q);
}

TubeData buildTubes(const PlyGeometry& pg, int sides) {
    // Step 1: the ply curves as polylines (the points the other modes use) -> sweepTubes.
    Polylines curves;
    std::vector<uint32_t> sourceCurve;
    for (size_t k = 0; k + 1 < pg.curveSegments.size(); ++k) {
        const uint32_t s0 = pg.curveSegments[k], s1 = pg.curveSegments[k + 1];
        if (s0 == s1) continue;
        const bool closed = pg.hasLeft(s0);
        std::vector<glm::dvec3> p;
        for (uint32_t s = s0; s < s1; ++s) p.push_back(pg.toWorld(glm::vec3(pg.points[pg.segments[s]])));
        if (!closed) p.push_back(pg.toWorld(glm::vec3(pg.points[pg.segments[s1 - 1] + 1])));
        curves.addCurve(p.data(), p.size(), closed);
        sourceCurve.push_back(static_cast<uint32_t>(k));
    }
    // The exporter's flat end caps are replaced by hemispheres (step 3): round ends like Embree's
    // round curves and the grid cells, so the three modes model the same solid.
    TubeOptions to;
    to.sides = sides;
    to.caps = false;
    const TubeMesh mesh = sweepTubes(curves, pg.unit * pg.radius, to, 0, curves.curveCount(), pg.origin);
    TubeData t;
    t.positions.reserve(mesh.positions.size() + 1);
    const float inv = static_cast<float>(1.0 / pg.unit);  // metres relative to origin -> scene units
    for (const glm::vec3& q : mesh.positions) t.positions.push_back(q * inv);
    t.triangles = mesh.triangles;
    if (mesh.curveOfVertex.size() != mesh.positions.size() || mesh.normals.size() != mesh.positions.size())
        throw Error("render: sweepTubes returned no curve index or normal per vertex");
    // Outward winding for every triangle (facet normal on the side of its vertex normals), so
    // the entry filter can trust the facet normal.
    for (glm::uvec3& tri : t.triangles) {
        const glm::vec3 f = glm::cross(t.positions[tri.y] - t.positions[tri.x], t.positions[tri.z] - t.positions[tri.x]);
        if (glm::dot(f, mesh.normals[tri.x] + mesh.normals[tri.y] + mesh.normals[tri.z]) < 0) std::swap(tri.y, tri.z);
    }
    // Step 2: the ply segment of each triangle: nearest segment of its curve to the centroid
    // (window search along the curve, full scan when the window loses it).
    t.segmentOfTriangle.resize(t.triangles.size());
    uint32_t lastCurve = UINT32_MAX, lastSeg = 0;
    for (size_t i = 0; i < t.triangles.size(); ++i) {
        const glm::uvec3 tri = t.triangles[i];
        const uint32_t c = sourceCurve.at(mesh.curveOfVertex[tri.x]);
        const glm::vec3 cen = (t.positions[tri.x] + t.positions[tri.y] + t.positions[tri.z]) / 3.f;
        const uint32_t s0 = pg.curveSegments[c], s1 = pg.curveSegments[c + 1];
        auto search = [&](uint32_t a, uint32_t b, float& bd) {
            uint32_t bs = a;
            bd = std::numeric_limits<float>::max();
            for (uint32_t s = a; s < b; ++s) {
                const uint32_t j = pg.segments[s];
                const float d = pointSegmentDistance2(cen, glm::vec3(pg.points[j]), glm::vec3(pg.points[j + 1]));
                if (d < bd) bd = d, bs = s;
            }
            return bs;
        };
        float bd;
        uint32_t bs;
        if (c == lastCurve) {
            bs = search(std::max(s0, lastSeg > s0 + 4 ? lastSeg - 4 : s0), std::min(s1, lastSeg + 5), bd);
            if (bd > 4.f * pg.radius * pg.radius) bs = search(s0, s1, bd);
        } else {
            bs = search(s0, s1, bd);
        }
        lastCurve = c, lastSeg = bs;
        t.segmentOfTriangle[i] = bs;
    }
    // Step 3: hemispherical caps on open ends, built on the end rings (sweep.hpp layout: an open
    // curve of n points has n rings of sides + 1 vertices, the last repeating the first).
    const uint32_t ringSize = static_cast<uint32_t>(sides) + 1, latitudes = static_cast<uint32_t>(std::max(2, sides / 4));
    size_t firstVertex = 0;
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const uint32_t n = static_cast<uint32_t>(curves.size(c));
        const bool closed = curves.isClosed(c);
        const size_t count = tubeVertexCount(n, closed, to);
        if (firstVertex + count > mesh.positions.size() || mesh.curveOfVertex[firstVertex] != c)
            throw Error("render: sweepTubes vertex layout differs from knit/sweep.hpp");
        const uint32_t k = sourceCurve[c];
        const uint32_t s0 = pg.curveSegments[k], s1 = pg.curveSegments[k + 1];
        for (int end = 0; end < 2 && !closed; ++end) {
            const uint32_t ring = static_cast<uint32_t>(firstVertex) + (end ? (n - 1) * ringSize : 0);
            const uint32_t seg = end ? s1 - 1 : s0;
            const uint32_t j = pg.segments[seg];
            const glm::vec3 centre(pg.points[end ? j + 1 : j]);
            const glm::vec3 axis = safeNormalize(end ? glm::vec3(pg.points[j + 1]) - glm::vec3(pg.points[j])
                                                     : glm::vec3(pg.points[j]) - glm::vec3(pg.points[j + 1]));
            uint32_t prev = ring;  // latitude 0 = the end ring itself
            for (uint32_t l = 1; l <= latitudes; ++l) {
                const float phi = 1.5707963f * float(l) / float(latitudes);
                const uint32_t cur = static_cast<uint32_t>(t.positions.size());
                if (l < latitudes) {
                    for (uint32_t q = 0; q < ringSize; ++q)
                        t.positions.push_back(centre + std::cos(phi) * (t.positions[ring + q] - centre) +
                                              std::sin(phi) * pg.radius * axis);
                } else {
                    t.positions.push_back(centre + pg.radius * axis);  // pole
                }
                auto addTriangle = [&](glm::uvec3 tri) {  // wound outward (away from the centre)
                    const glm::vec3 f = glm::cross(t.positions[tri.y] - t.positions[tri.x], t.positions[tri.z] - t.positions[tri.x]);
                    const glm::vec3 mid = (t.positions[tri.x] + t.positions[tri.y] + t.positions[tri.z]) / 3.f;
                    if (glm::dot(f, mid - centre) < 0) std::swap(tri.y, tri.z);
                    t.triangles.push_back(tri);
                    t.segmentOfTriangle.push_back(seg);
                };
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
        firstVertex += count;
    }
    t.positions.emplace_back(0.f);  // padding
    return t;
}

// Outward normal of ply segment s at point p: perpendicular to the axis, except beyond a round
// end (open end or joint too sharp to mitre: from the end point). u = position along the segment,
// clamped to [0, 1].
glm::vec3 axisNormal(const PlyGeometry& pg, uint32_t s, const glm::vec3& p, float& u) {
    const uint32_t j = pg.segments[s];
    const glm::vec3 a(pg.points[j]), b(pg.points[j + 1]);
    const glm::vec3 d = b - a;
    const float dd = glm::dot(d, d);
    const float raw = dd > 0 ? glm::dot(p - a, d) / dd : 0.f;
    u = std::clamp(raw, 0.f, 1.f);
    const glm::vec3 dir = safeNormalize(d);
    const bool capped =
        (raw < 0 && (!pg.hasLeft(s) || sharpJoint(safeNormalize(a - glm::vec3(pg.points[j - 1])), dir))) ||
        (raw > 1 && (!pg.hasRight(s) || sharpJoint(dir, safeNormalize(glm::vec3(pg.points[j + 2]) - b))));
    return safeNormalize(p - (a + (capped ? u : raw) * d));
}

}  // namespace

struct TraceScene::Impl {
    GridData grid;
    TubeData tubes;
    std::vector<glm::vec3> basePositions;
    std::vector<glm::uvec3> baseFaces;
    const PlyGeometry* plies = nullptr;
};

namespace {

// Plies are solids: drop hits where the ray leaves a ply (direction along the outward normal).
void curveEntryFilter(const RTCFilterFunctionNArguments* a) {
    for (unsigned i = 0; i < a->N; ++i) {
        if (a->valid[i] != -1) continue;
        const float d = RTCRayN_dir_x(a->ray, a->N, i) * RTCHitN_Ng_x(a->hit, a->N, i) +
                        RTCRayN_dir_y(a->ray, a->N, i) * RTCHitN_Ng_y(a->hit, a->N, i) +
                        RTCRayN_dir_z(a->ray, a->N, i) * RTCHitN_Ng_z(a->hit, a->N, i);
        if (d >= 0) a->valid[i] = 0;
    }
}

// Tubes: entering hits by the facet normal (triangles are wound outward, see buildTubes), at
// least kTubeMinHitDistance from the origin: the tube is a closed polyhedron, so its first
// entering facet is where a ray enters it. (Deciding by the centreline normal instead let grazing
// rays pass through the tube wherever the facet and centreline normals disagree: up to half the
// polygon angle plus the ring tilt at joints.) The triangle a spawned ray leaves is also ignored:
// the facets of rings tilted at joints deviate from the centreline normal by more than the polygon
// angle, so the offset along that normal alone does not always clear the facet plane.
constexpr float kTubeMinHitDistance = 1e-4f;  // ply radii (spawned rays start >= 1e-3 away)

void tubeEntryFilter(const RTCFilterFunctionNArguments* a) {
    const TraceScene::Impl& impl = *static_cast<const TraceScene::Impl*>(a->geometryUserPtr);
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
        const glm::vec3 dir(RTCRayN_dir_x(a->ray, a->N, i), RTCRayN_dir_y(a->ray, a->N, i), RTCRayN_dir_z(a->ray, a->N, i));
        const glm::uvec3 tri = impl.tubes.triangles[prim];
        const glm::vec3& v0 = impl.tubes.positions[tri.x];
        const glm::vec3 f = glm::cross(impl.tubes.positions[tri.y] - v0, impl.tubes.positions[tri.z] - v0);
        if (glm::dot(dir, f) >= 0) a->valid[i] = 0;
    }
}

}  // namespace

TraceScene::TraceScene(EmbreeDevice& device, const PlyGeometry& plies, const TraceSceneOptions& options)
    : plies_(plies), options_(options), impl_(std::make_unique<Impl>()) {
    if (plies.segmentCount() == 0) throw Error("render: the scene has no ply segments (nothing to render)");
    impl_->plies = &plies_;
    const int64_t before = device.allocatedBytes();
    RTCDevice dev = device.get();
    scene_ = rtcNewScene(dev);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    // Tubes: watertight triangle tests, or a ray through an edge shared by two facets can slip
    // between them (seen from 1e4 ply radii away).
    if (options.mode == GeometryMode::Tubes) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = nullptr;
    // Step 1: the plies in the chosen representation.
    switch (options.mode) {
        case GeometryMode::Curves: {
            geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, plies.points.data(), 0,
                                       sizeof(glm::vec4), plies.points.size());
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, plies.segments.data(), 0,
                                       sizeof(uint32_t), plies.segments.size());
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, plies.flags.data(), 0,
                                       sizeof(uint8_t), plies.flags.size());
            rtcSetGeometryIntersectFilterFunction(geom, curveEntryFilter);
            rtcSetGeometryOccludedFilterFunction(geom, curveEntryFilter);
            memory_.geometryBytes = static_cast<int64_t>(plies.intersectionBytes());
            primitives_ = plies.segmentCount();
            break;
        }
        case GeometryMode::Tubes: {
            if (options.tubeSides < 3) throw Error("render: tube sides must be >= 3");
            impl_->tubes = buildTubes(plies, options.tubeSides);
            geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, impl_->tubes.positions.data(),
                                       0, sizeof(glm::vec3), impl_->tubes.positions.size() - 1);
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, impl_->tubes.triangles.data(),
                                       0, sizeof(glm::uvec3), impl_->tubes.triangles.size());
            rtcSetGeometryUserData(geom, impl_.get());
            rtcSetGeometryIntersectFilterFunction(geom, tubeEntryFilter);
            rtcSetGeometryOccludedFilterFunction(geom, tubeEntryFilter);
            memory_.geometryBytes = static_cast<int64_t>(impl_->tubes.bytes());
            primitives_ = impl_->tubes.triangles.size();
            break;
        }
        case GeometryMode::Grid: {
            if (!options.segmentCells || options.segmentCells->size() != plies.segmentCount())
                throw Error("render: grid mode needs a UV-grid cell for every ply segment");
            impl_->grid = buildGrid(plies, *options.segmentCells);
            geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(impl_->grid.cells.size()));
            rtcSetGeometryUserData(geom, &impl_->grid);
            rtcSetGeometryBoundsFunction(geom, gridBounds, nullptr);
            rtcSetGeometryIntersectFunction(geom, gridIntersect);
            rtcSetGeometryOccludedFunction(geom, gridOccluded);
            memory_.geometryBytes = static_cast<int64_t>(impl_->grid.bytes());
            primitives_ = impl_->grid.cells.size();
            break;
        }
    }
    rtcCommitGeometry(geom);
    plyGeom_ = rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    // Step 2: the optional opaque base mesh.
    if (options.baseMesh && !options.baseMesh->faces.empty()) {
        const BaseMesh& m = *options.baseMesh;
        for (const glm::dvec3& p : m.positions) impl_->basePositions.push_back(plies.toScene(p));
        impl_->basePositions.emplace_back(0.f);
        impl_->baseFaces = m.faces;
        for (const glm::uvec3& f : m.faces)
            if (f.x >= m.positions.size() || f.y >= m.positions.size() || f.z >= m.positions.size())
                throw Error("render: base mesh face refers to a vertex that does not exist");
        RTCGeometry bg = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(bg, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, impl_->basePositions.data(), 0,
                                   sizeof(glm::vec3), impl_->basePositions.size() - 1);
        rtcSetSharedGeometryBuffer(bg, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, impl_->baseFaces.data(), 0,
                                   sizeof(glm::uvec3), impl_->baseFaces.size());
        rtcCommitGeometry(bg);
        baseGeom_ = rtcAttachGeometry(scene_, bg);
        rtcReleaseGeometry(bg);
    }
    baseOffset_ = 1e-3f * plies.radius;
    // Step 3: build the BVH and measure what Embree allocated for it.
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) throw Error("render: Embree failed to build the scene");
    memory_.embreeBytes = device.allocatedBytes() - before;
    memory_.shadingBytes = static_cast<int64_t>(plies.shadingBytes());
}

TraceScene::~TraceScene() {
    if (scene_) rtcReleaseScene(scene_);
}

bool TraceScene::intersect(const glm::vec3& org, const glm::vec3& dir, float tnear, float tfar, TraceHit& hit,
                           const TraceHit* from) const {
    HitContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.segment = 0;
    ctx.u = 0;
    ctx.ignore = ignoreOf(from);
    RTCRayHit rh;
    rh.ray.org_x = org.x, rh.ray.org_y = org.y, rh.ray.org_z = org.z;
    rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
    rh.ray.tnear = tnear, rh.ray.tfar = tfar;
    rh.ray.time = 0, rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx.base, &rh);
    hit = TraceHit();
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.t = rh.ray.tfar;
    hit.geomID = rh.hit.geomID;
    hit.primID = rh.hit.primID;
    glm::vec3 ng = safeNormalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    if (rh.hit.geomID == baseGeom_) {
        hit.kind = TraceHit::Base;
        hit.segment = rh.hit.primID;
        hit.ng = ng;
        return true;
    }
    hit.kind = TraceHit::Ply;
    switch (options_.mode) {
        case GeometryMode::Curves: hit.segment = rh.hit.primID; break;  // primID = segment
        case GeometryMode::Tubes: hit.segment = impl_->tubes.segmentOfTriangle[rh.hit.primID]; break;
        case GeometryMode::Grid: hit.segment = ctx.segment; break;
    }
    // The ply normal is taken from the segment's centreline in every mode (the facet normal of a
    // tube or Embree's curve normal only decide which side was entered): shading, the side tests
    // of the integrator and the spawn offsets all use this one normal.
    float u;
    const glm::vec3 axis = axisNormal(plies_, hit.segment, org + hit.t * dir, u);
    hit.u = u;
    hit.ng = glm::length(axis) > 0 ? axis : ng;
    return true;
}

uint32_t TraceScene::ignoreOf(const TraceHit* from) const {
    return from && from->kind == TraceHit::Ply && options_.mode == GeometryMode::Tubes ? from->primID
                                                                                       : RTC_INVALID_GEOMETRY_ID;
}

bool TraceScene::occluded(const glm::vec3& org, const glm::vec3& dir, float tnear, float tfar,
                          const TraceHit* from) const {
    HitContext hc;
    rtcInitIntersectContext(&hc.base);
    hc.ignore = ignoreOf(from);
    RTCIntersectContext& ctx = hc.base;
    RTCRay ray;
    ray.org_x = org.x, ray.org_y = org.y, ray.org_z = org.z;
    ray.dir_x = dir.x, ray.dir_y = dir.y, ray.dir_z = dir.z;
    ray.tnear = tnear, ray.tfar = tfar;
    ray.time = 0, ray.mask = 0xFFFFFFFFu, ray.id = 0, ray.flags = 0;
    rtcOccluded1(scene_, &ctx, &ray);
    return ray.tfar < 0;
}

glm::vec3 TraceScene::spawn(const TraceHit& hit, const glm::vec3& p, const glm::vec3& dir) const {
    const bool outside = glm::dot(dir, hit.ng) > 0;
    if (hit.kind == TraceHit::Base) return p + (outside ? baseOffset_ : -baseOffset_) * hit.ng;
    // Offsets are measured from the centreline, not from the computed hit point, so errors of the
    // hit point (Embree's round curves can be off by several percent of the radius) cannot put the
    // origin on the wrong side: outside = beyond max(|p - c|, r), inside = within the inscribed
    // radius (the polygon of a tube) minus the offset.
    const uint32_t j = plies_.segments[hit.segment];
    const glm::vec3 a(plies_.points[j]), b(plies_.points[j + 1]);
    const glm::vec3 c = a + hit.u * (b - a);
    const float r = plies_.radius;
    if (outside) return c + hit.ng * (std::max(glm::length(p - c), r) * (1.f + outsideOffset));
    const float inscribed = options_.mode == GeometryMode::Tubes
                                ? std::cos(3.14159265f / float(std::max(3, options_.tubeSides)))
                                : 1.f;
    return c + hit.ng * (r * std::max(0.f, inscribed - insideOffset));
}

}  // namespace knit
