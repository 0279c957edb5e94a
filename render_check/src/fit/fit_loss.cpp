// The fit's image loss: relative L2 on linear radiance plus (1 - multi-scale SSIM) on luminance,
// both weighted by an optional mask; and the block averaging the coarse stage and MS-SSIM use.
#include <algorithm>
#include <array>
#include <cmath>

#include "knit/error.hpp"
#include "knit/fit.hpp"

namespace knit {
namespace {

// A single-channel image with per-pixel weights (the mask).
struct LumaPlane {
    int width = 0, height = 0;
    std::vector<double> value, weight;
};

LumaPlane luminance(const Image& im, const std::vector<float>& mask, bool saturate) {
    LumaPlane p;
    p.width = im.width, p.height = im.height;
    const size_t n = size_t(im.width) * im.height;
    p.value.resize(n);
    p.weight.assign(n, 1.0);
    for (size_t i = 0; i < n; ++i) {
        const auto v = [&](int c) { return saturate ? std::min(im.rgb[3 * i + c], 1.f) : im.rgb[3 * i + c]; };
        p.value[i] = 0.2126 * v(0) + 0.7152 * v(1) + 0.0722 * v(2);
        if (!mask.empty()) p.weight[i] = mask[i];
    }
    return p;
}

// Halves the plane (2 x 2 averages; an odd last row/column is dropped).
LumaPlane halve(const LumaPlane& p) {
    LumaPlane h;
    h.width = p.width / 2, h.height = p.height / 2;
    h.value.resize(size_t(h.width) * h.height);
    h.weight.resize(h.value.size());
    for (int y = 0; y < h.height; ++y)
        for (int x = 0; x < h.width; ++x) {
            double v = 0, w = 0;
            for (int k = 0; k < 4; ++k) {
                const size_t i = size_t(2 * y + k / 2) * p.width + 2 * x + k % 2;
                v += p.value[i], w += p.weight[i];
            }
            h.value[size_t(y) * h.width + x] = v / 4, h.weight[size_t(y) * h.width + x] = w / 4;
        }
    return h;
}

// Mean SSIM of two planes of the same size: local statistics in a 7 x 7 Gaussian window
// (sigma 1.5, clamped at the border), averaged with the mask weight of the centre pixel.
// `range` is the dynamic range L of the constants C1 = (0.01 L)^2, C2 = (0.03 L)^2.
double meanSsim(const LumaPlane& a, const LumaPlane& b, double range) {
    std::array<double, 7> g{};
    for (int k = -3; k <= 3; ++k) g[size_t(k + 3)] = std::exp(-k * k / (2 * 1.5 * 1.5));
    const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
    double sum = 0, weights = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const double wc = a.weight[size_t(y) * a.width + x];
            if (wc <= 0) continue;
            double sw = 0, ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
            for (int dy = -3; dy <= 3; ++dy)
                for (int dx = -3; dx <= 3; ++dx) {
                    const int xx = std::clamp(x + dx, 0, a.width - 1), yy = std::clamp(y + dy, 0, a.height - 1);
                    const size_t i = size_t(yy) * a.width + xx;
                    const double w = g[size_t(dx + 3)] * g[size_t(dy + 3)] * a.weight[i];
                    const double va = a.value[i], vb = b.value[i];
                    sw += w, ma += w * va, mb += w * vb, aa += w * va * va, bb += w * vb * vb, ab += w * va * vb;
                }
            if (sw <= 0) continue;
            ma /= sw, mb /= sw;
            const double va = std::max(aa / sw - ma * ma, 0.0), vb = std::max(bb / sw - mb * mb, 0.0);
            const double cov = ab / sw - ma * mb;
            const double s = ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            sum += wc * s, weights += wc;
        }
    return weights > 0 ? sum / weights : 1.0;
}

}  // namespace

ImageLoss imageLoss(const Image& render, const Image& target, const std::vector<float>& mask,
                    const LossOptions& options) {
    if (render.width != target.width || render.height != target.height)
        throw Error("fit loss: the render is " + std::to_string(render.width) + " x " + std::to_string(render.height) +
                    " but the target is " + std::to_string(target.width) + " x " + std::to_string(target.height));
    const size_t n = size_t(target.width) * target.height;
    if (!mask.empty() && mask.size() != n) throw Error("fit loss: the mask does not have one weight per pixel");
    // Step 1: masked L2 on linear radiance, per channel relative to the target's mean squared
    // radiance in that channel (so a dark channel of a coloured yarn counts as much as a bright one).
    double se[3] = {0, 0, 0}, tt[3] = {0, 0, 0}, weights = 0;
    for (size_t i = 0; i < n; ++i) {
        const double w = mask.empty() ? 1.0 : mask[i];
        for (int c = 0; c < 3; ++c) {
            const double r = options.saturate ? std::min(render.rgb[3 * i + c], 1.f) : render.rgb[3 * i + c];
            const double d = r - target.rgb[3 * i + c];
            se[c] += w * d * d, tt[c] += w * double(target.rgb[3 * i + c]) * target.rgb[3 * i + c];
        }
        weights += w;
    }
    ImageLoss loss;
    const double floor = 1e-8 * std::max(tt[0] + tt[1] + tt[2], 1e-12);
    for (int c = 0; c < 3; ++c) loss.relativeL2 += se[c] / std::max(tt[c], floor) / 3;
    loss.rmse = weights > 0 ? std::sqrt((se[0] + se[1] + se[2]) / (3 * weights)) : 0;
    // Step 2: multi-scale SSIM of the luminance, the range taken from the target.
    LumaPlane a = luminance(render, mask, options.saturate), b = luminance(target, mask, false);
    const double range = std::max(*std::max_element(b.value.begin(), b.value.end()), 1e-6);
    double ssim = 0;
    int scales = 0;
    for (; scales < std::max(options.ssimScales, 1); ++scales) {
        if (scales > 0) {
            if (a.width < 8 || a.height < 8) break;
            a = halve(a), b = halve(b);
        }
        ssim += meanSsim(a, b, range);
    }
    loss.ssim = ssim / scales;
    // Step 3: the weighted sum.
    loss.total = loss.relativeL2 + options.ssimWeight * (1 - loss.ssim);
    return loss;
}

Image downsample(const Image& im, int factor) {
    if (factor <= 1) return im;
    Image out;
    out.width = im.width / factor, out.height = im.height / factor;
    out.rgb.assign(size_t(3) * out.width * out.height, 0.f);
    const float scale = 1.f / float(factor * factor);
    for (int y = 0; y < out.height * factor; ++y)
        for (int x = 0; x < out.width * factor; ++x)
            for (int c = 0; c < 3; ++c)
                out.rgb[3 * (size_t(y / factor) * out.width + x / factor) + c] +=
                    scale * im.rgb[3 * (size_t(y) * im.width + x) + c];
    return out;
}

std::vector<float> downsampleMask(const std::vector<float>& mask, int width, int height, int factor) {
    if (mask.empty() || factor <= 1) return mask;
    Image im;
    im.width = width, im.height = height;
    im.rgb.resize(3 * mask.size());
    for (size_t i = 0; i < mask.size(); ++i) im.rgb[3 * i] = im.rgb[3 * i + 1] = im.rgb[3 * i + 2] = mask[i];
    const Image small = downsample(im, factor);
    std::vector<float> out(size_t(small.width) * small.height);
    for (size_t i = 0; i < out.size(); ++i) out[i] = small.rgb[3 * i];
    return out;
}

}  // namespace knit
