// SurfaceScattering: bins of equal solid angle on a concentric square per side of the cloth,
// bilinear interpolation between bin centres on one side, and importance sampling of a row by
// its luminance.
#include "knit/surface_scattering.hpp"

#include <algorithm>
#include <cmath>

#include "util/math.hpp"

namespace knit {
namespace {

using util::kPi;

constexpr double kUniformShare = 0.15;  // of each row's sampling probability, spread over all bins
constexpr double kQuarterPi = 0.25 * kPi;

struct Corner {
    int bin = 0;
    double weight = 0;
};

// A direction's side of the cloth (1 = front, z >= 0) and its point (a, b) in [-1, 1]^2.
struct SquarePoint {
    int side = 1;
    double a = 0, b = 0;
};

// Lambert's equal-area projection of the hemisphere to the unit disk, then the inverse of the
// concentric map (disk to square).
SquarePoint toSquare(const glm::dvec3& w) {
    const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    SquarePoint p;
    p.side = w.z >= 0 ? 1 : 0;
    const double z = std::min(1.0, std::abs(w.z) / len);
    const double r = std::sqrt(std::max(0.0, 1 - z));  // disk radius
    if (!(r > 0)) return p;
    double phi = std::atan2(w.y, w.x);
    if (phi < -kQuarterPi) phi += 2 * kPi;  // phi in [-pi/4, 7 pi/4)
    if (phi < kQuarterPi) {
        p.a = r, p.b = phi / kQuarterPi * r;
    } else if (phi < 3 * kQuarterPi) {
        p.b = r, p.a = -(phi - 2 * kQuarterPi) / kQuarterPi * r;
    } else if (phi < 5 * kQuarterPi) {
        p.a = -r, p.b = -(phi - 4 * kQuarterPi) / kQuarterPi * r;
    } else {
        p.b = -r, p.a = (phi - 6 * kQuarterPi) / kQuarterPi * r;
    }
    p.a = std::clamp(p.a, -1.0, 1.0), p.b = std::clamp(p.b, -1.0, 1.0);
    return p;
}

// The concentric map (square to disk), then the disk back to the hemisphere on `side`.
glm::dvec3 fromSquare(int side, double a, double b) {
    double r = 0, phi = 0;
    if (a != 0 || b != 0) {
        if (std::abs(a) > std::abs(b)) r = a, phi = kQuarterPi * (b / a);
        else r = b, phi = 2 * kQuarterPi - kQuarterPi * (a / b);
    }
    const double r2 = std::min(1.0, r * r), s = std::sqrt(std::max(0.0, 2 - r2));
    const double z = 1 - r2;
    return {r * std::cos(phi) * s, r * std::sin(phi) * s, side == 1 ? z : -z};
}

// The four bins around w's position between bin centres, on w's side of the cloth, with their
// bilinear weights (clamped at the square's edge, the horizon).
void corners(const SurfaceScattering& s, const glm::dvec3& w, Corner out[4]) {
    const SquarePoint p = toSquare(w);
    const int n = s.side, base = p.side * n * n;
    const double fx = std::clamp(0.5 * (p.a + 1) * n - 0.5, 0.0, double(n - 1));
    const double fy = std::clamp(0.5 * (p.b + 1) * n - 0.5, 0.0, double(n - 1));
    const int x0 = std::min(int(fx), n - 1), y0 = std::min(int(fy), n - 1);
    const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
    const double tx = fx - x0, ty = fy - y0;
    out[0] = {base + y0 * n + x0, (1 - tx) * (1 - ty)};
    out[1] = {base + y0 * n + x1, tx * (1 - ty)};
    out[2] = {base + y1 * n + x0, (1 - tx) * ty};
    out[3] = {base + y1 * n + x1, tx * ty};
}

double rowProbability(const SurfaceScattering& s, int row, int bin) {
    const float* c = s.cdf.data() + size_t(row) * s.bins();
    return bin == 0 ? c[0] : double(c[bin]) - double(c[bin - 1]);
}

}  // namespace

void SurfaceScattering::interpolationCorners(const glm::dvec3& w, int bins[4], double weights[4]) const {
    Corner c[4];
    corners(*this, w, c);
    for (int k = 0; k < 4; ++k) bins[k] = c[k].bin, weights[k] = c[k].weight;
}

double SurfaceScattering::binSolidAngle() const { return 2 * kPi / (side * side); }

int SurfaceScattering::binOf(const glm::dvec3& w) const {
    const SquarePoint p = toSquare(w);
    const int x = std::clamp(int(0.5 * (p.a + 1) * side), 0, side - 1);
    const int y = std::clamp(int(0.5 * (p.b + 1) * side), 0, side - 1);
    return p.side * side * side + y * side + x;
}

glm::dvec3 SurfaceScattering::binDirection(int bin, double u, double v) const {
    const int h = bin / (side * side), cell = bin % (side * side);
    const double a = -1 + 2 * (cell % side + u) / side, b = -1 + 2 * (cell / side + v) / side;
    glm::dvec3 w = fromSquare(h, a, b);
    // On the bin's side of the cloth, also on the horizon.
    w.z = h == 0 ? std::min(w.z, -1e-9) : std::max(w.z, 1e-9);
    return w;
}

double SurfaceScattering::binCosine(int bin) const {
    // |z| = 1 - r^2 with r = max(|a|, |b|) on the concentric square: its mean over the cell.
    const int cell = bin % (side * side);
    constexpr int k = 16;
    double sum = 0;
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            const double a = -1 + 2 * (cell % side + (i + 0.5) / k) / side;
            const double b = -1 + 2 * (cell / side + (j + 0.5) / k) / side;
            const double r = std::max(std::abs(a), std::abs(b));
            sum += 1 - r * r;
        }
    return sum / (k * k);
}

