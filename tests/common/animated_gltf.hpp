// animated_gltf.hpp — small animated glTF files written in code (JSON with an embedded base64
// buffer) for the glTF animation input tests: a unit quad with a morph target whose weight rises
// 0 -> 1 over one second, and the same quad skinned to one joint turning 90 degrees about z.
#pragma once
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace knit::test {

// A glTF document being written: one buffer, a bufferView + accessor per array.
struct GltfText {
    nlohmann::json j = {{"asset", {{"version", "2.0"}}},
                        {"bufferViews", nlohmann::json::array()},
                        {"accessors", nlohmann::json::array()}};
    std::string bin;
    template <typename T>
    int add(const std::vector<T>& v, int componentType, const char* type, size_t count) {
        const size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
        bin.resize((bin.size() + 3) & ~size_t(3), '\0');
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", v.size() * sizeof(T)}});
        j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1},
                                  {"componentType", componentType},
                                  {"count", count},
                                  {"type", type}});
        return int(j["accessors"].size()) - 1;
    }
    std::string text() {
        static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string b64;
        for (size_t i = 0; i < bin.size(); i += 3) {
            const uint32_t a = uint8_t(bin[i]), b = i + 1 < bin.size() ? uint8_t(bin[i + 1]) : 0,
                           c = i + 2 < bin.size() ? uint8_t(bin[i + 2]) : 0, n = (a << 16) | (b << 8) | c;
            b64 += k[(n >> 18) & 63];
            b64 += k[(n >> 12) & 63];
            b64 += i + 1 < bin.size() ? k[(n >> 6) & 63] : '=';
            b64 += i + 2 < bin.size() ? k[n & 63] : '=';
        }
        j["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + b64}}};
        return j.dump();
    }
};

constexpr int kF = 5126, kU8 = 5121, kU16 = 5123;
inline const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

// The quad: POSITION, TEXCOORD_0, two triangles; mesh 0 on node 0.
inline nlohmann::json quadPrimitive(GltfText& g) {
    const int pos = g.add(kQuad, kF, "VEC3", 4);
    g.j["accessors"][size_t(pos)]["min"] = {0, 0, 0};
    g.j["accessors"][size_t(pos)]["max"] = {1, 1, 0};
    const int uv = g.add(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, kF, "VEC2", 4);
    const int idx = g.add(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kU16, "SCALAR", 6);
    return {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}, {"indices", idx}};
}

inline void addAnimation(GltfText& g, const std::vector<float>& values, const char* type, size_t node,
                         const char* path) {
    const int in = g.add(std::vector<float>{0, 1}, kF, "SCALAR", 2);
    g.j["accessors"][size_t(in)]["min"] = {0};
    g.j["accessors"][size_t(in)]["max"] = {1};
    const int out = g.add(values, kF, type, std::string(type) == "SCALAR" ? values.size() : 2);
    nlohmann::json anim;
    anim["samplers"] = nlohmann::json::array({{{"input", in}, {"output", out}}});
    anim["channels"] = nlohmann::json::array({{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}});
    g.j["animations"] = nlohmann::json::array({anim});
}

// Morph: target 0 lifts vertex i by (i + 1) along z; its weight goes 0 -> 1 over one second.
inline std::string writeMorphQuad(const std::string& dir) {
    GltfText g;
    nlohmann::json prim = quadPrimitive(g);
    const int target = g.add(std::vector<float>{0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4}, kF, "VEC3", 4);
    g.j["accessors"][size_t(target)]["min"] = {0, 0, 1};
    g.j["accessors"][size_t(target)]["max"] = {0, 0, 4};
    prim["targets"] = {{{"POSITION", target}}};
    g.j["meshes"] = {{{"primitives", {prim}}, {"weights", {0}}}};
    g.j["nodes"] = {{{"mesh", 0}}};
    g.j["scenes"] = {{{"nodes", {0}}}};
    g.j["scene"] = 0;
    addAnimation(g, {0, 1}, "SCALAR", 0, "weights");
    const std::string path = dir + "/morph.gltf";
    std::ofstream(path) << g.text();
    return path;
}

// Skin: every vertex fully on joint 0 (node 1, identity inverse bind); node 1 turns 0 -> 90
// degrees about z over one second.
// `signedJoints` stores JOINTS_0 as signed bytes holding -64 (the spec allows only unsigned types).
inline std::string writeSkinnedQuad(const std::string& dir, bool signedJoints = false) {
    GltfText g;
    nlohmann::json prim = quadPrimitive(g);
    prim["attributes"]["JOINTS_0"] = signedJoints ? g.add(std::vector<int8_t>(16, int8_t(-64)), 5120, "VEC4", 4)
                                                  : g.add(std::vector<uint8_t>(16, 0), kU8, "VEC4", 4);
    prim["attributes"]["WEIGHTS_0"] =
        g.add(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, kF, "VEC4", 4);
    const std::vector<float> identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const int ibm = g.add(identity, kF, "MAT4", 1);
    g.j["meshes"] = {{{"primitives", {prim}}}};
    g.j["skins"] = {{{"joints", {1}}, {"inverseBindMatrices", ibm}}};
    g.j["nodes"] = {{{"mesh", 0}, {"skin", 0}}, {{"name", "joint"}}};
    g.j["scenes"] = {{{"nodes", {0, 1}}}};
    g.j["scene"] = 0;
    const float h = float(std::sqrt(0.5));
    addAnimation(g, {0, 0, 0, 1, 0, 0, h, h}, "VEC4", 1, "rotation");
    const std::string path = dir + "/skin.gltf";
    std::ofstream(path) << g.text();
    return path;
}

}  // namespace knit::test
