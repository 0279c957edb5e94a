// KHR_draco_mesh_compression: decode every compressed chunk with the Draco decoder and match it
// against the uncompressed export of the same curves within the quantization bound.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <unordered_map>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "export/gltf_read.hpp"
#include "export/gltf_validator.hpp"
#include "export/test_curves.hpp"
#include "knit/error.hpp"
#include "knit/export.hpp"

namespace knit {
namespace {

struct Vertex {
    glm::dvec3 p, n;
    glm::dvec2 uv;
    glm::dvec4 t;
};

struct ChunkData {
    glm::dvec3 translation;
    std::vector<Vertex> v;
    size_t triangles = 0;
};

ExportStats write(const Polylines& c, double radius, const ExportOptions& o) {
    ExportInput in;
    in.curves = &c;
    in.radius = radius;
    return exportCurves(in, o);
}

glm::dvec3 translationOf(const gltf::Document& m, size_t node) {
    const std::vector<double> t = m.numbers(m.element("nodes", node, "test"), "translation", 3, "test");
    return t.size() == 3 ? glm::dvec3(t[0], t[1], t[2]) : glm::dvec3(0);
}

// Plain (uncompressed) chunks, local coordinates.
std::vector<ChunkData> readPlain(const gltf::Document& m) {
    std::vector<ChunkData> out;
    for (const auto& inst : m.meshInstances()) {
        const auto p = m.primitives(inst.mesh).at(0);
        ChunkData c;
        c.translation = translationOf(m, inst.node);
        const auto pos = test::readAttribute(m, p, "POSITION");
        const auto nor = test::readAttribute(m, p, "NORMAL");
        const auto uv = test::readAttribute(m, p, "TEXCOORD_0");
        const auto tan = test::readAttribute(m, p, "TANGENT");
        for (size_t i = 0; i < pos.size() / 3; ++i)
            c.v.push_back({{pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]},
                           {nor[3 * i], nor[3 * i + 1], nor[3 * i + 2]},
                           {uv[2 * i], uv[2 * i + 1]},
                           {tan[4 * i], tan[4 * i + 1], tan[4 * i + 2], tan[4 * i + 3]}});
        c.triangles = m.accessor(m.indices(p).value(), "test").count / 3;
        out.push_back(std::move(c));
    }
    return out;
}

// Decodes one primitive's KHR_draco_mesh_compression bufferView with the Draco library.
std::unique_ptr<draco::Mesh> decodePrimitive(const gltf::Document& g, const nlohmann::json& prim) {
    const nlohmann::json& ext = prim["extensions"]["KHR_draco_mesh_compression"];
    const gltf::Bytes view = g.bufferView(ext["bufferView"].get<size_t>(), "test");
    draco::DecoderBuffer db;
    db.Init(reinterpret_cast<const char*>(view.data), view.size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&db);
    EXPECT_TRUE(decoded.ok()) << decoded.status().error_msg_string();
    if (!decoded.ok()) return nullptr;
    return std::move(decoded).value();
}

// Draco chunks decoded with the Draco library; also checks the accessors describe the decoded data.
std::vector<ChunkData> readDraco(const gltf::Document& g) {
    std::vector<ChunkData> out;
    const nlohmann::json& doc = g.root();
    for (const auto& child : doc["nodes"][0]["children"]) {
        const nlohmann::json& node = doc["nodes"][child.get<size_t>()];
        const nlohmann::json& prim = doc["meshes"][node["mesh"].get<size_t>()]["primitives"][0];
        EXPECT_TRUE(prim.contains("extensions"));
        const std::unique_ptr<draco::Mesh> dm = decodePrimitive(g, prim);
        if (!dm) return out;
        const nlohmann::json& attrs = prim["extensions"]["KHR_draco_mesh_compression"]["attributes"];
        auto att = [&](const char* name) { return dm->GetAttributeByUniqueId(attrs[name].get<uint32_t>()); };
        const draco::PointAttribute *pa = att("POSITION"), *na = att("NORMAL"), *ta = att("TEXCOORD_0"),
                                    *ga = att("TANGENT");
        EXPECT_TRUE(pa && na && ta && ga);
        if (!(pa && na && ta && ga)) return out;
        ChunkData c;
        const auto t = node["translation"];
        c.translation = glm::dvec3(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (uint32_t i = 0; i < dm->num_points(); ++i) {
            float x[3], n[3], uv[2], tg[4];
            pa->GetMappedValue(draco::PointIndex(i), x);
            na->GetMappedValue(draco::PointIndex(i), n);
            ta->GetMappedValue(draco::PointIndex(i), uv);
            ga->GetMappedValue(draco::PointIndex(i), tg);
            c.v.push_back({{x[0], x[1], x[2]}, {n[0], n[1], n[2]}, {uv[0], uv[1]}, {tg[0], tg[1], tg[2], tg[3]}});
            lo = glm::min(lo, glm::vec3(x[0], x[1], x[2]));
            hi = glm::max(hi, glm::vec3(x[0], x[1], x[2]));
        }
        c.triangles = dm->num_faces();
        // Accessors must describe the decoded data exactly (count, float32 bounds, no bufferView).
        const nlohmann::json& pos = doc["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
        EXPECT_FALSE(pos.contains("bufferView"));
        EXPECT_EQ(pos["count"].get<size_t>(), dm->num_points());
        EXPECT_EQ(doc["accessors"][prim["indices"].get<size_t>()]["count"].get<size_t>(), 3 * size_t(dm->num_faces()));
        for (size_t k = 0; k < 3; ++k) {
            EXPECT_EQ(pos["min"][k].get<double>(), double(lo[int(k)]));
            EXPECT_EQ(pos["max"][k].get<double>(), double(hi[int(k)]));
        }
        out.push_back(std::move(c));
    }
    return out;
}

struct MatchBounds {
    double position, normal, uv, tangent;
};

// Every vertex of `a` has a vertex of `b` agreeing in position, normal, uv and tangent within
// the bounds (Draco may reorder points, so vertices are matched by search, not by index).
size_t unmatched(const std::vector<Vertex>& a, const std::vector<Vertex>& b, const MatchBounds& e) {
    const double cell = std::max(e.position * 4, 1e-9);
    auto key = [&](const glm::dvec3& p) {
        return std::make_tuple(int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)),
                               int64_t(std::floor(p.z / cell)));
    };
    struct Hash {
        size_t operator()(const std::tuple<int64_t, int64_t, int64_t>& k) const {
            return size_t(std::get<0>(k) * 73856093 ^ std::get<1>(k) * 19349663 ^ std::get<2>(k) * 83492791);
        }
    };
    std::unordered_map<std::tuple<int64_t, int64_t, int64_t>, std::vector<size_t>, Hash> grid;
    for (size_t i = 0; i < b.size(); ++i) grid[key(b[i].p)].push_back(i);
    size_t bad = 0;
    for (const Vertex& v : a) {
        const auto [x, y, z] = key(v.p);
        bool found = false;
        for (int dx = -1; dx <= 1 && !found; ++dx)
            for (int dy = -1; dy <= 1 && !found; ++dy)
                for (int dz = -1; dz <= 1 && !found; ++dz) {
                    auto it = grid.find({x + dx, y + dy, z + dz});
                    if (it == grid.end()) continue;
                    for (size_t j : it->second) {
                        const Vertex& w = b[j];
                        if (glm::length(v.p - w.p) <= e.position && glm::length(v.n - w.n) <= e.normal &&
                            glm::length(v.uv - w.uv) <= e.uv && glm::length(v.t - w.t) <= e.tangent) {
                            found = true;
                            break;
                        }
                    }
                }
        if (!found) ++bad;
    }
    return bad;
}

void expectDracoMatchesPlain(int bits) {
    const std::string dir = test::scratchDir("draco_" + std::to_string(bits));
    const Polylines c = test::mixedCurves(glm::dvec3(12.0, -4.0, 0.5));
    const double radius = 0.001;
    ExportOptions plain;
    plain.path = dir + "/plain.glb";
    plain.what = ExportWhat::Tubes;
    plain.sides = 8;
    plain.chunkVertices = 600;
    write(c, radius, plain);
    ExportOptions draco = plain;
    draco.path = dir + "/draco.glb";
    draco.draco = true;
    draco.dracoBits = bits;
    const ExportStats s = write(c, radius, draco);
    EXPECT_LT(s.compressedMeshBytes, s.uncompressedMeshBytes);

    test::ValidatorReport report;
    test::expectGltfValid(draco.path, &report);
    if (report.ran) EXPECT_TRUE(report.hasInfo("UNSUPPORTED_EXTENSION")) << "the validator does not decode Draco";

    const gltf::Document pm = test::loadGltf(plain.path);
    const gltf::Document dg = test::loadGltf(draco.path);
    EXPECT_EQ(dg.root()["extensionsRequired"], nlohmann::json::array({"KHR_draco_mesh_compression"}));
    const std::vector<ChunkData> a = readPlain(pm), b = readDraco(dg);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GE(a.size(), 2u);
    for (size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].translation, b[k].translation);
        EXPECT_EQ(a[k].v.size(), b[k].v.size());
        EXPECT_EQ(a[k].triangles, b[k].triangles);
        // Position bound: Draco quantizes every axis over the largest extent of the chunk.
        glm::dvec3 lo(1e30), hi(-1e30), uvLo(1e30), uvHi(-1e30);
        for (const Vertex& v : a[k].v) {
            lo = glm::min(lo, v.p);
            hi = glm::max(hi, v.p);
            uvLo = glm::min(uvLo, glm::dvec3(v.uv, 0));
            uvHi = glm::max(uvHi, glm::dvec3(v.uv, 0));
        }
        const double range = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        const double step = range / double((1 << bits) - 1);
        const double uvStep = std::max(uvHi.x - uvLo.x, uvHi.y - uvLo.y) / double((1 << 12) - 1);
        MatchBounds e{std::sqrt(3.0) * 0.5 * step * 1.01 + 1e-7, 0.01, std::sqrt(2.0) * 0.5 * uvStep * 1.01 + 1e-6,
                      0.01};
        EXPECT_EQ(unmatched(b[k].v, a[k].v, e), 0u) << "chunk " << k << " decoded -> plain, bits " << bits;
        EXPECT_EQ(unmatched(a[k].v, b[k].v, e), 0u) << "chunk " << k << " plain -> decoded, bits " << bits;
        // And the bound is not trivially loose: a quarter of it fails for a coarse quantization.
        if (bits <= 11) {
            MatchBounds tight = e;
            tight.position = e.position * 0.02;
            EXPECT_GT(unmatched(b[k].v, a[k].v, tight), 0u) << "positions were not quantized at " << bits << " bits";
        }
    }
}

