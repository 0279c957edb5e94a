// The strain convention and the trilinear table lookup (see knit/strain.hpp).
#include <algorithm>
#include <cmath>

#include "knit/strain.hpp"
#include "strain_lookup.hpp"

namespace knit {

Strain strainOf(const glm::dmat2& C) { return strainOfC(C[0][0], C[1][0], C[1][1]); }

glm::dmat2 latticeMap(const Strain& s) {
    return glm::dmat2(glm::dvec2(1 + s.sx, 0.0),
                      (1 + s.sy) * glm::dvec2(s.sa, std::sqrt(std::max(0.0, 1 - s.sa * s.sa))));
}

namespace {

// The interval of `axis` holding v (clamped) and the fraction along it. Round-off beyond the end
// samples (a strain of exactly the largest sample computed from a mesh) is not counted as clamped.
void locateOnAxis(const std::vector<double>& axis, double v, size_t& i, double& t, bool& clamped) {
    constexpr double kSlack = 1e-9;
    if (axis.size() == 1) {
        i = 0;
        t = 0;
        clamped = clamped || !(std::abs(v - axis[0]) <= kSlack);
        return;
    }
    if (!(v >= axis.front())) {  // NaN clamps to the first sample
        clamped = clamped || !(v >= axis.front() - kSlack);
        v = axis.front();
    } else if (v > axis.back()) {
        clamped = clamped || v > axis.back() + kSlack;
        v = axis.back();
    }
    const auto it = std::upper_bound(axis.begin(), axis.end(), v);
    i = std::min(size_t(std::max<std::ptrdiff_t>(it - axis.begin() - 1, 0)), axis.size() - 2);
    t = (v - axis[i]) / (axis[i + 1] - axis[i]);
}

}  // namespace

glm::dvec4 lookupStrainTable(const StrainTable& table, uint32_t vertex, const Strain& s, bool* clamped) {
    const size_t nx = table.axes[0].size(), na = table.axes[1].size(), ny = table.axes[2].size();
    size_t i[3] = {0, 0, 0};
    double t[3] = {0, 0, 0};
    bool c = false;
    locateOnAxis(table.axes[0], s.sx, i[0], t[0], c);
    locateOnAxis(table.axes[1], s.sa, i[1], t[1], c);
    locateOnAxis(table.axes[2], s.sy, i[2], t[2], c);
    if (clamped) *clamped = c;
    const size_t base = nx * na * ny * size_t(vertex);
    glm::dvec4 out(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        double w = 1;
        size_t k[3];
        for (int a = 0; a < 3; ++a) {
            const bool up = (corner >> a) & 1;
            const size_t count = table.axes[size_t(a)].size();
            k[a] = std::min(i[a] + (up ? 1 : 0), count - 1);
            w *= up ? t[a] : 1 - t[a];
        }
        if (w == 0) continue;
        const float* row = &table.data[4 * (base + k[0] + nx * k[1] + nx * na * k[2])];
        out += w * glm::dvec4(row[0], row[1], row[2], row[3]);
    }
    return out;
}

StrainLookup::StrainLookup(const StrainTable& table) : data_(table.data.data()) {
    size_t stride = 4;
    for (size_t a = 0; a < 3; ++a) {
        const std::vector<double>& v = table.axes[a];
        Axis& ax = axes_[a];
        ax.values = &v;
        ax.first = v.front();
        ax.last = v.back();
        ax.stride = stride;
        ax.count = v.size();
        ax.lastInterval = v.size() >= 2 ? v.size() - 2 : 0;
        stride *= v.size();
        ax.even = v.size() >= 2;
        const double step = v.size() >= 2 ? (v.back() - v.front()) / double(v.size() - 1) : 0.0;
        for (size_t i = 1; ax.even && i < v.size(); ++i)
            ax.even = std::abs(v[i] - (v.front() + double(i) * step)) <= 1e-9 * std::max(1.0, std::abs(step));
        ax.inverseStep = ax.even ? 1.0 / step : 0.0;
    }
    vertexStride_ = stride;
}

void StrainLookup::locateSlow(int axis, double v, size_t& i, double& t, bool& clamped) const {
    locateOnAxis(*axes_[axis].values, v, i, t, clamped);
}

}  // namespace knit
