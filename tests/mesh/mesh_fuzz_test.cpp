// Property test for the mesh parsers: deterministically mutated OBJ / PLY / OFF files either
// load into a valid mesh or raise knit::Error — never crash, hang or return garbage.
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "test_util.hpp"

#include <gtest/gtest.h>

#include <random>

namespace {

const char* kObj = "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                   "f 1/1 2/2 3/3 4/4\nf -2/-2 -1/-1 1/1\n";
const char* kPly = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "property float texture_u\nproperty float texture_v\nelement face 2\n"
                   "property list uchar int vertex_indices\nend_header\n"
                   "0 0 0 0 0\n1 0 0 1 0\n1 1 0.5 1 1\n0 1 0 0 1\n4 0 1 2 3\n3 0 2 3\n";
const char* kOff = "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0.5 1 1\n0 1 0 0 1\n4 0 1 2 3\n3 0 2 3\n";

std::string binaryPly() {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                    "property float z\nproperty float s\nproperty float t\nelement face 2\n"
                    "property list uchar int vertex_indices\nend_header\n";
    const float v[4][5] = {{0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {1, 1, 0.5f, 1, 1}, {0, 1, 0, 0, 1}};
    s.append(reinterpret_cast<const char*>(v), sizeof(v));
    const int32_t f0[4] = {0, 1, 2, 3}, f1[3] = {0, 2, 3};
    s.push_back(char(4));
    s.append(reinterpret_cast<const char*>(f0), sizeof(f0));
    s.push_back(char(3));
    s.append(reinterpret_cast<const char*>(f1), sizeof(f1));
    return s;
}

std::string mutate(std::string s, std::mt19937& rng) {
    static const char kBytes[] = "0123456789-+.e/ \n#nafivxyz\xff";
    const int edits = 1 + int(rng() % 3);
    for (int e = 0; e < edits && !s.empty(); ++e) {
        const size_t at = rng() % s.size();
        switch (rng() % 4) {
            case 0: s[at] = kBytes[rng() % (sizeof(kBytes) - 1)]; break;           // replace
            case 1: s.insert(at, 1, kBytes[rng() % (sizeof(kBytes) - 1)]); break;  // insert
            case 2: s.erase(at, 1 + rng() % 4); break;                             // delete
            default: s.resize(at); break;                                          // truncate
        }
    }
    return s;
}

}  // namespace

TEST(MeshFuzz, mutatedFilesLoadValidOrThrowKnitError) {
    knit::test::TempDir dir;
    const std::pair<std::string, std::string> seeds[] = {
        {"m.obj", kObj}, {"m.ply", kPly}, {"m.off", kOff}, {"b.ply", binaryPly()}};
    std::mt19937 rng(12345);
    size_t loaded = 0, rejected = 0;
    for (const auto& [name, text] : seeds) {
        ASSERT_NO_THROW(knit::loadMesh(dir.write(name, text))) << name;  // the seeds are valid
        for (int i = 0; i < 250; ++i) {
            const std::string path = dir.write(name, mutate(text, rng));
            try {
                const knit::BaseMesh m = knit::loadMesh(path);
                EXPECT_NO_THROW(knit::validateMesh(m)) << name << " #" << i;
                ++loaded;
            } catch (const knit::Error& e) {
                EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
                ++rejected;
            }
        }
    }
    EXPECT_GT(loaded, 0u);
    EXPECT_GT(rejected, 0u);
}
