// trace_scene.hpp — internal: the Embree scene for one geometry mode, and ray queries on it.
// (Internal to render_check, its tests and benchmarks: the public side is knit/trace_mode.hpp.)
//
// Modes (knit/trace_mode.hpp; one file each behind trace_geometry.hpp):
//   Curves: RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE over the ply segments (float4 x, y, z, r).
//   Tubes:  triangle meshes from knit::sweepTubes (the exporter's sweep; caps: see below).
//   Grid:   the two-stage idea: one RTC_GEOMETRY_TYPE_USER primitive per non-empty UV-grid cell;
//           its callback intersects only that cell's ply segments, as cylinders trimmed by the
//           bisector planes at the joints (round caps at open ends; joints bent by more than 157
//           degrees, where a mitre would reach 5 radii out, are round: cut perpendicular plus the
//           sphere beyond the cut). Segment points are stored 16-bit quantized per cell, with one
//           8-bit box per chunk of up to 8 segments; ray-cylinder tests run from the ray point
//           nearest each segment (float cancellation from far ray origins).
//   Tubes mode replaces the exporter's flat end caps by hemispheres, so all three modes model the
//   same solid (round ends); its triangles are wound outward and traced watertight
//   (RTC_SCENE_FLAG_ROBUST), entering hits decided by the facet normal, none closer than 1e-4
//   ply radii to the ray origin.
// Plies are solids seen from the outside: only hits where the ray enters a ply count (a ray that
// starts inside a ply leaves it without a hit). Spawned rays start on the outward normal through
// the hit's centreline point: at (1 + outsideOffset) times the hit's distance (at least the radius)
// when they leave on the outside, at (inscribed radius - insideOffset) when they are transmitted
// into the ply; so a spawned ray never re-hits the primitive it leaves (a convex ply piece cannot
// be re-entered from outside, and its exit is not a hit), whatever the error of the hit point.
// The optional base mesh is an opaque two-sided triangle mesh.
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "knit/base_mesh.hpp"
#include "knit/fiber_tables.hpp"
#include "knit/ply_geometry.hpp"
#include "knit/trace_mode.hpp"
#include "trace_surface.hpp"

namespace knit {

// An Embree device with a memory monitor (bytes Embree allocates). Pass it explicitly.
class EmbreeDevice {
public:
    explicit EmbreeDevice(const char* config = nullptr);
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;
    RTCDevice get() const { return device_; }
    int64_t allocatedBytes() const { return bytes_.load(); }

private:
    static bool monitor(void* user, ssize_t bytes, bool post);
    RTCDevice device_ = nullptr;
    std::atomic<int64_t> bytes_{0};
};

struct TraceSceneOptions {
    GeometryMode mode = GeometryMode::Curves;
    int tubeSides = 8;                                   // tubes mode
    const BaseMesh* baseMesh = nullptr;                  // optional opaque base surface (positions in metres)
    const std::vector<int64_t>* segmentCells = nullptr;  // grid mode: cell per segment (required)
    // Surface level (trace_surface.hpp): the base mesh masked and coloured by a bake; the plies
    // may then be empty.
    const SurfaceTexture* baseTexture = nullptr;
};

struct TraceHit {
    enum Kind : uint8_t { None, Ply, Base };
    Kind kind = None;
    float t = 0;
    glm::vec3 ng{0.f};     // unit normal: for plies, outward from the segment's centreline; for the
                           // base mesh, its counter-clockwise normal (the front of the cloth)
    uint32_t segment = 0;  // ply segment (Ply) or triangle (Base)
    float u = 0;           // position along the ply segment in [0, 1]; Base: Embree's barycentric u
    float v = 0;           // Base: Embree's barycentric v
    uint32_t geomID = RTC_INVALID_GEOMETRY_ID, primID = RTC_INVALID_GEOMETRY_ID;  // Embree primitive
};

class TraceGeometry;  // one geometry mode (trace_geometry.hpp)

class TraceScene {
public:
    TraceScene(EmbreeDevice& device, const PlyGeometry& plies, const TraceSceneOptions& options);
    ~TraceScene();
    TraceScene(const TraceScene&) = delete;
    TraceScene& operator=(const TraceScene&) = delete;

    // Closest entering hit in (tnear, tfar); scene units (PlyGeometry::toScene). `from` is the hit
    // a spawned ray leaves (tubes mode ignores that triangle: see tubeEntryFilter).
    bool intersect(const glm::vec3& org, const glm::vec3& dir, float tnear, float tfar, TraceHit& hit,
                   const TraceHit* from = nullptr) const;
    bool occluded(const glm::vec3& org, const glm::vec3& dir, float tnear, float tfar,
                  const TraceHit* from = nullptr) const;
    // Origin for a ray leaving `hit` at point p in direction dir (offset along +-ng).
    glm::vec3 spawn(const TraceHit& hit, const glm::vec3& p, const glm::vec3& dir) const;
    // The ply surface point of a Ply hit (tangent, centreline normal, radial, arc), as shading needs it.
    PlySurfacePoint plyPoint(const TraceHit& hit) const;
    // Albedo of a Base hit: the baked texel with a baseTexture, else `plain`.
    Rgb baseAlbedo(const TraceHit& hit, const Rgb& plain) const;
    // Diffuse transmittance of a Base hit: the baked texel with a baseTexture, else black.
    Rgb baseTransmittance(const TraceHit& hit) const;
    // The surface level's texture (null without one) and, for a Base hit, its triangle's tangent
    // space and texture uv.
    const SurfaceTexture* baseTexture() const { return options_.baseTexture; }
    ShadingFrame baseFrame(const TraceHit& hit) const { return surface_.frame(hit.segment); }
    glm::dvec2 baseUv(const TraceHit& hit) const { return surface_.uvAt(hit.segment, hit.u, hit.v); }
    // The texture pyramid level a ray from org along dir sees at its Base hit (SurfaceMesh::level).
    int baseLevel(const TraceHit& hit, const glm::vec3& org, const glm::vec3& dir) const {
        return surface_.level(hit.segment, org, dir, hit.t);
    }

    GeometryMode mode() const { return options_.mode; }
    const PlyGeometry& plies() const { return plies_; }
    const TraceMemory& memory() const { return memory_; }
    size_t primitiveCount() const { return primitives_; }

    float outsideOffset = 1e-3f;  // ply radii
    float insideOffset = 0.1f;    // ply radii

private:
    void attachBaseMesh(RTCDevice device, const BaseMesh& mesh);
    uint32_t ignoreOf(const TraceHit* from) const;
    const PlyGeometry& plies_;
    TraceSceneOptions options_;
    std::unique_ptr<TraceGeometry> geometry_;
    RTCScene scene_ = nullptr;
    unsigned plyGeom_ = RTC_INVALID_GEOMETRY_ID, baseGeom_ = RTC_INVALID_GEOMETRY_ID;
    std::vector<glm::vec3> basePositions_;  // scene units, padded by one element
    std::vector<glm::uvec3> baseFaces_;
    SurfaceMesh surface_;  // the MASK filter's data (baseTexture)
    TraceMemory memory_;
    size_t primitives_ = 0;
    float baseOffset_ = 0;
};

}  // namespace knit
