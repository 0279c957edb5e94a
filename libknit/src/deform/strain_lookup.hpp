// The trilinear strain-table lookup prepared once for a table (the per-frame hot loop of the
// strain-aware deformer): evenly spaced axes (as makeStrainTable's) are indexed directly and
// inline, others searched. Agrees with lookupStrainTable (knit/strain.hpp) to round-off.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

#include "knit/strain.hpp"

namespace knit {

// The strain of C = [[c00, c01], [c01, c11]] (strainOf's arithmetic, inline for the hot loop).
inline Strain strainOfC(double c00, double c01, double c11) {
    Strain s;
    const double a = std::sqrt(std::max(c00, 0.0)), b = std::sqrt(std::max(c11, 0.0));
    s.sx = a - 1;
    s.sy = b - 1;
    s.sa = a > 0 && b > 0 ? c01 / (a * b) : 0.0;
    return s;
}

class StrainLookup {
public:
    explicit StrainLookup(const StrainTable& table);  // keeps a reference to the table

    // Floats from the start of the table to `vertex`'s first row.
    size_t vertexOffset(uint32_t vertex) const { return vertexStride_ * size_t(vertex); }

    glm::dvec4 operator()(uint32_t vertex, const Strain& s, bool& clamped) const {
        return at(vertexOffset(vertex), s, clamped);
    }

    // Where a strain lies in the table (the same for every cell vertex): the offset of its lower
    // corner, the fractions along sx, sa, sy and the floats to the upper neighbours.
    struct Cell {
        size_t offset = 0;
        double t[3] = {0, 0, 0};
        size_t step[3] = {0, 0, 0};
    };
    // Sets `clamped` when a strain lies outside the axes (round-off beyond the end samples is not
    // counted).
    Cell locate(const Strain& s, bool& clamped) const {
        const double value[3] = {s.sx, s.sa, s.sy};
        Cell c;
        for (int a = 0; a < 3; ++a) {
            const Axis& ax = axes_[a];
            size_t i = 0;
            if (ax.even) {
                double v = value[a];
                if (!(v >= ax.first)) {  // NaN clamps to the first sample
                    clamped = clamped || !(v >= ax.first - 1e-9);
                    v = ax.first;
                } else if (v > ax.last) {
                    clamped = clamped || v > ax.last + 1e-9;
                    v = ax.last;
                }
                const double f = (v - ax.first) * ax.inverseStep;
                i = std::min(size_t(std::max(f, 0.0)), ax.lastInterval);
                c.t[a] = std::min(std::max(f - double(i), 0.0), 1.0);
                c.step[a] = ax.stride;
            } else {
                locateSlow(a, value[a], i, c.t[a], clamped);
                c.step[a] = ax.count > 1 ? ax.stride : 0;
            }
            c.offset += i * ax.stride;
        }
        return c;
    }

    // The trilinear blend at `cell` for the vertex whose rows start at `vertexOffset`: along sx,
    // then sa, then sy (each a linear blend of two rows).
    glm::dvec4 blend(const Cell& cell, size_t vertexOffset) const {
        const float* r = data_ + vertexOffset + cell.offset;
        const size_t s0 = cell.step[0], s1 = cell.step[1], s2 = cell.step[2];
        const double* t = cell.t;
        const auto row = [r](size_t o) { return glm::dvec4(r[o], r[o + 1], r[o + 2], r[o + 3]); };
        const auto mix = [](const glm::dvec4& a, const glm::dvec4& b, double w) { return a + w * (b - a); };
        const glm::dvec4 c00 = mix(row(0), row(s0), t[0]), c10 = mix(row(s1), row(s1 + s0), t[0]);
        const glm::dvec4 c01 = mix(row(s2), row(s2 + s0), t[0]), c11 = mix(row(s2 + s1), row(s2 + s1 + s0), t[0]);
        return mix(mix(c00, c10, t[1]), mix(c01, c11, t[1]), t[2]);
    }

    glm::dvec4 at(size_t vertexOffset, const Strain& s, bool& clamped) const {
        return blend(locate(s, clamped), vertexOffset);
    }

private:
    struct Axis {
        const std::vector<double>* values = nullptr;
        double first = 0, last = 0, inverseStep = 0;
        size_t stride = 0;        // floats between neighbouring samples
        size_t count = 0;         // samples
        size_t lastInterval = 0;  // count - 2 (0 for a single sample)
        bool even = false;
    };
    void locateSlow(int axis, double v, size_t& i, double& t, bool& clamped) const;

    Axis axes_[3];
    const float* data_ = nullptr;
    size_t vertexStride_ = 0;
};

}  // namespace knit
