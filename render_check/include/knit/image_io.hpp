// knit/image_io.hpp — writing rendered images (PNG sRGB via stb, linear EXR via tinyexr) without
// partial files (temporary file in the same folder, then rename), and comparing two renders.
#pragma once
#include <string>

#include "knit/path_tracer.hpp"

namespace knit {

// Throws knit::Error naming the path when a file cannot be created there (checked before a render).
void checkWritable(const std::string& path);
void writePng(const std::string& path, const Image& image);  // sRGB, 8 bit, clamped
void writeExr(const std::string& path, const Image& image);  // linear float32 RGB

// Block-wise comparison of two renders of the same view: the image is cut into blocks of
// `block` x `block` pixels; per block the luminance difference of the means is divided by its
// standard error (from the per-pixel variances). Blocks whose z exceeds `zLimit` are outliers.
// When both images estimate the same expected image with independent noise (different seeds),
// each block z is close to a standard normal, so chiSquare = sum of z^2 follows a chi-square law
// with `blocks` degrees of freedom and meanZ (the same statistic over the whole image) is a
// standard normal: the most sensitive test for a global brightness difference.
struct ImageComparison {
    int blocks = 0;
    int testedBlocks = 0;  // blocks with a non-zero standard error (chi-square dof)
    int outliers = 0;
    double maxZ = 0;
    double chiSquare = 0;          // sum over blocks of z^2
    double meanZ = 0;              // signed z of the whole-image mean luminance difference (a - b)
    double meanAbsDifference = 0;  // over pixels, luminance
    double rmse = 0;               // over pixels, luminance
};
ImageComparison compareImages(const Image& a, const Image& b, int block = 8, double zLimit = 4.0);

}  // namespace knit
