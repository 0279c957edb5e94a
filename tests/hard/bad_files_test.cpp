// Bad input files through the library's front doors (loadPatternFileOrName, loadMeshFileOrName):
// truncated at every byte, garbage, NaN/Inf fields, absurd counts in headers, missing files and
// directories. Every outcome is either a valid value or a knit::Error whose message names the
// file — never another exception, a crash or a hang.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

#include "hard_cases.hpp"
#include "knit/base_mesh.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/pattern.hpp"
#include "test_util.hpp"
#include "common/test_paths.hpp"

namespace knit::hard {
namespace {

namespace fs = std::filesystem;

class BadFiles : public ::testing::Test {
protected:
    std::string write(const std::string& name, const std::string& content) const { return tmp.write(name, content); }
    test::TempDir tmp;
    const fs::path dir = tmp.path();
};

enum class Kind { Pattern, Mesh };

// Loads `path`; returns true when it loaded (and the value validates), false for knit::Error
// (whose message must name the file). Any other exception fails the test.
bool loadsOrNamesFile(Kind kind, const std::string& path, std::string* message = nullptr) {
    try {
        if (kind == Kind::Pattern) validatePattern(loadPatternFileOrName(path), path);
        else validateMesh(loadMeshFileOrName(path));
        return true;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos)
            << "message does not name the file: " << e.what();
        if (message) *message = e.what();
        return false;
    } catch (const std::exception& e) {
        ADD_FAILURE() << path << ": non-knit exception " << e.what();
        return false;
    }
}

std::string validPyp() {
    std::ostringstream out;
    writePyp(out, generateStockinette());
    return out.str();
}

const char* kObj = "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float u\n"
    "property float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0\n1 0 0 1 0\n1 1 "
    "0.5 1 1\n"
    "0 1 0 0 1\n4 0 1 2 3\n";
const char* kOff = "STOFF\n4 1 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0.5 1 1\n0 1 0 0 1\n4 0 1 2 3\n";
const char* kJson =
    R"({"period": [1, 1], "radius": 0.05, "curves": [[[0.0, 0.25, 0], [0.45, 0.25, 0]], [[0.55, 0.25, 0], [0.95, 0.25, 0.01]]]})";

TEST_F(BadFiles, everyTruncationOfEachFormatLoadsOrNamesTheFile) {
    const std::pair<std::string, std::string> files[] = {
        {"p.pyp", validPyp().substr(0, 1500)}, {"c.json", kJson}, {"m.obj", kObj}, {"m.ply", kPly}, {"m.off", kOff}};
    for (const auto& [name, text] : files) {
        const Kind kind = name[0] == 'm' ? Kind::Mesh : Kind::Pattern;
        size_t rejected = 0;
        for (size_t n = 0; n < text.size(); ++n) {
            const std::string path = write(name, text.substr(0, n));
            rejected += !loadsOrNamesFile(kind, path);
        }
        EXPECT_GT(rejected, text.size() / 2) << name << ": most truncations must be rejected";
    }
}

TEST_F(BadFiles, garbageBytesAreRejectedWithTheFileName) {
    std::mt19937 rng(5);
    for (const char* name : {"g.pyp", "g.json", "g.obj", "g.ply", "g.off"}) {
        const Kind kind =
            std::string(name).find(".pyp") != std::string::npos || std::string(name).find(".json") != std::string::npos
                ? Kind::Pattern
                : Kind::Mesh;
        for (int k = 0; k < 20; ++k) {
            std::string junk(1 + rng() % 400, '\0');
            for (char& c : junk) c = char(rng());
            EXPECT_FALSE(loadsOrNamesFile(kind, write(name, junk))) << name << " #" << k;
        }
    }
}

TEST_F(BadFiles, nanAndInfFieldsAreRejectedNamingTheLine) {
    const std::string pyp = validPyp();
    const size_t q = pyp.find("*Q");
    const size_t firstRow = pyp.find('\n', q) + 1;
    for (const char* bad : {"nan", "inf", "-inf", "1e400", "NaN"}) {
        std::string text = pyp;
        text.replace(firstRow, text.find(' ', firstRow) - firstRow, bad);
        std::string msg;
        EXPECT_FALSE(loadsOrNamesFile(Kind::Pattern, write("n.pyp", text), &msg)) << bad;
        // The line of the first *Q row.
        const size_t line = size_t(std::count(pyp.begin(), pyp.begin() + firstRow, '\n')) + 1;
        EXPECT_NE(msg.find("n.pyp:" + std::to_string(line) + ":"), std::string::npos) << msg;
    }
    for (const char* bad : {"nan", "inf", "1e999"}) {
        std::string obj = kObj;
        obj.replace(obj.find("0.5"), 3, bad);
        std::string msg;
        EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("n.obj", obj), &msg)) << bad;
        EXPECT_NE(msg.find("n.obj:3:"), std::string::npos) << msg;
        std::string ply = kPly;
        ply.replace(ply.find("0.5"), 3, bad);
        EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("n.ply", ply))) << bad;
        std::string off = kOff;
        off.replace(off.find("0.5"), 3, bad);
        EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("n.off", off))) << bad;
    }
    std::string json = kJson;
    json.replace(json.find("0.05"), 4, "1e400");
    EXPECT_FALSE(loadsOrNamesFile(Kind::Pattern, write("n.json", json)));
}

