// frames_transport.hpp (internal) — the parts of curveFrames' double-reflection transport
// (frames.cpp, step 4) that do not depend on the normal being carried, for a block of steps at
// once (frames_transport.cpp): the segment vector and its reflection coefficient, the second
// reflection's vector and coefficient. What is left per step is the chain of the normal itself:
// two dot products and two scaled subtractions, without a division.
#pragma once
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace knit::impl {

constexpr size_t kTransportBlock = 64;

// Step k of a block carries the frame from point first + k to first + k + 1.
struct TransportBlock {
    enum Flag : uint8_t {
        kZeroSegment = 1,  // no first reflection (the segment is below the points' resolution)
        kStraight = 2,     // no second reflection (the reflected tangent is the next tangent)
        kReversal = 4,     // the tangent turns by more than 90 degrees: transport() decides
    };
    double v1[3][kTransportBlock];  // x1 - x0
    double a1[kTransportBlock];     // 2 / |v1|^2
    double v2[3][kTransportBlock];  // t1 - (t0 reflected in the plane normal to v1)
    double b2[kTransportBlock];     // 2 / |v2|^2
    uint8_t flags[kTransportBlock];
};

// Fills steps [0, count) of `b` (count <= kTransportBlock) for the steps from point `first`,
// four at a time in AVX2 where util::avx2Kernels() says so; bit for bit the same either way
// and the same operations as frames.cpp's transport().
void transportCoefficients(const glm::dvec3* x, const glm::dvec3* t, size_t first, size_t count, TransportBlock& b);

}  // namespace knit::impl
