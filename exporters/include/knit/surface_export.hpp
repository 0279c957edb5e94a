// knit/surface_export.hpp — the surface level of detail as a file: the base mesh with the knit
// baked into textures (render_check's knit/bake.hpp) as a standard glTF 2.0 PBR material, GLB
// with the PNG images embedded.
//
// What is written: one mesh (POSITION, NORMAL: the base mesh's angle-weighted vertex normals,
// TANGENT, TEXCOORD_0), one node at the mesh's local origin (float32 positions relative to it, the node
// translation in double), one material: baseColorTexture (sRGB albedo, alpha = coverage),
// normalTexture (tangent space: TANGENT xyz along increasing u, w such that
// w cross(NORMAL, TANGENT) runs along increasing v, the image's up), metallic 0, roughness `roughness`, doubleSided (cloth is seen from both sides),
// and one sampler with REPEAT wrapping and mipmaps.
// Texture repeat: TEXCOORD_0 = (u U, 1 - v V) for the mesh's uv = (u, v) and repeats (U, V) (the
// pattern's placement): one texture tile is one pattern cell, at the place the ply-level knit
// puts it (pattern origin at uv (0, 0); libknit's v up becomes glTF's t down, as for loaded
// glTF meshes). Scaling the coordinates instead of KHR_texture_transform keeps the file
// readable by clients without the extension.
// Alpha: MASK with cutoff 0.5 by default: coverage is the fraction of the cell's area under yarn,
// and a knit seen from afar is mostly opaque; MASK keeps depth writes and needs no sorting, which
// BLEND on one self-overlapping garment mesh would (wrong order of overlapping layers in
// real-time clients). BLEND (`alphaMode = Blend`) shows the partial transparency of sub-pixel
// gaps where a client sorts or the mesh does not overlap itself.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "knit/base_mesh.hpp"

namespace knit {

// 8-bit images, row-major from the top (knit/bake.hpp: baseColorRgba8, normalRgb8).
struct SurfaceImages {
    int width = 0, height = 0;
    std::vector<uint8_t> baseColorRgba;  // sRGB colour + linear alpha (coverage), 4 per pixel
    std::vector<uint8_t> normalRgb;      // tangent-space normal (n + 1) / 2, 3 per pixel
};

enum class SurfaceAlpha { Mask, Blend };

struct SurfaceExportOptions {
    std::string path;              // .glb
    glm::dvec2 repeats{1.0, 1.0};  // texture tiles (pattern periods) across u and v in [0, 1]
    SurfaceAlpha alphaMode = SurfaceAlpha::Mask;
    double alphaCutoff = 0.5;  // MASK
    double roughness = 0.85;   // yarn is a rough dielectric
    double normalScale = 1.0;
};

struct SurfaceExportStats {
    size_t vertices = 0, triangles = 0;
    size_t imageBytes = 0;  // PNG bytes embedded
    size_t bytes = 0;       // file size
};

// A view's surface level as part of a curve or tube glTF export (knit/export.hpp: exportScene's
// `surface`): the triangles (e.g. meshSubset of the surface-level faces), the baked images and
// the material options (`material.path` is not used).
struct SurfaceLayer {
    BaseMesh mesh;
    SurfaceImages images;
    SurfaceExportOptions material;
};

// The checks of the output path alone, for callers that fail before the bake: a .glb name in a
// writable folder (knit::Error naming the path).
void checkSurfaceOutput(const std::string& path);

// Throws knit::Error naming the path or the option: checkSurfaceOutput, empty mesh or missing UVs,
// image sizes that do not match, repeats not positive and finite, cutoff outside [0, 1].
// Writes through a temporary file renamed when complete (no partial file).
SurfaceExportStats exportSurface(const BaseMesh& mesh, const SurfaceImages& images,
                                 const SurfaceExportOptions& options);

}  // namespace knit
