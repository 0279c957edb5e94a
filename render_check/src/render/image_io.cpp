// Image output (PNG / EXR, atomic) and statistical image comparison.
#include "knit/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

#include <stb/stb_image_write.h>
#include <tinyexr.h>

#include "io/atomic_file.hpp"
#include "knit/error.hpp"
#include "knit/output_file.hpp"
#include "knit/ply_bsdf.hpp"

namespace knit {
namespace {

float toSrgb(float v) {
    v = std::clamp(v, 0.f, 1.f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

void checkImage(const Image& im, const std::string& path) {
    if (im.width < 1 || im.height < 1 || im.rgb.size() != size_t(3) * im.width * im.height)
        throw Error("cannot write image '" + path + "': the image is empty");
}

}  // namespace

void checkWritable(const std::string& path) {
    if (path.empty()) throw Error("image path is empty");
    impl::checkOutputFolder(path);  // the check every output of the project gets
}

// Both writers go through the project's atomic output file (a temporary sibling renamed when
// complete, removed on failure or SIGINT / SIGTERM).
void writePng(const std::string& path, const Image& im) {
    checkImage(im, path);
    std::vector<unsigned char> px(im.rgb.size());
    for (size_t i = 0; i < px.size(); ++i) px[i] = static_cast<unsigned char>(std::lround(toSrgb(im.rgb[i]) * 255.f));
    std::vector<unsigned char> png;
    const auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(context);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &png, im.width, im.height, 3, px.data(), im.width * 3))
        throw Error("cannot write image '" + path + "': PNG encoding failed");
    writeFileAtomically(
        path,
        [&](std::ostream& out) { out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size())); },
        true);
}

void writeExr(const std::string& path, const Image& im) {
    checkImage(im, path);
    // tinyexr writes to a file name: the atomic file's temporary sibling, renamed when complete.
    impl::AtomicFile file(path, true);
    file.close();
    const char* err = nullptr;
    if (SaveEXR(im.rgb.data(), im.width, im.height, 3, 0, file.tempPath().c_str(), &err) < 0) {
        const std::string msg = err ? err : "unknown error";
        if (err) FreeEXRErrorMessage(err);
        throw Error("cannot write image '" + path + "': " + msg);
    }
    file.commit();
}

ImageComparison compareImages(const Image& a, const Image& b, int block, double zLimit) {
    if (a.width != b.width || a.height != b.height) throw Error("comparing images: they differ in size");
    if (block < 1) throw Error("comparing images: the block size must be at least 1");
    ImageComparison c;
    double sumAbs = 0, sum2 = 0;
    const int n = a.width * a.height;
    for (int i = 0; i < n; ++i) {
        const double la = luminance(Rgb(a.rgb[3 * i], a.rgb[3 * i + 1], a.rgb[3 * i + 2]));
        const double lb = luminance(Rgb(b.rgb[3 * i], b.rgb[3 * i + 1], b.rgb[3 * i + 2]));
        sumAbs += std::abs(la - lb), sum2 += (la - lb) * (la - lb);
    }
    c.meanAbsDifference = sumAbs / n;
    c.rmse = std::sqrt(sum2 / n);
    double sumDiff = 0, sumVar = 0;  // whole image: difference of the means and its variance (x n^2)
    for (int by = 0; by < a.height; by += block)
        for (int bx = 0; bx < a.width; bx += block) {
            double ma = 0, mb = 0, va = 0, vb = 0;
            int count = 0;
            for (int y = by; y < std::min(a.height, by + block); ++y)
                for (int x = bx; x < std::min(a.width, bx + block); ++x) {
                    const int i = y * a.width + x;
                    ma += luminance(Rgb(a.rgb[3 * i], a.rgb[3 * i + 1], a.rgb[3 * i + 2]));
                    mb += luminance(Rgb(b.rgb[3 * i], b.rgb[3 * i + 1], b.rgb[3 * i + 2]));
                    va += a.variance.empty() ? 0 : a.variance[i];
                    vb += b.variance.empty() ? 0 : b.variance[i];
                    ++count;
                }
            sumDiff += ma - mb, sumVar += va + vb;
            ma /= count, mb /= count;
            const double se = std::sqrt((va + vb) / (double(count) * count));
            const double z = se > 0 ? std::abs(ma - mb) / se : (ma == mb ? 0.0 : 1e30);
            ++c.blocks;
            c.testedBlocks += se > 0;
            c.maxZ = std::max(c.maxZ, z);
            c.chiSquare += z * z;
            if (z > zLimit) ++c.outliers;
        }
    c.meanZ = sumVar > 0 ? sumDiff / std::sqrt(sumVar) : (sumDiff == 0 ? 0.0 : 1e30);
    return c;
}

}  // namespace knit
