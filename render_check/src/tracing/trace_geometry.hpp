// trace_geometry.hpp — internal: what the tracer needs from one geometry mode of the plies.
//
// One implementation per mode, one file each: trace_curves.cpp (Embree round linear curves),
// trace_tubes.cpp (swept tube triangle meshes), trace_grid.cpp (the two-stage UV-grid cells).
// TraceScene (trace_scene.cpp) picks one with makeTraceGeometry, attaches its Embree geometry
// next to the optional base mesh and turns Embree hits into TraceHits; the hit normal itself is
// the same for every mode (trace_segments.hpp: axisNormal).
#pragma once
#include <cstdint>
#include <memory>

#include <embree3/rtcore.h>

#include "knit/ply_geometry.hpp"
#include "trace_scene.hpp"

namespace knit {

// Ray context of every query: carries the segment and position of a user-geometry (grid) hit
// out of its callback, and the primitive a spawned ray leaves into the tubes' filter.
struct HitContext {
    RTCIntersectContext base;
    uint32_t segment;
    float u;
    uint32_t ignore;  // tubes mode: the triangle a spawned ray leaves (or RTC_INVALID_GEOMETRY_ID)
};

class TraceGeometry {
public:
    virtual ~TraceGeometry() = default;
    // Scene flags the mode needs (tubes: robust, i.e. watertight triangle tests).
    virtual RTCSceneFlags sceneFlags() const { return RTC_SCENE_FLAG_NONE; }
    // A new, uncommitted Embree geometry of the plies on `device`, with the mode's filter or
    // callbacks set; it refers to buffers owned by this object or by the PlyGeometry.
    virtual RTCGeometry newGeometry(RTCDevice device) = 0;
    // The ply segment of an Embree hit on this geometry (primID and the query's context).
    virtual uint32_t segmentOf(uint32_t primID, const HitContext& context) const = 0;
    // The primitive that a ray spawned from ply hit `from` must ignore (RTC_INVALID_GEOMETRY_ID:
    // none; the spawn offsets alone keep it off its origin).
    virtual uint32_t ignoredPrimitive(const TraceHit& from) const;
    // Radius, in ply radii, within which a transmitted ray starts inside the solid (1 for round
    // solids; the inscribed radius of a tube polygon).
    virtual float inscribedRadius() const { return 1.f; }
    // Our buffers needed to intersect, and the number of Embree primitives.
    virtual int64_t bytes() const = 0;
    virtual size_t primitiveCount() const = 0;
};

// The geometry of options.mode over the plies (validates the mode's options: knit::Error).
std::unique_ptr<TraceGeometry> makeTraceGeometry(const PlyGeometry& plies, const TraceSceneOptions& options);

std::unique_ptr<TraceGeometry> makeCurveGeometry(const PlyGeometry& plies);
std::unique_ptr<TraceGeometry> makeTubeGeometry(const PlyGeometry& plies, int sides);
std::unique_ptr<TraceGeometry> makeGridGeometry(const PlyGeometry& plies, const std::vector<int64_t>* segmentCells);

}  // namespace knit
