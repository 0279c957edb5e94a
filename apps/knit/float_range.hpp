// float_range.hpp — refuses an export that would write a value beyond its type's range (inf in a
// float32 file or point cache): radii, ply pitch and coordinates, naming the option or input that drives it.
#pragma once
#include "knit/export.hpp"
#include "knit/scene.hpp"

namespace knit::cli {

// Throws knit::Error when the yarn radius, the ply radii or pitch (when plies are written), or
// the coordinates of a float32 format (.bcc, .gltf, .glb, .pbrt, .pc2, .mdd: world positions,
// glTF node translations) exceed the float32 range.
void refuseValuesBeyondFloat32(const Scene& scene, const ExportOptions& options);

}  // namespace knit::cli
