// fitMaterial: minimise the front + back image loss over the free material fields with NLopt's
// BOBYQA (bounded, derivative-free), coarse stage then full size, every render with the same seed.
#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "knit/error.hpp"
#include "knit/fit.hpp"
#include "fit_renderer.hpp"

namespace knit {
namespace {

using Clock = std::chrono::steady_clock;

// One resolution of the fit: targets (and mask) at that size and the samples per pixel.
struct Stage {
    int index = 0, factor = 1, spp = 1;
    Image front, back;
    std::vector<float> mask;
    int maxEvaluations = 0;
    double seconds = 0;
};

// What the objective needs between NLopt calls.
struct Search {
    FitRenderer* renderer = nullptr;
    const FitOptions* options = nullptr;
    const FitSpace* space = nullptr;
    const Stage* stage = nullptr;
    FitResult* result = nullptr;
    Clock::time_point start;
    double stageBest = 1e300;
    std::vector<double> bestX;                           // best of the current stage
    double fullBest = 1e300;                             // best full-size loss (what the result reports)
    bool frontSaturates = false, backSaturates = false;  // 8-bit targets: renders clipped at 1
    std::string failure;  // an exception inside the objective (NLopt is C: it must not unwind)
};

double elapsed(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Image render(const Search& s, const PlyMaterial& m, LightPlacement light) {
    return s.renderer->render(m, light, s.stage->front.width, s.stage->front.height, s.stage->spp);
}

// The loss of x at the current stage: render front and back, compare, keep the best.
double evaluate(Search& s, const std::vector<double>& x) {
    const PlyMaterial m = s.space->material(x);
    Image front = render(s, m, LightPlacement::Front), back = render(s, m, LightPlacement::Back);
    s.result->renders += 2;
    LossOptions lo = s.options->loss;
    lo.saturate = s.frontSaturates;
    const ImageLoss lf = imageLoss(front, s.stage->front, s.stage->mask, lo);
    lo.saturate = s.backSaturates;
    const ImageLoss lb = imageLoss(back, s.stage->back, s.stage->mask, lo);
    FitIteration it;
    it.evaluation = int(s.result->history.size()) + 1;
    it.stage = s.stage->index;
    it.frontLoss = lf.total, it.backLoss = lb.total, it.loss = lf.total + lb.total;
    it.values = s.space->values(m);
    s.result->history.push_back(it);
    if (s.options->progress) s.options->progress(it);
    if (it.loss < s.stageBest) s.stageBest = it.loss, s.bestX = x;
    if (s.stage->factor == 1 && it.loss < s.fullBest) {
        s.fullBest = it.loss;
        s.result->material = m, s.result->values = it.values, s.result->loss = it.loss;
        s.result->front = lf, s.result->back = lb;
        s.result->frontRender = std::move(front), s.result->backRender = std::move(back);
    }
    return it.loss;
}

double objective(unsigned n, const double* x, double* /*grad: derivative-free*/, void* data) {
    auto& s = *static_cast<Search*>(data);
    try {
        return evaluate(s, std::vector<double>(x, x + n));
    } catch (const std::exception& e) {
        s.failure = e.what();
        return HUGE_VAL;
    }
}

const char* stopReason(nlopt_result r) {
    switch (r) {
        case NLOPT_FTOL_REACHED: return "converged (the loss changes less than the tolerance)";
        case NLOPT_XTOL_REACHED: return "converged (the parameters change less than the tolerance)";
        case NLOPT_MAXEVAL_REACHED: return "evaluation limit reached";
        case NLOPT_MAXTIME_REACHED: return "time budget reached";
        case NLOPT_STOPVAL_REACHED: return "loss target reached";
        case NLOPT_ROUNDOFF_LIMITED: return "stopped by round-off";
        default: return r > 0 ? "converged" : "optimiser failed";
    }
}

// Runs NLopt over one stage from s.bestX; returns NLopt's reason.
std::string runStage(Search& s, const Stage& stage) {
    s.stage = &stage;
    s.stageBest = 1e300;
    const unsigned n = unsigned(s.space->size());
    // BOBYQA needs two or more dimensions; one free value goes to Sbplx (also bounded, derivative-free).
    std::unique_ptr<nlopt_opt_s, void (*)(nlopt_opt)> opt(nlopt_create(n >= 2 ? NLOPT_LN_BOBYQA : NLOPT_LN_SBPLX, n),
                                                          nlopt_destroy);
    nlopt_set_lower_bounds1(opt.get(), 0.0);
    nlopt_set_upper_bounds1(opt.get(), 1.0);
    nlopt_set_min_objective(opt.get(), objective, &s);
    nlopt_set_ftol_rel(opt.get(), s.options->relativeTolerance);
    nlopt_set_xtol_abs1(opt.get(), 1e-3);
    nlopt_set_maxeval(opt.get(), std::max(stage.maxEvaluations, 1));
    nlopt_set_maxtime(opt.get(), std::max(stage.seconds, 1e-3));
    nlopt_set_initial_step1(opt.get(), stage.factor > 1 ? 0.15 : 0.05);
    std::vector<double> x = s.bestX;
    double f = 0;
    const nlopt_result r = nlopt_optimize(opt.get(), x.data(), &f);
    if (!s.failure.empty()) throw Error("fit: " + s.failure);
    return stopReason(r);
}

// The coarse factor: the largest f <= requested dividing both sizes that leaves >= 16 x 12 pixels
// (smaller images hold too little structure for the SSIM window and the loss is mostly noise).
int coarseFactor(int width, int height, int requested) {
    for (int f = requested; f >= 2; --f)
        if (width % f == 0 && height % f == 0 && width / f >= 16 && height / f >= 12) return f;
    return 1;
}

bool uniform(const Image& im, const std::vector<float>& mask) {
    float lo = 1e30f, hi = -1e30f;
    for (size_t i = 0; i < im.rgb.size(); ++i)
        if (mask.empty() || mask[i / 3] > 0) lo = std::min(lo, im.rgb[i]), hi = std::max(hi, im.rgb[i]);
    return hi - lo <= 1e-6f * std::max(hi, 1e-6f);
}

}  // namespace

void checkFitTargets(const FitTarget& front, const FitTarget& back, const std::vector<float>& mask) {
    const auto size = [](const Image& im) { return std::to_string(im.width) + " x " + std::to_string(im.height); };
    for (const FitTarget* t : {&front, &back})
        if (t->image.width < 1 || t->image.height < 1 ||
            t->image.rgb.size() != size_t(3) * t->image.width * t->image.height)
            throw Error(t->source + ": the image is empty");
    if (front.image.width != back.image.width || front.image.height != back.image.height)
        throw Error(back.source + " is " + size(back.image) + " but " + front.source + " is " + size(front.image) +
                    ": the two photographs must have the same size");
    if (!mask.empty() && mask.size() != size_t(front.image.width) * front.image.height)
        throw Error("fit: the mask does not have one weight per pixel of the photographs (" + size(front.image) + ")");
}

namespace {

std::vector<Stage> makeStages(const FitTarget& front, const FitTarget& back, const std::vector<float>& mask,
                              const FitOptions& o) {
    std::vector<Stage> stages;
    const int w = front.image.width, h = front.image.height, f = coarseFactor(w, h, o.coarseFactor);
    const int coarseEvaluations = f > 1 ? int(std::lround(o.coarseShare * o.maxEvaluations)) : 0;
    if (f > 1 && coarseEvaluations > 0) {
        Stage c;
        c.index = 0, c.factor = f, c.spp = std::min(o.coarseSpp, o.render.spp);
        c.front = downsample(front.image, f), c.back = downsample(back.image, f);
        c.mask = downsampleMask(mask, w, h, f);
        c.maxEvaluations = coarseEvaluations, c.seconds = o.coarseShare * o.budgetSeconds;
        stages.push_back(std::move(c));
    }
    Stage full;
    full.index = 1, full.factor = 1, full.spp = o.render.spp;
    full.front = front.image, full.back = back.image, full.mask = mask;
    full.maxEvaluations = std::max(o.maxEvaluations - coarseEvaluations, 1);
    stages.push_back(std::move(full));
    return stages;
}

}  // namespace

FitResult fitMaterial(const Scene& scene, const FitTarget& front, const FitTarget& back, const std::vector<float>& mask,
                      const FitOptions& options) {
    const Clock::time_point start = Clock::now();
    // Step 1: validate the targets, the options and the free fields against the energy bound.
    checkFitTargets(front, back, mask);
    if (!(options.budgetSeconds > 0)) throw Error("fit: the time budget must be positive (seconds)");
    if (options.maxEvaluations < 1) throw Error("fit: at least one evaluation is needed");
    if (options.render.spp < 1) throw Error("fit: the samples per pixel must be at least 1");
    const PlyMaterial base = resolveMaterial(options.render);
    const std::vector<FitParameter> params =
        options.parameters.empty() ? parseFitList("kR,kTT,body-albedo") : options.parameters;
    const FitSpace space(params, base, options.boundOption);
    FitResult result;
    result.labels = space.labels();
    for (const FitTarget* t : {&front, &back})
        if (uniform(t->image, mask))
            result.warnings.push_back(t->source + " is uniform (a solid colour): no ply material reproduces a cloth's "
                                                  "structure there; the result is the best fit of its mean colour");
    // Step 2: coarse then full-size search, each stage starting at the previous stage's best.
    FitRenderer renderer(scene, options.render);
    Search s;
    s.renderer = &renderer, s.options = &options, s.space = &space, s.result = &result, s.start = start;
    s.frontSaturates = front.saturates, s.backSaturates = back.saturates;
    s.bestX = space.vector(base);
    std::vector<Stage> stages = makeStages(front, back, mask, options);
    for (Stage& stage : stages) {
        const double left = options.budgetSeconds - elapsed(start);
        stage.seconds = stage.factor > 1 ? std::min(stage.seconds, left) : left;
        result.stopReason = runStage(s, stage);
    }
    // Step 3: a budget the coarse stage used up still gets one full-size evaluation of its best.
    if (result.frontRender.rgb.empty()) evaluate(s, s.bestX);
    // Step 4: a match no material reaches is said, with the best fit kept.
    if (std::min(result.front.ssim, result.back.ssim) < 0.3)
        result.warnings.push_back("poor match: the best fit's SSIM is " + std::to_string(result.front.ssim) +
                                  " (front) and " + std::to_string(result.back.ssim) +
                                  " (back); check the scene and camera options against the photographs");
    validateMaterial(result.material, "fitted material");
    result.seconds = elapsed(start);
    return result;
}

}  // namespace knit
