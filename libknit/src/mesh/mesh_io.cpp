// mesh_io.cpp — loadMesh: one table from file extension to reader.
//
//  * Dispatch is by the file's extension, case-insensitive: .obj (mesh_obj.cpp), .ply
//    (mesh_ply.cpp), .off (mesh_off.cpp), .gltf/.glb (mesh_gltf.cpp); anything else is an error
//    that lists the table.
//  * Every file is read by its reader, which checks it as it goes and names the line of a bad
//    element where the format has lines. OBJ, PLY and OFF are each parsed in one pass by
//    libknit alone (OBJ positions in double; PLY and OFF values as OpenMesh's readers, used
//    before, delivered them). The readers are our own because OpenMesh 9.0's crash on some
//    malformed headers, trust list and element counts and turn bad tokens into zeros without
//    reporting failure, while the checking walk already reads every value.
//  * Faces are triangulated inside their outline (polygon_triangulation.hpp: convex ones as the
//    fan (v0, vi, vi+1), concave ones by a constrained Delaunay triangulation in their best-fit
//    plane; a polygon without area or crossing itself is refused naming it). Positions that are
//    exactly equal (-0 == +0) are welded when MeshLoadOptions::weldEqualPositions is set, so
//    PLY/OFF files that duplicate vertices along UV seams get the same 3D topology as the OBJ.
//    Vertices no face references are dropped. A UV vertex is one distinct (position, uv) pair,
//    numbered in first-use order (mesh_weld.hpp).
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "mesh_reader.hpp"
#include "util/platform.hpp"
#include "io/special_file.hpp"

#include <filesystem>
#include <fstream>

namespace knit {
namespace {

struct MeshFormat {
    const char* extension;  // lower case, without the dot
    BaseMesh (*read)(const std::string& path, const MeshLoadOptions& options);
    bool text;  // a line-based format: opened and checked for a byte-order mark first, validated after
};

const MeshFormat kMeshFormats[] = {
    {"obj", impl::readObjMesh, true}, {"ply", impl::readPlyMesh, true}, {"off", impl::readOffMesh, true},
    {"gltf", loadGltfMesh, false},    {"glb", loadGltfMesh, false},
};

// Files saved with a UTF-8 byte-order mark: named instead of blamed on the first element.
void refuseByteOrderMark(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char head[3] = {};
    if (in.read(head, 3) && head[0] == '\xEF' && head[1] == '\xBB' && head[2] == '\xBF')
        impl::failMesh(
            path, "starts with a UTF-8 byte-order mark (BOM), which mesh files may not have; save it without the BOM");
}

}  // namespace

BaseMesh loadMesh(const std::string& path, const MeshLoadOptions& options) {
    // Check the file exists, is a regular file and has a known extension.
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) impl::failMesh(path, "no such file");
    if (std::filesystem::is_directory(status)) impl::failMesh(path, "is a directory, not a mesh file");
    if (impl::isSpecialFile(path)) impl::failMesh(path, impl::notRegularFile());
    const std::string ext = util::lowerExtension(path);  // without the dot
    const MeshFormat* format = nullptr;
    std::string supported;
    for (const MeshFormat& f : kMeshFormats) {
        if (ext == f.extension) format = &f;
        supported += std::string(supported.empty() ? "" : ", ") + "." + f.extension;
    }
    if (!format) {
        const std::string dot = std::filesystem::path(path).has_extension() ? "." : "";  // "name." shows '.'
        impl::failMesh(path, "unknown mesh file extension '" + dot + ext + "' (supported: " + supported + ")");
    }
    if (!format->text) return format->read(path, options);
    if (!std::ifstream(path, std::ios::binary)) impl::failMesh(path, "cannot open for reading");
    refuseByteOrderMark(path);
    BaseMesh mesh = format->read(path, options);
    validateMesh(mesh);
    return mesh;
}

}  // namespace knit
