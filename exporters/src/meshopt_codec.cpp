// meshopt_codec.cpp — EXT_meshopt_compression payloads with Debian's meshoptimizer (0.18).
//
// Steps per view: pick the codec (vertex codec for attributes, index codec for triangle lists),
// size the output with the codec's bound, encode, trim. The extension requires vertex codec
// version 0 and index codec version 1; both are set before each encode (meshoptimizer keeps the
// version in a process-wide setting, so it is set explicitly rather than relied upon).
#include "meshopt_codec.hpp"

#include <algorithm>
#include <string>

#include "knit/error.hpp"

#ifdef KNIT_WITH_MESHOPT
#include <meshoptimizer.h>
#endif

namespace knit::impl {

#ifdef KNIT_WITH_MESHOPT

void requireMeshopt() {}

MeshoptView encodeMeshoptAttributes(const void* data, size_t count, size_t stride) {
    if (stride == 0 || stride % 4 != 0 || stride > 256)
        throw Error("glTF meshopt compression: attribute stride " + std::to_string(stride) +
                    " is not a multiple of 4 in [4, 256]");
    MeshoptView v;
    v.count = count;
    v.stride = stride;
    v.mode = "ATTRIBUTES";
    meshopt_encodeVertexVersion(0);
    v.bytes.resize(meshopt_encodeVertexBufferBound(count, stride));
    const size_t n = meshopt_encodeVertexBuffer(v.bytes.data(), v.bytes.size(), data, count, stride);
    if (n == 0) throw Error("glTF meshopt compression: the vertex codec failed");
    v.bytes.resize(n);
    return v;
}

MeshoptView encodeMeshoptTriangles(const void* indices, size_t count, size_t indexSize) {
    if (count % 3 != 0 || (indexSize != 2 && indexSize != 4))
        throw Error("glTF meshopt compression: triangle indices need a multiple of 3 indices of 2 or 4 bytes");
    MeshoptView v;
    v.count = count;
    v.stride = indexSize;
    v.mode = "TRIANGLES";
    meshopt_encodeIndexVersion(1);
    size_t vertices = 0;  // the bound needs the vertex count: one more than the largest index
    auto encode = [&](const auto* idx) {
        for (size_t i = 0; i < count; ++i) vertices = std::max<size_t>(vertices, size_t(idx[i]) + 1);
        v.bytes.resize(meshopt_encodeIndexBufferBound(count, vertices));
        return meshopt_encodeIndexBuffer(v.bytes.data(), v.bytes.size(), idx, count);
    };
    const size_t n =
        indexSize == 2 ? encode(static_cast<const uint16_t*>(indices)) : encode(static_cast<const uint32_t*>(indices));
    if (n == 0) throw Error("glTF meshopt compression: the index codec failed");
    v.bytes.resize(n);
    return v;
}

#else

void requireMeshopt() {
    throw Error("meshopt compression: this build has no meshoptimizer (configure with KNIT_WITH_MESHOPT=ON and "
                "libmeshoptimizer-dev installed)");
}
MeshoptView encodeMeshoptAttributes(const void*, size_t, size_t) {
    requireMeshopt();
    return {};
}
MeshoptView encodeMeshoptTriangles(const void*, size_t, size_t) {
    requireMeshopt();
    return {};
}

#endif

}  // namespace knit::impl
