// The Embree scene of one geometry mode (trace_geometry.hpp) plus the optional base mesh, and its
// ray queries: entering hits with the centreline normal, occlusion, spawn offsets.
#include "trace_scene.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "knit/error.hpp"
#include "trace_geometry.hpp"
#include "trace_segments.hpp"

namespace knit {

EmbreeDevice::EmbreeDevice(const char* config) {
    device_ = rtcNewDevice(config);
    if (!device_)
        throw Error("cannot render: cannot create an Embree device (error " +
                    std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeDevice::monitor, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

bool EmbreeDevice::monitor(void* user, ssize_t bytes, bool) {
    static_cast<EmbreeDevice*>(user)->bytes_ += bytes;
    return true;
}

TraceScene::TraceScene(EmbreeDevice& device, const PlyGeometry& plies, const TraceSceneOptions& options)
    : plies_(plies), options_(options) {
    // A view may leave no curves (every visible cell at the surface level): the base mesh alone.
    const bool hasBase = options.baseMesh && !options.baseMesh->faces.empty();
    if (plies.segmentCount() == 0 && !hasBase)
        throw Error("cannot render: the scene has no ply segments (nothing to render)");
    const int64_t before = device.allocatedBytes();
    RTCDevice dev = device.get();
    scene_ = rtcNewScene(dev);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    // Step 1: the plies in the chosen mode (validates the mode's options).
    if (plies.segmentCount() > 0) {
        geometry_ = makeTraceGeometry(plies, options);
        rtcSetSceneFlags(scene_, geometry_->sceneFlags());
        RTCGeometry geom = geometry_->newGeometry(dev);
        rtcCommitGeometry(geom);
        plyGeom_ = rtcAttachGeometry(scene_, geom);
        rtcReleaseGeometry(geom);
        memory_.geometryBytes = geometry_->bytes();
        primitives_ = geometry_->primitiveCount();
    }
    // Step 2: the optional opaque base mesh.
    if (hasBase) attachBaseMesh(dev, *options.baseMesh);
    baseOffset_ = 1e-3f * plies.radius;
    // Step 3: build the BVH and measure what Embree allocated for it.
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) throw Error("cannot render: Embree failed to build the scene");
    memory_.embreeBytes = device.allocatedBytes() - before;
    memory_.shadingBytes = static_cast<int64_t>(plies.shadingBytes());
}

TraceScene::~TraceScene() {
    if (scene_) rtcReleaseScene(scene_);
}

void TraceScene::attachBaseMesh(RTCDevice device, const BaseMesh& m) {
    for (const glm::dvec3& p : m.positions) basePositions_.push_back(plies_.toScene(p));
    basePositions_.emplace_back(0.f);
    baseFaces_ = m.faces;
    for (const glm::uvec3& f : m.faces)
        if (f.x >= m.positions.size() || f.y >= m.positions.size() || f.z >= m.positions.size())
            throw Error("cannot render: base mesh face refers to a vertex that does not exist");
    RTCGeometry bg = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(bg, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, basePositions_.data(), 0,
                               sizeof(glm::vec3), basePositions_.size() - 1);
    rtcSetSharedGeometryBuffer(bg, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, baseFaces_.data(), 0, sizeof(glm::uvec3),
                               baseFaces_.size());
    if (options_.baseTexture) {  // the surface level: alpha MASK from the baked coverage
        surface_.mesh = &m, surface_.texture = options_.baseTexture, surface_.unit = plies_.unit;
        setSurfaceFilter(bg, surface_);
    }
    rtcCommitGeometry(bg);
    baseGeom_ = rtcAttachGeometry(scene_, bg);
    rtcReleaseGeometry(bg);
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
        // The counter-clockwise normal (the cloth's front), whatever side Embree's Ng is on.
        const glm::uvec3 f = baseFaces_[rh.hit.primID];
        const glm::vec3 ccw =
            glm::cross(basePositions_[f.y] - basePositions_[f.x], basePositions_[f.z] - basePositions_[f.x]);
        hit.ng = glm::dot(ccw, ng) < 0 ? -ng : ng;
        hit.u = rh.hit.u, hit.v = rh.hit.v;
        return true;
    }
    hit.kind = TraceHit::Ply;
    hit.segment = geometry_->segmentOf(rh.hit.primID, ctx);
    // The ply normal is taken from the segment's centreline in every mode (the facet normal of a
    // tube or Embree's curve normal only decide which side was entered): shading, the side tests
    // of the integrator and the spawn offsets all use this one normal.
    float u;
    const glm::vec3 axis = axisNormal(plies_, hit.segment, org + hit.t * dir, u);
    hit.u = u;
    hit.ng = glm::length(axis) > 0 ? axis : ng;
    return true;
}

PlySurfacePoint TraceScene::plyPoint(const TraceHit& h) const {
    const uint32_t j = plies_.segments[h.segment];
    const float u = h.u;
    PlySurfacePoint sp;
    sp.tangent = glm::dvec3(glm::vec3(plies_.points[j + 1]) - glm::vec3(plies_.points[j]));
    sp.normal = glm::dvec3(h.ng);  // centreline normal of the hit (see intersect)
    sp.radial = glm::dvec3((1 - u) * plies_.radial[j] + u * plies_.radial[j + 1]);
    sp.v = (1 - u) * plies_.arc[j] + u * plies_.arc[j + 1];
    sp.bundle = h.segment >= plies_.firstBundleSegment;
    // A yarn-level curve shows its plies' helices, not its own axis (PlyGeometry::bundleHelix).
    if (sp.bundle && plies_.bundleHelix != 0) {
        const double len = glm::length(sp.tangent), nn = glm::length(sp.normal);
        if (len > 0 && nn > 0) sp.tangent += plies_.bundleHelix * glm::cross(sp.tangent, sp.normal / nn);
    }
    return sp;
}

Rgb TraceScene::baseAlbedo(const TraceHit& hit, const Rgb& plain) const {
    if (!options_.baseTexture || hit.kind != TraceHit::Base) return plain;
    return options_.baseTexture->albedo(surface_.uvAt(hit.segment, hit.u, hit.v));
}

Rgb TraceScene::baseTransmittance(const TraceHit& hit) const {
    if (!options_.baseTexture || hit.kind != TraceHit::Base) return Rgb(0.0);
    return options_.baseTexture->transmittance(surface_.uvAt(hit.segment, hit.u, hit.v));
}

uint32_t TraceScene::ignoreOf(const TraceHit* from) const {
    return from && from->kind == TraceHit::Ply ? geometry_->ignoredPrimitive(*from) : RTC_INVALID_GEOMETRY_ID;
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

namespace {
constexpr float kBaseOffsetPerUnit = 1e-5f;  // ~80 float epsilons per scene unit of |p| + t
}  // namespace

glm::vec3 TraceScene::spawn(const TraceHit& hit, const glm::vec3& p, const glm::vec3& dir) const {
    const bool outside = glm::dot(dir, hit.ng) > 0;
    if (hit.kind == TraceHit::Base) {
        // The hit point's float error grows with its distance from the scene origin and the ray's
        // length (a garment is thousands of yarn radii across): the offset grows with both, else
        // spawned rays hit their own triangle again and darken the surface level.
        const float scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) + hit.t;
        const float offset = baseOffset_ + kBaseOffsetPerUnit * scale;
        return p + (outside ? offset : -offset) * hit.ng;
    }
    // Offsets are measured from the centreline, not from the computed hit point, so errors of the
    // hit point (Embree's round curves can be off by several percent of the radius) cannot put the
    // origin on the wrong side: outside = beyond max(|p - c|, r), inside = within the inscribed
    // radius (the polygon of a tube) minus the offset.
    const uint32_t j = plies_.segments[hit.segment];
    const glm::vec3 a(plies_.points[j]), b(plies_.points[j + 1]);
    const glm::vec3 c = a + hit.u * (b - a);
    const float r = plies_.radius;
    if (outside) return c + hit.ng * (std::max(glm::length(p - c), r) * (1.f + outsideOffset));
    return c + hit.ng * (r * std::max(0.f, geometry_->inscribedRadius() - insideOffset));
}

}  // namespace knit
