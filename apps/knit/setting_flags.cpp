// The flags of the settings library messages name (see setting_flags.hpp).
#include "setting_flags.hpp"

namespace knit::cli {

const std::vector<SettingSpelling>& settingFlags() {
    static const std::vector<SettingSpelling> flags = {
        // The scene: placement, binding, plies, memory.
        {"the repeats", "--repeats"},
        {"the gauge", "--gauge"},
        {"the clamp tolerance", "--clamp-tolerance"},
        {"the weld tolerance", "--weld-tolerance"},
        {"the number of plies", "--plies"},
        {"the ply radius", "--ply-radius"},
        {"the ply centre radius", "--ply-center-radius"},
        {"the ply pitch", "--ply-pitch"},
        {"the samples per turn", "--samples-per-turn"},
        {"the twist direction", "--twist"},
        {"the samples per stitch", "--samples"},
        // The generator's model.
        {"the generator's yarn radius", "--radius"},
        {"the loop height", "--h"},
        {"the row gap", "--row-gap"},
        {"the loop width", "--a"},
        {"the over/under depth", "--d"},
        {"the model yarn radius", "--model-radius"},
        {"the memory budget", "--max-memory"},
        {"the deform mode", "--deform"},
        {"the mesh resolution", "--mesh-res"},
        // The view.
        {"the eye position", "--eye"},
        {"the target position", "--target"},
        {"the up direction", "--up"},
        {"the field of view", "--fov"},
        {"the image width", "--width"},
        {"the image height", "--height"},
        {"the environment radiance", "--env"},
        {"the light irradiance", "--light-irradiance"},
        // Charts.
        {"the float limit", "--max-float"},
        // The export.
        {"what to export", "--export"},
        {"the number of tube sides", "--sides"},
        {"the vertices per chunk", "--chunk-vertices"},
        {"Draco compression", "--draco"},
        {"the Draco position bits", "--draco-bits"},
        {"the Draco level", "--draco-level"},
        {"mesh quantization", "--quantize"},
        {"meshopt compression", "--meshopt"},
        {"the surface level alone", "--surface-only"},
        // Animation.
        {"the fitted parameters", "--fit"},
        {"the parameter bounds", "--bound"},
        {"the frame sequence", "--frames"},
        {"the frame rate", "--fps"},
        {"the frame step", "--step"},
        {"the last frame", "--last"},
        // Strain tables.
        {"the sx range", "--sx-range"},
        {"the sa range", "--sa-range"},
        {"the sy range", "--sy-range"},
        // The ply material: messages name a field as the --material file spells it, which the
        // render flags override.
        {"'eta'", "--eta"},
        {"'alphaAlong'", "--alpha-along"},
        {"'alphaAcross'", "--alpha-across"},
        {"'kR'", "--kR"},
        {"'alphaTT'", "--alpha-tt"},
        {"'kTT'", "--kTT"},
        {"'bodyAlbedo'", "--body-albedo"},
        {"'reflectFraction'", "--reflect-fraction"},
        {"'fiberCount'", "--fiber-count"},
        {"'fiberTwist'", "--fiber-twist"},
        {"'fiberShadowFloor'", "--fiber-shadow-floor"},
        {"'plyShadowFloor'", "--ply-shadow-floor"},
    };
    return flags;
}

std::string withFlags(const std::string& message) { return spellSettings(message, settingFlags()); }

}  // namespace knit::cli
