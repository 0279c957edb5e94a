// The render flags of `knit render` (see render_flags.hpp).
#include "render_flags.hpp"

#include "choice.hpp"

namespace knit::cli {

void addRenderFlags(CLI::App& app, RenderOptions& o) {
    addChoice(app, "--light", o.light,
              Choices<LightPlacement>{{"front", LightPlacement::Front}, {"back", LightPlacement::Back}},
              "Light placement: front (camera side) or back (behind the cloth)");
    addChoice(app, "--mode", o.mode,
              Choices<GeometryMode>{
                  {"curves", GeometryMode::Curves}, {"tubes", GeometryMode::Tubes}, {"grid", GeometryMode::Grid}},
              "Geometry: curves (Embree round curves), tubes (swept meshes), grid (two-stage cells)");
    app.add_option("--spp", o.spp, "Samples per pixel (>= 1)");
    app.add_option("--output", o.output, "PNG image (sRGB)");
    app.add_option("--exr", o.exr, "Linear EXR image");
    app.add_option("--seed", o.seed, "Random seed (images are deterministic for a seed)");
    app.add_option("--material", o.materialFile, "Ply material JSON file (flags below override its fields)");
    auto scalar = [&](const char* flag, const char* field, const char* help) {
        app.add_option_function<double>(
            flag, [&o, field](double v) { o.materialOverrides[field] = {v}; }, help);
    };
    auto color = [&](const char* flag, const char* field, const char* help) {
        app.add_option_function<std::vector<double>>(
               flag, [&o, field](const std::vector<double>& v) { o.materialOverrides[field] = v; }, help)
            ->expected(1, 3)
            ->delimiter(',');
    };
    scalar("--eta", "eta", "Fiber index of refraction");
    scalar("--alpha-along", "alphaAlong", "R roughness along the fiber");
    scalar("--alpha-across", "alphaAcross", "R roughness across the fiber");
    color("--kR", "kR", "R weight (grey or r,g,b)");
    scalar("--alpha-tt", "alphaTT", "TT roughness");
    color("--kTT", "kTT", "TT weight (grey or r,g,b)");
    color("--body-albedo", "bodyAlbedo", "Body colour rho_B (grey or r,g,b); max(kR,kTT)+rho_B <= 1");
    scalar("--reflect-fraction", "reflectFraction", "Share r of the body lobe that is reflected");
    scalar("--fiber-count", "fiberCount", "Fibers per ply cross-section (tables)");
    scalar("--fiber-twist", "fiberTwist", "Fiber twist (radians per ply radius)");
    scalar("--fiber-shadow-floor", "fiberShadowFloor", "Fiber shadow floor thr");
    scalar("--ply-shadow-floor", "plyShadowFloor", "Ply shadow floor thr");
    app.add_flag_callback(
        "--no-fiber-detail", [&o] { o.materialOverrides["fiberDetail"] = {0.0}; },
        "Disable the fiber normal/tangent perturbation");
    app.add_option("--max-depth", o.maxDepth, "Maximum path length (bounces)");
    app.add_option("--env", o.environment, "Constant environment radiance");
    app.add_option("--light-irradiance", o.lightIrradiance, "Irradiance of the area light at the cloth centre");
    app.add_flag("--base-mesh", o.baseMesh, "Also render the base mesh (opaque, diffuse)");
    app.add_option("--tube-sides", o.tubeSides, "Sides of the swept tubes (tubes mode)");
}

}  // namespace knit::cli
