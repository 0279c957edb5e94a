// mesh_openmesh.hpp (internal) — the PLY and OFF readers (mesh_ply.cpp, mesh_off.cpp) parse
// through OpenMesh 9.0's readers after checking the file themselves (OpenMesh accepts garbage
// silently and, on some malformed files, crashes, loops or allocates without bound).
//
// OpenMesh's readers talk to a BaseImporter. They get a *recording* importer instead of a
// halfedge mesh: it keeps the file's vertices, polygons and texture coordinates exactly as read
// (a halfedge mesh would silently split "non-manifold" faces into duplicated vertices); topology
// is rebuilt by welding (buildPolygonMesh). OpenMesh keeps positions and texture coordinates as
// float32. It prints its own warnings to std::cerr (omerr); libknit's knit::Error is the
// authoritative result. The reader singletons hold state (OFF options), so calls into them are
// serialized by openMeshReaderMutex().
#pragma once
#include "mesh_reader.hpp"

#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/Mesh/ArrayKernel.hh>

#include <mutex>

namespace knit::impl {

// Recording importer: what OpenMesh's reader saw, without building halfedge topology.
class RecordingImporter final : public OpenMesh::IO::BaseImporter {
public:
    std::vector<OpenMesh::Vec3d> points;
    std::vector<OpenMesh::Vec2f> vertexUv;
    std::vector<char> vertexHasUv;
    Polygons polys;                     // faces as read (PLY/OFF texture coordinates are per vertex)
    OpenMesh::ArrayKernel customProps;  // PLY custom properties (texture_u, ...) land here

    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
        return add_vertex(OpenMesh::Vec3d(p[0], p[1], p[2]));
    }
    OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
        points.push_back(p);
        vertexUv.emplace_back(0.f, 0.f);
        vertexHasUv.push_back(0);
        customProps.new_vertex();
        return OpenMesh::VertexHandle(int(points.size() - 1));
    }
    OpenMesh::VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
    OpenMesh::FaceHandle add_face(const VHandles& indices) override {
        for (const auto& vh : indices) polys.faceVerts.push_back(vh.idx());
        polys.faceStart.push_back(uint32_t(polys.faceVerts.size()));
        customProps.new_face();
        return OpenMesh::FaceHandle(int(polys.count() - 1));
    }
    void set_texcoord(OpenMesh::VertexHandle vh, const OpenMesh::Vec2f& t) override {
        if (vh.is_valid() && size_t(vh.idx()) < vertexUv.size()) {
            vertexUv[vh.idx()] = t;
            vertexHasUv[vh.idx()] = 1;
        }
    }
    void set_point(OpenMesh::VertexHandle vh, const OpenMesh::Vec3f& p) override {
        if (vh.is_valid() && size_t(vh.idx()) < points.size()) points[vh.idx()] = OpenMesh::Vec3d(p[0], p[1], p[2]);
    }
    OpenMesh::BaseKernel* kernel() override { return &customProps; }
    size_t n_vertices() const override { return points.size(); }
    size_t n_faces() const override { return polys.count(); }
    size_t n_edges() const override { return 0; }

    // Everything below is information libknit does not use.
    OpenMesh::HalfedgeHandle add_edge(OpenMesh::VertexHandle, OpenMesh::VertexHandle) override {
        return OpenMesh::HalfedgeHandle();
    }
    OpenMesh::FaceHandle add_face(OpenMesh::HalfedgeHandle) override { return OpenMesh::FaceHandle(); }
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle,
                            const std::vector<OpenMesh::Vec2f>&) override {}  // PLY/OFF UVs are per vertex
    void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle,
                            const std::vector<OpenMesh::Vec3f>&) override {}
    void set_face_texindex(OpenMesh::FaceHandle, int) override {}
    void set_halfedge(OpenMesh::VertexHandle, OpenMesh::HalfedgeHandle) override {}
    void set_normal(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(OpenMesh::VertexHandle, const OpenMesh::Vec3d&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::VertexHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_next(OpenMesh::HalfedgeHandle, OpenMesh::HalfedgeHandle) override {}
    void set_face(OpenMesh::HalfedgeHandle, OpenMesh::FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec2f&) override {}
    void set_texcoord(OpenMesh::VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_texcoord(OpenMesh::HalfedgeHandle, const OpenMesh::Vec3f&) override {}
    void set_status(OpenMesh::HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_normal(OpenMesh::FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(OpenMesh::FaceHandle, const OpenMesh::Vec3d&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::FaceHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}
};

// Reads a float or double custom vertex property written by OpenMesh's PLY reader.
bool customVertexScalar(OpenMesh::ArrayKernel& k, const std::string& name, size_t n, std::vector<double>& out);

std::mutex& openMeshReaderMutex();

// The recorded positions, float32 as OpenMesh read them, in double.
std::vector<glm::dvec3> recordedPoints(const RecordingImporter& rec);

}  // namespace knit::impl
