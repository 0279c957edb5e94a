// knit/polylines.hpp — flat storage for many curves (yarns, plies) in one array.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace knit {

// Curves stored back to back: curve c owns points [offsets[c], offsets[c+1]).
// A closed curve stores each point once; the segment last -> first is implied by closed[c] != 0.
struct Polylines {
    std::vector<glm::dvec3> points;
    std::vector<uint32_t> offsets{0};  // size curveCount() + 1
    std::vector<uint8_t> closed;       // size curveCount()

    size_t curveCount() const { return closed.size(); }
    size_t pointCount() const { return points.size(); }
    uint32_t begin(size_t c) const { return offsets[c]; }
    uint32_t end(size_t c) const { return offsets[c + 1]; }
    uint32_t size(size_t c) const { return offsets[c + 1] - offsets[c]; }
    bool isClosed(size_t c) const { return closed[c] != 0; }
    // Number of segments of curve c (a closed curve has as many segments as points).
    uint32_t segmentCount(size_t c) const {
        const uint32_t n = size(c);
        return n < 2 ? 0 : (isClosed(c) ? n : n - 1);
    }
    // Appends one curve; returns its index.
    size_t addCurve(const glm::dvec3* p, size_t n, bool isClosedCurve) {
        points.insert(points.end(), p, p + n);
        offsets.push_back(static_cast<uint32_t>(points.size()));
        closed.push_back(isClosedCurve ? 1 : 0);
        return closed.size() - 1;
    }
    // Appends every curve of `more` (its offsets shifted past this one's points). The caller keeps
    // the total under 2^32 points.
    void append(const Polylines& more) {
        const uint32_t base = static_cast<uint32_t>(points.size());
        points.insert(points.end(), more.points.begin(), more.points.end());
        for (size_t c = 1; c < more.offsets.size(); ++c) offsets.push_back(base + more.offsets[c]);
        closed.insert(closed.end(), more.closed.begin(), more.closed.end());
    }
};

}  // namespace knit