void SurfaceScattering::prepare() {
    const int n = bins();
    cdf.assign(size_t(n) * n, 0.f);
    for (int row = 0; row < n; ++row) {
        const float* t = table.data() + size_t(3) * n * row;
        double total = 0;
        for (int b = 0; b < n; ++b) total += std::max(0.0, luminance(Rgb(t[3 * b], t[3 * b + 1], t[3 * b + 2])));
        double run = 0;
        for (int b = 0; b < n; ++b) {
            const double l = std::max(0.0, luminance(Rgb(t[3 * b], t[3 * b + 1], t[3 * b + 2])));
            run += total > 0 ? (1 - kUniformShare) * l / total + kUniformShare / n : 1.0 / n;
            cdf[size_t(row) * n + b] = float(run);
        }
        cdf[size_t(row) * n + n - 1] = 1.f;
    }
}

double SurfaceScattering::passAt(const glm::dvec3& out) const {
    Corner c[4];
    corners(*this, out, c);
    double p = 0;
    for (const Corner& k : c) p += k.weight * pass[k.bin];
    return p;
}

Rgb SurfaceScattering::eval(const glm::dvec3& out, const glm::dvec3& in) const {
    Corner o[4], i[4];
    corners(*this, out, o);
    corners(*this, in, i);
    const size_t n = size_t(bins());
    Rgb f(0.0);
    for (const Corner& a : o)
        for (const Corner& b : i) {
            const float* t = table.data() + 3 * (n * a.bin + b.bin);
            f += a.weight * b.weight * Rgb(t[0], t[1], t[2]);
        }
    return f / binSolidAngle();
}

double SurfaceScattering::pdf(const glm::dvec3& out, const glm::dvec3& in) const {
    Corner o[4];
    corners(*this, out, o);
    const int bin = binOf(in);
    double p = 0;
    for (const Corner& a : o) p += a.weight * rowProbability(*this, a.bin, bin);
    return p / binSolidAngle();
}

glm::dvec3 SurfaceScattering::sample(const glm::dvec3& out, const double u[4], double& pdfOut) const {
    Corner o[4];
    corners(*this, out, o);
    // Step 1: the row, by the interpolation weights.
    int row = o[3].bin;
    double acc = 0;
    for (const Corner& a : o) {
        acc += a.weight;
        if (u[0] < acc) {
            row = a.bin;
            break;
        }
    }
    // Step 2: the bin, by the row's cumulative probabilities.
    const int n = bins();
    const float* c = cdf.data() + size_t(row) * n;
    const int bin = std::min(int(std::upper_bound(c, c + n, float(u[1])) - c), n - 1);
    // Step 3: a uniform direction in the bin (the map keeps solid angle).
    const glm::dvec3 in = binDirection(bin, u[2], u[3]);
    pdfOut = pdf(out, in);
    return in;
}

}  // namespace knit
