// Grid mode, the paper's two-stage idea: one Embree user primitive per non-empty UV-grid cell,
// whose callback intersects only that cell's ply segments, as cylinders trimmed by the bisector
// planes of their joints (round ends: trace_segments.hpp). Points are stored 16-bit quantized per
// cell, with one 8-bit box per chunk of up to 8 segments; ray-cylinder tests run from the ray
// point nearest each segment (float cancellation from far ray origins).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <glm/geometric.hpp>
#include <glm/gtc/type_precision.hpp>

#include "knit/error.hpp"
#include "trace_geometry.hpp"
#include "trace_segments.hpp"

namespace knit {
namespace {

constexpr int kChunk = 8;  // segments per chunk box (8-bit box per chunk)

struct GridRun {
    uint32_t firstSegment;
    uint32_t pointOffset;  // into qpoints: [prev], p0 .. p(count), [next]
    uint32_t chunkOffset;  // into chunk boxes (2 per chunk: lo, hi)
    uint16_t count;
    uint8_t hasPrev, hasNext;
    float radius;  // of its curve (scene units): plies 1, a view's yarn-level curves the bundle's
};

struct GridCell {
    float lo[3], hi[3];  // primitive bounds
    float qo[3], qs[3];  // dequantization: p = qo + q * qs
    uint32_t firstRun, runCount;
};

struct GridData {
    std::vector<GridCell> cells;
    std::vector<GridRun> runs;
    std::vector<glm::u16vec3> qpoints;
    std::vector<glm::u8vec3> boxes;  // chunk boxes on the cell's grid coarsened 257x (8 bit)
    float radius = 0;
    size_t bytes() const {
        return cells.size() * sizeof(GridCell) + runs.size() * sizeof(GridRun) + qpoints.size() * sizeof(glm::u16vec3) +
               boxes.size() * sizeof(glm::u8vec3);
    }
};

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
bool traverseCell(const GridData& g, const GridCell& cell, const RayData& r, float& tfar, bool anyHit, glm::vec3& ng,
                  uint32_t& segment, float& u) {
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
                if (hitPlySegment(r, point(p0 + k), point(p0 + k + 1), joints, run.radius, tfar, t, n, uu)) {
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
    const RayData r = rayData(rh->ray.org_x, rh->ray.org_y, rh->ray.org_z, rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z,
                              rh->ray.tnear);
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
    if (traverseCell(g, g.cells[args->primID], r, tfar, true, ng, seg, u))
        ray->tfar = -std::numeric_limits<float>::infinity();
}

// Consecutive segments [first, first + count) of one curve in one cell.
struct SegmentRun {
    uint32_t first, count;
};

// Runs of consecutive segments of one curve in one cell, grouped by cell (ordered by cell id).
std::map<int64_t, std::vector<SegmentRun>> runsByCell(const PlyGeometry& pg, const std::vector<int64_t>& cellOf) {
    std::map<int64_t, std::vector<SegmentRun>> byCell;
    for (uint32_t s = 0; s < pg.segmentCount(); ++s) {
        std::vector<SegmentRun>& runs = byCell[cellOf[s]];
        if (!runs.empty()) {
            SegmentRun& last = runs.back();
            if (last.first + last.count == s && pg.curveOfSegment[s] == pg.curveOfSegment[last.first] &&
                last.count < 65535) {
                ++last.count;
                continue;
            }
        }
        runs.push_back({s, 1});
    }
    return byCell;
}

glm::vec3 pointOf(const PlyGeometry& pg, uint32_t i) { return glm::vec3(pg.points[i]); }

// How far segment s reaches from its end points: mitred ends reach r / cos(half bend angle) from
// the joint. (From the half bend angle directly, so a joint near the mitre limit is covered
// whichever way the quantized points of the cell decide it.)
float segmentExtent(const PlyGeometry& pg, uint32_t s) {
    const float r = pg.points[pg.segments[s]].w;  // the curve's radius
    const uint32_t i = pg.segments[s];
    const glm::vec3 dir = safeNormalize(pointOf(pg, i + 1) - pointOf(pg, i));
    float e = r;
    if (pg.hasLeft(s))
        e = std::max(e, r / std::max(kMinMitreCos,
                                     0.5f * glm::length(safeNormalize(pointOf(pg, i) - pointOf(pg, i - 1)) + dir)));
    if (pg.hasRight(s))
        e = std::max(e, r / std::max(kMinMitreCos,
                                     0.5f * glm::length(dir + safeNormalize(pointOf(pg, i + 2) - pointOf(pg, i + 1)))));
    return e * 1.001f;
}

// A cell's primitive bounds (its segments grown by their extents) and its quantization frame
// (those bounds and the joint neighbours, on 65535 steps per axis).
GridCell cellFrame(const PlyGeometry& pg, const std::vector<SegmentRun>& runs) {
    GridCell cell;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    glm::vec3 qlo = lo, qhi = hi;
    for (const SegmentRun& run : runs)
        for (uint32_t s = run.first; s < run.first + run.count; ++s) {
            const uint32_t i = pg.segments[s];
            const float e = segmentExtent(pg, s);
            for (uint32_t j : {i, i + 1}) {
                lo = glm::min(lo, pointOf(pg, j) - e), hi = glm::max(hi, pointOf(pg, j) + e);
            }
            if (pg.hasLeft(s)) qlo = glm::min(qlo, pointOf(pg, i - 1)), qhi = glm::max(qhi, pointOf(pg, i - 1));
            if (pg.hasRight(s)) qlo = glm::min(qlo, pointOf(pg, i + 2)), qhi = glm::max(qhi, pointOf(pg, i + 2));
        }
    qlo = glm::min(qlo, lo), qhi = glm::max(qhi, hi);
    const glm::vec3 scale = glm::max(qhi - qlo, glm::vec3(1e-30f)) / 65535.f;
    for (int k = 0; k < 3; ++k) cell.lo[k] = lo[k], cell.hi[k] = hi[k], cell.qo[k] = qlo[k], cell.qs[k] = scale[k];
    return cell;
}

// Appends one run of a cell: its quantized points (with the joint neighbours) and chunk boxes.
void addRun(GridData& g, const GridCell& cell, const PlyGeometry& pg, const SegmentRun& run) {
    const glm::vec3 qlo(cell.qo[0], cell.qo[1], cell.qo[2]), scale(cell.qs[0], cell.qs[1], cell.qs[2]);
    auto quant = [&](const glm::vec3& p) {
        const glm::vec3 q = glm::round((p - qlo) / scale);
        return glm::u16vec3(glm::clamp(q, glm::vec3(0.f), glm::vec3(65535.f)));
    };
    auto quant8 = [&](const glm::vec3& p, bool up) {  // conservative: floor for lo, ceil for hi
        glm::vec3 q = (p - qlo) / (scale * 257.f);
        q = up ? glm::ceil(q) : glm::floor(q);
        return glm::u8vec3(glm::clamp(q, glm::vec3(0.f), glm::vec3(255.f)));
    };
    GridRun gr;
    gr.firstSegment = run.first;
    gr.count = static_cast<uint16_t>(run.count);
    gr.hasPrev = pg.hasLeft(run.first);
    gr.hasNext = pg.hasRight(run.first + run.count - 1);
    gr.radius = pg.points[pg.segments[run.first]].w;
    gr.pointOffset = static_cast<uint32_t>(g.qpoints.size());
    gr.chunkOffset = static_cast<uint32_t>(g.boxes.size());
    const uint32_t i0 = pg.segments[run.first];
    if (gr.hasPrev) g.qpoints.push_back(quant(pointOf(pg, i0 - 1)));
    for (uint32_t k = 0; k <= run.count; ++k) g.qpoints.push_back(quant(pointOf(pg, i0 + k)));
    if (gr.hasNext) g.qpoints.push_back(quant(pointOf(pg, i0 + run.count + 1)));
    for (uint32_t c = 0; c < run.count; c += kChunk) {
        glm::vec3 blo(std::numeric_limits<float>::max()), bhi(-std::numeric_limits<float>::max());
        for (uint32_t s = run.first + c; s < std::min(run.first + run.count, run.first + c + kChunk); ++s) {
            const float e = segmentExtent(pg, s);
            for (uint32_t j : {pg.segments[s], pg.segments[s] + 1})
                blo = glm::min(blo, pointOf(pg, j) - e), bhi = glm::max(bhi, pointOf(pg, j) + e);
        }
        g.boxes.push_back(quant8(blo, false));
        g.boxes.push_back(quant8(bhi, true));
    }
    g.runs.push_back(gr);
}

GridData buildGrid(const PlyGeometry& pg, const std::vector<int64_t>& cellOf) {
    GridData g;
    g.radius = pg.radius;
    // Step 1: runs of consecutive segments of one curve in one cell, grouped by cell.
    const std::map<int64_t, std::vector<SegmentRun>> byCell = runsByCell(pg, cellOf);
    // Step 2: per cell, bounds and quantization frame, then its runs' quantized points and boxes.
    for (const auto& [key, runs] : byCell) {
        GridCell cell = cellFrame(pg, runs);
        cell.firstRun = static_cast<uint32_t>(g.runs.size());
        cell.runCount = static_cast<uint32_t>(runs.size());
        for (const SegmentRun& run : runs) addRun(g, cell, pg, run);
        g.cells.push_back(cell);
    }
    return g;
}

class GridGeometry final : public TraceGeometry {
public:
    GridGeometry(const PlyGeometry& plies, const std::vector<int64_t>* segmentCells) {
        if (!segmentCells || segmentCells->size() != plies.segmentCount())
            throw Error("cannot render: grid mode needs a UV-grid cell for every ply segment");
        grid_ = buildGrid(plies, *segmentCells);
    }

    RTCGeometry newGeometry(RTCDevice device) override {
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(grid_.cells.size()));
        rtcSetGeometryUserData(geom, &grid_);
        rtcSetGeometryBoundsFunction(geom, gridBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, gridIntersect);
        rtcSetGeometryOccludedFunction(geom, gridOccluded);
        return geom;
    }
    // The callback found the segment (one primitive is a whole cell).
    uint32_t segmentOf(uint32_t, const HitContext& context) const override { return context.segment; }
    int64_t bytes() const override { return static_cast<int64_t>(grid_.bytes()); }
    size_t primitiveCount() const override { return grid_.cells.size(); }

private:
    GridData grid_;
};

}  // namespace

std::unique_ptr<TraceGeometry> makeGridGeometry(const PlyGeometry& plies, const std::vector<int64_t>* segmentCells) {
    return std::make_unique<GridGeometry>(plies, segmentCells);
}

}  // namespace knit
