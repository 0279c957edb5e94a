// Reading an uploaded garment mesh (mesh_upload.hpp).
#include "mesh_upload.hpp"

#include <cctype>
#include <cstdio>
#include <fstream>

#include "api_request.hpp"
#include "knit/error.hpp"

namespace knit::serve {
namespace {

std::string lowerExtension(const std::string& name) {
    const size_t dot = name.find_last_of('.');
    if (dot == std::string::npos) return "";
    std::string ext = name.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// The reader's message with the server's file path replaced by the user's file name.
std::string inUserWords(std::string message, const std::string& path, const std::string& name) {
    for (size_t at = message.find(path); at != std::string::npos; at = message.find(path, at + name.size()))
        message.replace(at, path.size(), name);
    return message;
}

}  // namespace

BaseMesh loadUploadedMesh(const std::string& bytes, const std::string& name, TempFolder& temp,
                          const MemoryBudget& budget) {
    const std::string ext = lowerExtension(name);
    if (ext != "obj" && ext != "glb" && ext != "gltf")
        throw RequestError(
            415, "upload a mesh as .obj, .glb or .gltf with UVs (got '" + name + "'; give it with ?name=FILE)");
    if (bytes.empty()) throw RequestError(400, "the upload '" + name + "' is empty");
    MeshLoadOptions options;
    options.budget = budget;
    if (ext != "obj") return parseGltfMesh(bytes, name, "", options);  // external files refused
    const std::string path = temp.newFile("upload", "obj");
    {
        std::ofstream out(path, std::ios::binary);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        if (!out) throw Error("cannot store the upload '" + name + "' in the server's temporary folder");
    }
    try {
        BaseMesh mesh = loadMesh(path, options);
        std::remove(path.c_str());
        mesh.name = name;
        return mesh;
    } catch (const Error& e) {
        std::remove(path.c_str());
        throw Error(inUserWords(e.what(), path, name));
    }
}

}  // namespace knit::serve
