// draco_codec.hpp (internal) — one tube-mesh chunk to a Draco buffer (KHR_draco_mesh_compression).
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "knit/sweep.hpp"

namespace knit::impl {

struct DracoSettings {
    int positionBits = 14;
    int normalBits = 10;  // NORMAL and TANGENT
    int texcoordBits = 12;
    int level = 7;  // 0 fast .. 10 small (speed = 10 - level)
};

struct DracoChunk {
    std::vector<char> bytes;                  // the compressed Draco bitstream
    std::map<std::string, int> attributeIds;  // glTF attribute name -> Draco unique id
    // What a decoder gets back (the glTF accessors must describe the decoded data):
    size_t points = 0;
    size_t faces = 0;
    glm::vec3 minPosition{0.0f}, maxPosition{0.0f};  // exact float32 bounds of decoded POSITION
};

// Encodes POSITION, NORMAL, TEXCOORD_0, TANGENT (Draco GENERIC) and optional COLOR_0 (RGBA8)
// with edgebreaker, then decodes the result once to read the decoded counts and bounds.
// Throws knit::Error if Draco fails.
DracoChunk encodeDracoTubes(const TubeMesh& mesh, const std::vector<glm::u8vec4>* colors,
                            const DracoSettings& settings);

}  // namespace knit::impl
