// gltf_builder.hpp — glTF files assembled byte by byte for the tests of the glTF reader (JSON
// with a base64 buffer, GLB container, external .bin), independently of the reader under test.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace knit_test {

inline std::string base64(const std::string& bytes) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v =
            uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out.push_back(t[(v >> (6 * k)) & 63]);
    }
    if (i + 1 == bytes.size()) {
        const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
    }
    return out;
}

// A glTF under construction: one buffer; views and accessors appended; meshes/nodes as JSON.
struct GltfBuilder {
    using json = nlohmann::json;

    std::string bin;
    json doc = {{"asset", {{"version", "2.0"}}}, {"bufferViews", json::array()}, {"accessors", json::array()}};

    template <class T>
    int accessor(const std::vector<T>& values, int componentType, const char* type, size_t count,
                 bool normalized = false, bool bounds = false) {
        while (bin.size() % 4) bin.push_back('\0');
        const size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        json a = {{"bufferView", doc["bufferViews"].size() - 1},
                  {"componentType", componentType},
                  {"type", type},
                  {"count", count}};
        if (normalized) a["normalized"] = true;
        if (bounds) {  // POSITION min / max
            std::vector<double> lo(3, 1e300), hi(3, -1e300);
            for (size_t i = 0; i < count; ++i)
                for (int k = 0; k < 3; ++k) {
                    lo[size_t(k)] = std::min(lo[size_t(k)], double(values[3 * i + size_t(k)]));
                    hi[size_t(k)] = std::max(hi[size_t(k)], double(values[3 * i + size_t(k)]));
                }
            a["min"] = lo;
            a["max"] = hi;
        }
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }
    // A mesh with one primitive; returns the mesh index.
    int mesh(const std::vector<float>& pos, const std::vector<float>& uv, const std::vector<uint32_t>& idx,
             int mode = 4) {
        json prim = {{"attributes",
                      {{"POSITION", accessor(pos, 5126, "VEC3", pos.size() / 3, false, true)},
                       {"TEXCOORD_0", accessor(uv, 5126, "VEC2", uv.size() / 2)}}},
                     {"mode", mode}};
        if (!idx.empty()) prim["indices"] = accessor(idx, 5125, "SCALAR", idx.size());
        doc["meshes"].push_back({{"primitives", json::array({prim})}});
        return int(doc["meshes"].size()) - 1;
    }
    // JSON with the buffer embedded as a data URI.
    std::string gltf() const {
        json d = doc;
        d["buffers"] =
            json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        return d.dump();
    }
    // JSON with the buffer in an external file `binName`.
    std::string gltfExternal(const std::string& binName) const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", binName}}});
        return d.dump();
    }
    // GLB container: header, JSON chunk, BIN chunk.
    std::string glb() const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin.size()}}});
        std::string j = d.dump();
        while (j.size() % 4) j.push_back(' ');
        std::string b = bin;
        while (b.size() % 4) b.push_back('\0');
        std::string out = "glTF";
        auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        u32(2);
        u32(uint32_t(12 + 8 + j.size() + 8 + b.size()));
        u32(uint32_t(j.size()));
        u32(0x4E4F534A);
        out += j;
        u32(uint32_t(b.size()));
        u32(0x004E4942);
        out += b;
        return out;
    }
};

}  // namespace knit_test