TEST_F(BadFiles, absurdCountsInHeadersAreRejectedQuickly) {
    // Counts far beyond the data must be refused before anything is allocated for them (the
    // watchdog turns an attempt to allocate or loop over them into a named failure).
    Watchdog dog("absurd counts", 60);
    std::string pyp = validPyp();
    pyp.replace(pyp.find(" 24\n"), 4, " 99999999999\n");
    EXPECT_FALSE(loadsOrNamesFile(Kind::Pattern, write("a.pyp", pyp)));
    std::string ply = kPly;
    ply.replace(ply.find("vertex 4"), 8, "vertex 4000000000");
    EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("a.ply", ply)));
    ply = kPly;
    ply.replace(ply.find("face 1"), 6, "face 18446744073709551615");
    EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("b.ply", ply)));
    std::string off = kOff;
    off.replace(off.find("4 1 0"), 5, "4 3000000000 0");
    EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("a.off", off)));
    std::string obj = kObj;
    obj.replace(obj.find("f 1/1 2/2 3/3 4/4"), 17, "f 1/1 2/2 4000000000/3");
    EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("a.obj", obj)));
}

TEST_F(BadFiles, binaryPlyPropertyTypesOpenMeshCannotConvertAreRefused) {
    // OpenMesh skips such properties without consuming their bytes: the rest of the file is
    // misread (the fuzzer found a 301-byte file that kept the reader busy for ~50 s).
    Watchdog dog("binary ply types", 60);
    auto binaryPly = [](const std::string& xType, const std::string& indexType) {
        std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty " + xType +
                        " x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 1\n"
                        "property list uchar " +
                        indexType + " vertex_indices\nend_header\n";
        for (int v = 0; v < 3; ++v) {
            if (xType == "uchar") s.push_back(char(v == 1));
            else if (xType == "int") {
                const int32_t x = v == 1;
                s.append(reinterpret_cast<const char*>(&x), 4);
            } else {
                const float x = float(v == 1);
                s.append(reinterpret_cast<const char*>(&x), 4);
            }
            const float rest[4] = {float(v == 2), 0.f, float(v == 1), float(v == 2)};
            s.append(reinterpret_cast<const char*>(rest), sizeof rest);
        }
        s.push_back(char(3));
        for (int i = 0; i < 3; ++i) {
            if (indexType == "float") {
                const float f = float(i);
                s.append(reinterpret_cast<const char*>(&f), 4);
            } else {
                const int32_t k = i;
                s.append(reinterpret_cast<const char*>(&k), 4);
            }
        }
        return s;
    };
    EXPECT_TRUE(loadsOrNamesFile(Kind::Mesh, write("ok.ply", binaryPly("float", "int"))));
    for (const auto& [x, index] :
         {std::pair<std::string, std::string>{"uchar", "int"}, {"int", "int"}, {"float", "float"}}) {
        std::string msg;
        EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("bad.ply", binaryPly(x, index)), &msg)) << x << " " << index;
        EXPECT_NE(msg.find("is not supported"), std::string::npos) << msg;
    }
    // The fuzzer's original input.
    const std::string found =
        std::string(test::sourceDir()) + "/tests/fuzz_corpus/ply/timeout-59d571a8a34814063d48c0bfebbefaf90db350f1";
    const std::string bytes = test::readText(found);
    ASSERT_FALSE(bytes.empty());
    EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("found.ply", bytes)));
}

TEST_F(BadFiles, integersBeyondTheirRangeAreRejectedWithoutOverflow) {
    // Found by the fuzzer (UBSan): |dx| + |dy| overflowed for offsets near LONG_MAX, and strtol's
    // saturation went unnoticed; an OFF count of ~1e38 was cast to size_t for the message.
    const std::string base = "*pattern\n0.01 0.01 0.001 2\n*Q\n0 0.005 0 0\n0.005 0.005 0 0\n*E\n0 1 0 0\n";
    std::string msg;
    EXPECT_FALSE(
        loadsOrNamesFile(Kind::Pattern, write("a.pyp", base + "1 0 9223372036854775807 -9223372036854775807\n"), &msg));
    EXPECT_NE(msg.find("a.pyp:8: edge offset"), std::string::npos) << msg;
    EXPECT_FALSE(loadsOrNamesFile(Kind::Pattern, write("b.pyp", base + "1 0 99999999999999999999 0\n"), &msg));
    EXPECT_NE(msg.find("b.pyp:8: integer '99999999999999999999' is out of range"), std::string::npos) << msg;
    EXPECT_TRUE(loadsOrNamesFile(Kind::Pattern, write("ok.pyp", base + "1 0 1 0\n"), &msg)) << msg;
    EXPECT_FALSE(loadsOrNamesFile(Kind::Mesh, write("c.off", "STOFF 1e38 1 0\n0 0 0 0 0\n3 0 0 0\n"), &msg));
    EXPECT_NE(msg.find("1e+38"), std::string::npos) << msg;
}

TEST_F(BadFiles, missingFilesAndDirectoriesAreNamed) {
    for (const char* name : {"missing.pyp", "missing.json", "missing.obj", "missing.ply", "missing.off"}) {
        const std::string path = (dir / name).string();
        const Kind kind =
            std::string(name).find(".pyp") != std::string::npos || std::string(name).find(".json") != std::string::npos
                ? Kind::Pattern
                : Kind::Mesh;
        std::string msg;
        EXPECT_FALSE(loadsOrNamesFile(kind, path, &msg));
        EXPECT_TRUE(msg.find("does not exist") != std::string::npos || msg.find("no such file") != std::string::npos)
            << msg;
        // A directory where the file is expected.
        fs::create_directories(dir / ("d" + std::string(name)));
        const std::string d = (dir / ("d" + std::string(name))).string();
        EXPECT_FALSE(loadsOrNamesFile(kind, d, &msg));
        EXPECT_NE(msg.find("directory"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace knit::hard
