// knit/fit.hpp — fit the ply material to two photographs of the fabric, one lit from the front
// (reflection) and one lit from behind (transmission), as `knit fit` does.
//
// Pipeline: read the photographs (PNG sRGB or EXR linear) and an optional mask -> choose the free
// material fields and their bounds (energy-conserving by construction) -> minimise the image loss
// (L2 on linear radiance + multi-scale SSIM, both lightings) with a bounded derivative-free method
// (NLopt BOBYQA), coarse to fine, every render with the same seed (common random numbers) ->
// report the best material, the fitted renders and their per-image error.
// Renders go through renderScene (render.hpp) with the caller's scene and render options, so the
// fitted images are exactly what `knit render` shows for the same options.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "knit/path_tracer.hpp"
#include "knit/ply_material.hpp"
#include "knit/render.hpp"

namespace knit {

class Scene;

// ---- Images (fit_images.cpp) ----

struct FitTarget {
    Image image;             // linear RGB
    std::string source;      // named in messages ("the front-lit photograph 'f.png'")
    bool saturates = false;  // an 8-bit image (PNG): radiance above 1 was clipped to 1
};

// Reads a photograph as linear RGB: PNG/JPEG/... through stb (sRGB decoded to linear), EXR through
// tinyexr (already linear). Errors name `option` and the path ("--front 'f.png': ...").
Image readLinearImage(const std::string& path, const std::string& option);
// The photograph as a fit target: read, named "<option> '<path>'", saturating unless it is an EXR.
FitTarget readFitTarget(const std::string& path, const std::string& option);
// Reads a mask (any image stb or tinyexr reads; the first channel, 0 = ignore, 1 = use, values in
// between weight the pixel) that must be width x height; errors name `option` and the path.
std::vector<float> readMask(const std::string& path, const std::string& option, int width, int height);
// Side by side for a person to look at: targets in the left column, renders in the right, front
// row above the back row. All four images must have the same size.
Image sideBySide(const Image& frontTarget, const Image& frontFit, const Image& backTarget, const Image& backFit);

// ---- Loss (fit_loss.cpp) ----

struct LossOptions {
    double ssimWeight = 0.5;  // weight of (1 - MS-SSIM) next to the relative L2 term
    int ssimScales = 3;       // scales of the multi-scale SSIM (each halves the image; stops at 4 px)
    bool saturate = false;    // clamp the render to [0, 1] first, as an 8-bit photograph saturates
};

struct ImageLoss {
    double relativeL2 = 0;  // per channel: mean squared linear-radiance difference / mean squared target
                            // radiance; averaged over the channels
    double rmse = 0;        // root mean squared linear-radiance difference (over pixels and channels)
    double ssim = 1;        // multi-scale SSIM of the luminance (mean over scales), 1 = identical
    double total = 0;       // relativeL2 + ssimWeight (1 - ssim)
};

// Loss of `render` against `target` (same size) over the pixels of `mask` (empty = all; else one
// weight per pixel).
ImageLoss imageLoss(const Image& render, const Image& target, const std::vector<float>& mask,
                    const LossOptions& options = {});
// The image (and mask) averaged over factor x factor blocks (width and height divisible by factor).
Image downsample(const Image& image, int factor);
std::vector<float> downsampleMask(const std::vector<float>& mask, int width, int height, int factor);

// ---- Free parameters (fit_parameters.cpp) ----

// A material field the fit may change, with its bounds. Names as the render flags spell them:
// kR, kTT (grey weights), body-albedo (RGB: three free values), reflect-fraction, alpha-along,
// alpha-across, alpha-tt, fiber-shadow-floor, ply-shadow-floor, fiber-twist.
struct FitParameter {
    std::string name;
    double lower = 0, upper = 1;
};

// The default bounds of a field; knit::Error naming `option` for an unknown name.
FitParameter fitParameter(const std::string& name, const std::string& option = "the fitted parameters");
// "kR,kTT,body-albedo" -> the fields with default bounds (duplicates and unknown names are errors).
std::vector<FitParameter> parseFitList(const std::string& list, const std::string& option = "the fitted parameters");
// Applies "NAME=LO:HI" to the matching entry of `params` (it must be free), checking LO <= HI and
// the field's valid range; errors name `option`.
void applyFitBound(std::vector<FitParameter>& params, const std::string& bound,
                   const std::string& option = "the parameter bounds");

// The free fields of a fit and the map between a material and the optimiser's vector x in
// [0, 1]^n. Body albedo is stored as a fraction of the energy left by max(kR, kTT), so every x in
// the box is an energy-conserving material (max(kR, kTT) + body albedo <= 1 per channel).
class FitSpace {
public:
    // Checks the bounds against the fixed fields of `base`: a box in which some point breaks the
    // energy bound (e.g. kR up to 0.9 with body albedo from 0.3) is a knit::Error naming `option`.
    FitSpace(std::vector<FitParameter> params, const PlyMaterial& base,
             const std::string& option = "the parameter bounds");
    size_t size() const { return dims_; }
    const std::vector<FitParameter>& parameters() const { return params_; }
    PlyMaterial material(const std::vector<double>& x) const;       // x in [0, 1]^n -> material
    std::vector<double> vector(const PlyMaterial& material) const;  // clamped into the box
    // The free values of a material, in the order of parameters() (body albedo as 3 values), and
    // their labels ("kR", "body-albedo.r", ...).
    std::vector<double> values(const PlyMaterial& material) const;
    std::vector<std::string> labels() const;

private:
    std::vector<FitParameter> params_;
    PlyMaterial base_;
    size_t dims_ = 0;
};

// ---- The fit (fit.cpp) ----

// One loss evaluation (two renders: front and back).
struct FitIteration {
    int evaluation = 0;  // 1-based, over all stages
    int stage = 0;       // 0 = coarse, 1 = full size
    double loss = 0, frontLoss = 0, backLoss = 0;
    std::vector<double> values;  // the free values (FitSpace::values order)
};

struct FitOptions {
    RenderOptions render;                              // scene view, lights, spp (full stage), seed, base material
    std::vector<FitParameter> parameters;              // free fields (empty: kR, kTT, body-albedo)
    std::string boundOption = "the parameter bounds";  // named in bound errors (the CLI: --bound)
    LossOptions loss;
    double budgetSeconds = 600;                         // wall-clock budget of the whole fit (both stages)
    int maxEvaluations = 200;                           // loss evaluations over both stages
    int coarseFactor = 4;                               // coarse stage: images divided by (up to) this factor ...
    int coarseSpp = 4;                                  // ... rendered with this many samples per pixel
    double coarseShare = 0.6;                           // share of the evaluations and the budget for the coarse stage
    double relativeTolerance = 1e-4;                    // stop when a step changes the loss by less (relative)
    std::function<void(const FitIteration&)> progress;  // after every evaluation (may be empty)
};

struct FitResult {
    PlyMaterial material;  // the best fit (full-size loss), validated
    std::vector<std::string> labels;
    std::vector<double> values;  // the best free values
    std::vector<FitIteration> history;
    ImageLoss front, back;  // of the best material at full size
    Image frontRender, backRender;
    double loss = 0;
    int renders = 0;
    double seconds = 0;
    std::string stopReason;             // why the optimiser stopped (last stage)
    std::vector<std::string> warnings;  // e.g. a uniform target no material can match
};

// knit::Error unless both targets are non-empty images of the same size and the mask (if not
// empty) has one weight per pixel; messages name the targets' sources.
void checkFitTargets(const FitTarget& front, const FitTarget& back, const std::vector<float>& mask);

// Fits the material of `options.render` to the two photographs (same size; the mask, if not
// empty, one weight per pixel). knit::Error for bad input, naming the target's source.
FitResult fitMaterial(const Scene& scene, const FitTarget& front, const FitTarget& back, const std::vector<float>& mask,
                      const FitOptions& options);

}  // namespace knit
