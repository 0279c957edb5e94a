// Photographs for the fit: read PNG (sRGB) or EXR (linear) as linear RGB, read a mask, and lay
// targets and renders side by side.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <stb/stb_image.h>
#include <tinyexr.h>

#include "knit/error.hpp"
#include "knit/fit.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

// IEC 61966-2-1 decoding of an 8-bit sRGB value.
float decodeSrgb(unsigned char v) {
    const double c = v / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

std::string where(const std::string& option, const std::string& path) { return option + " '" + path + "'"; }

void checkFile(const std::string& path, const std::string& option) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(where(option, path) + ": the file does not exist");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(where(option, path) + ": is not a regular file");
}

// RGBA float32 from an EXR file.
Image readExr(const std::string& path, const std::string& option) {
    float* rgba = nullptr;
    int w = 0, h = 0;
    const char* err = nullptr;
    if (LoadEXR(&rgba, &w, &h, path.c_str(), &err) != TINYEXR_SUCCESS) {
        const std::string why = err ? err : "unknown reason";
        if (err) FreeEXRErrorMessage(err);
        throw Error(where(option, path) + ": cannot read the EXR image (" + why + ")");
    }
    Image im;
    im.width = w, im.height = h;
    im.rgb.resize(size_t(3) * w * h);
    for (size_t i = 0; i < size_t(w) * h; ++i)
        for (int c = 0; c < 3; ++c) im.rgb[3 * i + c] = rgba[4 * i + c];
    std::free(rgba);
    return im;
}

// 8-bit RGB from any format stb reads, decoded from sRGB.
Image readStb(const std::string& path, const std::string& option) {
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load(path.c_str(), &w, &h, &n, 3);
    if (!px) throw Error(where(option, path) + ": cannot read the image (" + stbi_failure_reason() + ")");
    Image im;
    im.width = w, im.height = h;
    im.rgb.resize(size_t(3) * w * h);
    std::transform(px, px + im.rgb.size(), im.rgb.begin(), decodeSrgb);
    stbi_image_free(px);
    return im;
}

}  // namespace

Image readLinearImage(const std::string& path, const std::string& option) {
    checkFile(path, option);
    Image im = util::lowerExtension(path) == "exr" ? readExr(path, option) : readStb(path, option);
    for (float v : im.rgb)
        if (!std::isfinite(v) || v < 0)
            throw Error(where(option, path) + ": holds a negative or non-finite value (not a radiance image)");
    return im;
}

FitTarget readFitTarget(const std::string& path, const std::string& option) {
    return {readLinearImage(path, option), option + " '" + path + "'", util::lowerExtension(path) != "exr"};
}

std::vector<float> readMask(const std::string& path, const std::string& option, int width, int height) {
    checkFile(path, option);
    std::vector<float> mask;
    int w = 0, h = 0;
    if (util::lowerExtension(path) == "exr") {
        const Image im = readExr(path, option);
        w = im.width, h = im.height;
        for (size_t i = 0; i < size_t(w) * h; ++i) mask.push_back(std::clamp(im.rgb[3 * i], 0.f, 1.f));
    } else {
        int n = 0;
        unsigned char* px = stbi_load(path.c_str(), &w, &h, &n, 1);
        if (!px) throw Error(where(option, path) + ": cannot read the mask (" + stbi_failure_reason() + ")");
        mask.assign(px, px + size_t(w) * h);
        for (float& v : mask) v /= 255.f;
        stbi_image_free(px);
    }
    if (w != width || h != height)
        throw Error(where(option, path) + ": the mask is " + std::to_string(w) + " x " + std::to_string(h) +
                    " but the photographs are " + std::to_string(width) + " x " + std::to_string(height));
    if (*std::max_element(mask.begin(), mask.end()) <= 0)
        throw Error(where(option, path) + ": the mask is empty (every pixel is 0)");
    return mask;
}

Image sideBySide(const Image& frontTarget, const Image& frontFit, const Image& backTarget, const Image& backFit) {
    const int w = frontTarget.width, h = frontTarget.height;
    Image out;
    out.width = 2 * w, out.height = 2 * h;
    out.rgb.assign(size_t(3) * out.width * out.height, 0.f);
    const Image* tiles[4] = {&frontTarget, &frontFit, &backTarget, &backFit};
    for (int t = 0; t < 4; ++t) {
        const int ox = (t % 2) * w, oy = (t / 2) * h;
        for (int y = 0; y < h; ++y)
            std::copy_n(tiles[t]->rgb.begin() + size_t(3) * y * w, 3 * w,
                        out.rgb.begin() + size_t(3) * ((oy + y) * out.width + ox));
    }
    return out;
}

}  // namespace knit
