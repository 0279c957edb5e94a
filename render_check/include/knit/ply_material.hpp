// knit/ply_material.hpp — parameters of the ply BSDF, their validation and JSON loading.
//
// The lobes (see ply_bsdf.hpp): specular reflection R (anisotropic GGX, dielectric Fresnel),
// specular transmission TT (the GGX lobe mirrored through the surface plane), body reflection and
// transmission (Lambertian, times the fiber/ply shadow factor S'). Colours are linear RGB.
#pragma once
#include <string>

#include <glm/vec3.hpp>

namespace knit {

using Rgb = glm::dvec3;

struct PlyMaterial {
    double eta = 1.5;                  // fiber index of refraction (dielectric Fresnel of R / TT)
    double alphaAlong = 0.4;           // R roughness along the fiber (local x)
    double alphaAcross = 0.4;          // R roughness across the fiber (local y)
    Rgb kR{0.3};                       // R weight
    double alphaTT = 0.9;              // TT roughness (isotropic)
    Rgb kTT{0.1};                      // TT weight
    Rgb bodyAlbedo{0.55, 0.32, 0.18};  // rho_B: body colour (reflection + transmission)
    double reflectFraction = 0.5;      // r: share of the body lobe reflected (1 - r transmitted)
    // Fiber detail (1D tables built at start-up, see fiber_tables.hpp).
    bool fiberDetail = true;        // perturb the shading frame by the fiber tables
    int fiberCount = 40;            // fibers on the ring of one ply cross-section
    double fiberTwist = -1.5;       // tau_f: fiber helix rate, radians per ply radius along the ply
    double fiberShadowFloor = 0.4;  // thr: S' = S (1 - thr) + thr for the fiber-level shadow
    double plyShadowFloor = 0.3;    // same for the ply-level shadow (plies around the yarn)
    int tableSize = 1000;           // texels per 1D table
    int aoRays = 1000;              // 2D rays per texel for the shadow (AO) tables
};

// The body albedo of a ply whose yarn has a colour (a pattern with colours, linear RGB in
// [0, 1]): the yarn colour at the material's body brightness, colour * max_k bodyAlbedo[k]. It
// keeps the energy bound of a valid material (every channel is at most the brightest one).
Rgb yarnBodyAlbedo(const PlyMaterial& material, const glm::vec3& colour);
// Throws knit::Error naming the field when a value is out of range or not finite, or when the
// energy bound max(kR, kTT) + bodyAlbedo <= 1 fails in some channel (then albedo may exceed 1).
// `where` prefixes the message (e.g. a file name).
void validateMaterial(const PlyMaterial& material, const std::string& where = "material");

// Parses a JSON material: the fields of the object in `text` override `base`; invalid JSON, a
// value that is not an object, unknown fields and wrong types are errors naming `source` and the
// field ("<source>: unknown field 'x'"). Colours are a number (grey) or [r, g, b]. As in a file,
// text after the first JSON value is not read. The result is validated.
PlyMaterial parseMaterialJson(const std::string& text, const std::string& source, const PlyMaterial& base = {});
// Reads a JSON material file (see parseMaterialJson); errors name the file
// ("material file '<path>': ...").
PlyMaterial loadMaterialFile(const std::string& path, const PlyMaterial& base = {});
// Every field of `material` as a JSON object text, which parseMaterialJson reads back exactly.
std::string materialJsonText(const PlyMaterial& material);

}  // namespace knit
