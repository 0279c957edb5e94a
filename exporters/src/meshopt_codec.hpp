// meshopt_codec.hpp (internal) — EXT_meshopt_compression: meshoptimizer's vertex and index codecs
// for one glTF bufferView (built with KNIT_WITH_MESHOPT; without it every call throws knit::Error).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace knit::impl {

// One compressed bufferView: the bytes of the extension's buffer range, and what the extension
// object records about them (count elements of byteStride bytes, mode ATTRIBUTES or TRIANGLES).
struct MeshoptView {
    std::vector<unsigned char> bytes;
    size_t count = 0;
    size_t stride = 0;
    const char* mode = "ATTRIBUTES";
};

// Throws knit::Error naming the build option when the library was built without meshoptimizer.
void requireMeshopt();

// Vertex codec (version 0): `count` elements of `stride` bytes (stride % 4 == 0, <= 256).
MeshoptView encodeMeshoptAttributes(const void* data, size_t count, size_t stride);

// Index codec (version 1) of a triangle list of `count` indices, 2 or 4 bytes each
// (`indexSize`); the decoded view holds them with that stride.
MeshoptView encodeMeshoptTriangles(const void* indices, size_t count, size_t indexSize);

}  // namespace knit::impl
