// mesh_openmesh.cpp — helpers of the PLY/OFF readers around OpenMesh (mesh_openmesh.hpp).
#include "mesh_openmesh.hpp"

namespace knit::impl {

bool customVertexScalar(OpenMesh::ArrayKernel& k, const std::string& name, size_t n, std::vector<double>& out) {
    out.assign(n, 0.0);
    OpenMesh::VPropHandleT<float> pf;
    if (k.get_property_handle(pf, name)) {
        for (size_t i = 0; i < n; ++i) out[i] = k.property(pf, OpenMesh::VertexHandle(int(i)));
        return true;
    }
    OpenMesh::VPropHandleT<double> pd;
    if (k.get_property_handle(pd, name)) {
        for (size_t i = 0; i < n; ++i) out[i] = k.property(pd, OpenMesh::VertexHandle(int(i)));
        return true;
    }
    return false;
}

std::mutex& openMeshReaderMutex() {
    static std::mutex m;
    return m;
}

std::vector<glm::dvec3> recordedPoints(const RecordingImporter& rec) {
    std::vector<glm::dvec3> points(rec.points.size());
    for (size_t i = 0; i < points.size(); ++i) points[i] = {rec.points[i][0], rec.points[i][1], rec.points[i][2]};
    return points;
}

}  // namespace knit::impl
