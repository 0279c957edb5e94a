// Curves mode: Embree's round linear curves (cones between spheres) over the ply segments, on the
// PlyGeometry's own buffers (float4 x, y, z, r; neighbour flags), entering hits only.
#include "trace_geometry.hpp"

namespace knit {
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

class CurveGeometry final : public TraceGeometry {
public:
    explicit CurveGeometry(const PlyGeometry& plies) : plies_(plies) {}

    RTCGeometry newGeometry(RTCDevice device) override {
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, plies_.points.data(), 0,
                                   sizeof(glm::vec4), plies_.points.size());
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, plies_.segments.data(), 0,
                                   sizeof(uint32_t), plies_.segments.size());
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, plies_.flags.data(), 0,
                                   sizeof(uint8_t), plies_.flags.size());
        rtcSetGeometryIntersectFilterFunction(geom, curveEntryFilter);
        rtcSetGeometryOccludedFilterFunction(geom, curveEntryFilter);
        return geom;
    }
    uint32_t segmentOf(uint32_t primID, const HitContext&) const override { return primID; }  // one per segment
    int64_t bytes() const override { return static_cast<int64_t>(plies_.intersectionBytes()); }
    size_t primitiveCount() const override { return plies_.segmentCount(); }

private:
    const PlyGeometry& plies_;
};

}  // namespace

std::unique_ptr<TraceGeometry> makeCurveGeometry(const PlyGeometry& plies) {
    return std::make_unique<CurveGeometry>(plies);
}

}  // namespace knit
