// exportSurface: the base mesh with the baked knit textures as a glTF PBR material, one GLB.
#include "knit/surface_export.hpp"

#include <tiny_gltf.h>

#include "io/atomic_file.hpp"
#include "knit/error.hpp"
#include "surface_gltf.hpp"
#include "util/platform.hpp"

namespace knit {

void checkSurfaceOutput(const std::string& path) {
    if (util::lowerExtension(path) != "glb")
        throw Error("cannot export '" + path + "': the surface level alone is written as GLB only (use a .glb name)");
    impl::checkOutputFolder(path);
}

SurfaceExportStats exportSurface(const BaseMesh& mesh, const SurfaceImages& images, const SurfaceExportOptions& o) {
    // Step 1: validate everything before any file exists.
    checkSurfaceOutput(o.path);
    impl::validateSurfaceData(mesh, images, o, "cannot export '" + o.path + "': ");
    // Step 2: vertices, the material with its PNG textures, one buffer.
    const impl::SurfaceData d = impl::prepareSurface(mesh, images, o);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "libknit surface level";
    model.buffers.emplace_back();
    std::vector<unsigned char>& buffer = model.buffers[0].data;
    const impl::AddView addView = [&](const void* data, size_t bytes, int target) {
        while (buffer.size() % 4) buffer.push_back(0);
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = buffer.size();
        v.byteLength = bytes;
        v.target = target;
        buffer.insert(buffer.end(), static_cast<const unsigned char*>(data),
                      static_cast<const unsigned char*>(data) + bytes);
        model.bufferViews.push_back(v);
        return int(model.bufferViews.size()) - 1;
    };
    tinygltf::Scene scene;
    scene.nodes = {impl::addSurface(model, addView, d)};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    SurfaceExportStats stats;
    stats.imageBytes = d.colourPng.size() + d.normalPng.size();
    stats.vertices = d.vertexCount();
    stats.triangles = d.indices.size() / 3;
    // Step 3: GLB through a temporary file, renamed when complete.
    impl::AtomicFile file(o.path, true);
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&model, file.stream(), false, true))
        throw Error("cannot export '" + o.path + "': tinygltf failed to write the GLB");
    file.commit();
    stats.bytes = size_t(file.bytesWritten());
    return stats;
}

}  // namespace knit
