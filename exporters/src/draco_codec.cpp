// draco_codec.cpp — Draco encoding of a tube chunk (and the decode that describes it in glTF).
#include "draco_codec.hpp"

#include <algorithm>
#include <limits>
#include <memory>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "knit/error.hpp"

namespace knit::impl {

namespace {

// Adds an attribute with identity point -> value mapping and copies `count` packed values.
int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components, draco::DataType dt,
                 bool normalized, size_t componentBytes, const void* data, size_t count) {
    draco::GeometryAttribute ga;
    ga.Init(type, nullptr, uint8_t(components), dt, normalized, int64_t(componentBytes * components), 0);
    const int id = mesh.AddAttribute(ga, true, uint32_t(count));
    mesh.attribute(id)->buffer()->Write(0, data, componentBytes * components * count);
    return id;
}

}  // namespace

DracoChunk encodeDracoTubes(const TubeMesh& tube, const std::vector<glm::u8vec4>* colors,
                            const DracoSettings& settings) {
    DracoChunk out;
    const size_t nv = tube.vertexCount();
    // Step 1: the Draco mesh (points = tube vertices, identity attribute mapping).
    draco::Mesh mesh;
    mesh.set_num_points(uint32_t(nv));
    mesh.SetNumFaces(tube.triangles.size());
    for (size_t f = 0; f < tube.triangles.size(); ++f) {
        const glm::uvec3& t = tube.triangles[f];
        mesh.SetFace(draco::FaceIndex(uint32_t(f)),
                     {draco::PointIndex(t.x), draco::PointIndex(t.y), draco::PointIndex(t.z)});
    }
    const int pos = addAttribute(mesh, draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, false, 4,
                                 tube.positions.data(), nv);
    const int nor =
        addAttribute(mesh, draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32, false, 4, tube.normals.data(), nv);
    const int tex =
        addAttribute(mesh, draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32, false, 4, tube.uvs.data(), nv);
    const int tan =
        addAttribute(mesh, draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32, false, 4, tube.tangents.data(), nv);
    int col = -1;
    if (colors)
        col = addAttribute(mesh, draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8, true, 1, colors->data(), nv);
    out.attributeIds["POSITION"] = int(mesh.attribute(pos)->unique_id());
    out.attributeIds["NORMAL"] = int(mesh.attribute(nor)->unique_id());
    out.attributeIds["TEXCOORD_0"] = int(mesh.attribute(tex)->unique_id());
    out.attributeIds["TANGENT"] = int(mesh.attribute(tan)->unique_id());
    if (col >= 0) out.attributeIds["COLOR_0"] = int(mesh.attribute(col)->unique_id());

    // Step 2: encode with edgebreaker and the requested quantization.
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, settings.positionBits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, settings.normalBits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, settings.texcoordBits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, settings.normalBits);
    const int speed = 10 - std::clamp(settings.level, 0, 10);
    encoder.SetSpeedOptions(speed, speed);
    encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buffer;
    const draco::Status st = encoder.EncodeMeshToBuffer(mesh, &buffer);
    if (!st.ok()) throw Error(std::string("Draco encoding failed: ") + st.error_msg());
    out.bytes.assign(buffer.data(), buffer.data() + buffer.size());

    // Step 3: decode once; the glTF accessors describe the decoded data (counts, exact bounds).
    draco::DecoderBuffer in;
    in.Init(out.bytes.data(), out.bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok())
        throw Error(std::string("Draco decoding of the encoded chunk failed: ") + decoded.status().error_msg());
    const std::unique_ptr<draco::Mesh> dm = std::move(decoded).value();
    out.points = dm->num_points();
    out.faces = dm->num_faces();
    const draco::PointAttribute* dp = dm->GetAttributeByUniqueId(uint32_t(out.attributeIds["POSITION"]));
    if (!dp) throw Error("Draco decoding lost the POSITION attribute");
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (uint32_t i = 0; i < dm->num_points(); ++i) {
        float v[3];
        dp->GetMappedValue(draco::PointIndex(i), v);
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], v[k]);
            hi[k] = std::max(hi[k], v[k]);
        }
    }
    out.minPosition = lo;
    out.maxPosition = hi;
    return out;
}

}  // namespace knit::impl