TEST(DracoExport, decodedTubesMatchUncompressedWithin11BitBound) { expectDracoMatchesPlain(11); }
TEST(DracoExport, decodedTubesMatchUncompressedWithin14BitBound) { expectDracoMatchesPlain(14); }
TEST(DracoExport, decodedTubesMatchUncompressedWithin16BitBound) { expectDracoMatchesPlain(16); }

TEST(DracoExport, dracoWithYarnColoursDecodesColours) {
    const std::string dir = test::scratchDir("draco_colours");
    const Polylines c = test::mixedCurves();
    const std::vector<uint32_t> yarns{0, 1, 2};
    ExportInput in;
    in.curves = &c;
    in.radius = 0.001;
    in.yarnOfCurve = &yarns;
    ExportOptions o;
    o.path = dir + "/c.gltf";
    o.what = ExportWhat::Tubes;
    o.draco = true;
    o.yarnColors = true;
    exportCurves(in, o);
    test::expectGltfValid(o.path);
    const gltf::Document g = test::loadGltf(o.path);
    const nlohmann::json& p = g.root()["meshes"][0]["primitives"][0];
    ASSERT_TRUE(p["attributes"].contains("COLOR_0"));
    const auto mesh = decodePrimitive(g, p);
    ASSERT_TRUE(mesh);
    const auto* col = mesh->GetAttributeByUniqueId(
        p["extensions"]["KHR_draco_mesh_compression"]["attributes"]["COLOR_0"].get<uint32_t>());
    ASSERT_NE(col, nullptr);
    std::set<uint32_t> distinct;
    for (uint32_t i = 0; i < mesh->num_points(); ++i) {
        uint8_t rgba[4];
        col->GetMappedValue(draco::PointIndex(i), rgba);
        EXPECT_EQ(rgba[3], 255);
        distinct.insert(uint32_t(rgba[0]) << 16 | uint32_t(rgba[1]) << 8 | rgba[2]);
    }
    EXPECT_EQ(distinct.size(), 3u);
}

}  // namespace
}  // namespace knit
