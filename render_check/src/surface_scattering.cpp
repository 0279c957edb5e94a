// SurfaceScattering: bins of equal solid angle, bilinear interpolation between bin centres on one
// side of the cloth, and importance sampling of a row by its luminance.
#include "knit/surface_scattering.hpp"

#include <algorithm>
#include <cmath>

#include "util/math.hpp"

namespace knit {
namespace {

using util::kPi;
using util::kTwoPi;

constexpr double kUniformShare = 0.15;  // of each row's sampling probability, spread over all bins

struct Corner {
    int bin = 0;
    double weight = 0;
};

double azimuth(const glm::dvec3& w) {
    const double phi = std::atan2(w.y, w.x);
    return phi < 0 ? phi + kTwoPi : phi;
}

// The four bins around w's position between bin centres, on w's side of the cloth (z >= 0 is
// the front), with their bilinear weights; azimuth wraps around.
void corners(const SurfaceScattering& s, const glm::dvec3& w, Corner out[4]) {
    const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    const double z = len > 0 ? w.z / len : 1.0;
    const int half = s.zBins / 2;
    const int lo = z >= 0 ? half : 0, hi = z >= 0 ? s.zBins - 1 : half - 1;
    const double fz = std::clamp(0.5 * (z + 1) * s.zBins - 0.5, double(lo), double(hi));
    const int iz0 = std::min(int(std::floor(fz)), hi), iz1 = std::min(iz0 + 1, hi);
    const double tz = fz - iz0;
    const double fp = azimuth(w) / kTwoPi * s.phiBins - 0.5;
    const double fl = std::floor(fp);
    const double tp = fp - fl;
    const int ip0 = (int(fl) % s.phiBins + s.phiBins) % s.phiBins, ip1 = (ip0 + 1) % s.phiBins;
    out[0] = {iz0 * s.phiBins + ip0, (1 - tz) * (1 - tp)};
    out[1] = {iz0 * s.phiBins + ip1, (1 - tz) * tp};
    out[2] = {iz1 * s.phiBins + ip0, tz * (1 - tp)};
    out[3] = {iz1 * s.phiBins + ip1, tz * tp};
}

double rowProbability(const SurfaceScattering& s, int row, int bin) {
    const float* c = s.cdf.data() + size_t(row) * s.bins();
    return bin == 0 ? c[0] : double(c[bin]) - double(c[bin - 1]);
}

}  // namespace

double SurfaceScattering::binSolidAngle() const { return 4 * kPi / bins(); }

int SurfaceScattering::binOf(const glm::dvec3& w) const {
    const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    const double z = w.z / len;
    const int half = zBins / 2;
    int iz = std::clamp(int(0.5 * (z + 1) * zBins), 0, zBins - 1);
    iz = z >= 0 ? std::max(iz, half) : std::min(iz, half - 1);  // rounding never crosses the cloth
    const int ip = std::clamp(int(azimuth(w) / kTwoPi * phiBins), 0, phiBins - 1);
    return iz * phiBins + ip;
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
    // Step 3: a uniform direction in the bin (uniform in z and azimuth: uniform in solid angle).
    const int iz = bin / phiBins, ip = bin % phiBins;
    double z = std::clamp(-1 + 2 * (iz + u[2]) / zBins, -1.0, 1.0);
    z = iz < zBins / 2 ? std::min(z, -1e-9) : std::max(z, 1e-9);  // on the bin's side of the cloth
    const double phi = kTwoPi * (ip + u[3]) / phiBins, r = std::sqrt(std::max(0.0, 1 - z * z));
    const glm::dvec3 in(r * std::cos(phi), r * std::sin(phi), z);
    pdfOut = pdf(out, in);
    return in;
}

}  // namespace knit
