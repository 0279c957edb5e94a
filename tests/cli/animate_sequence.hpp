// Small mesh sequences for the animation CLI tests, generated in code, and readers of what
// `knit animate` writes (OBJ vertices, PC2 frames).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "common/run_knit.hpp"

namespace knit::test {

// An n x n quad grid (0.1 m square, UVs in [0, 1]) with a travelling wave whose amplitude
// grows with the frame number k (frame 1 is flat).
inline void writeWaveFrame(const std::filesystem::path& path, int k, int n) {
    std::ostringstream s;
    s.precision(17);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = 0.1 * i / n, y = 0.1 * j / n;
            s << "v " << x << ' ' << y << ' ' << 0.003 * (k - 1) * std::sin(60 * x + 0.3 * k) << '\n';
        }
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) s << "vt " << double(i) / n << ' ' << double(j) / n << '\n';
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
            s << "f " << a << '/' << a << ' ' << b << '/' << b << ' ' << c << '/' << c << '\n';
            s << "f " << a << '/' << a << ' ' << c << '/' << c << ' ' << d << '/' << d << '\n';
        }
    std::ofstream(path) << s.str();
}

inline void writeWaveSequence(const std::filesystem::path& dir, int frames, int n) {
    for (int k = 1; k <= frames; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.obj", k);
        writeWaveFrame(dir / name, k, n);
    }
}

inline std::vector<glm::dvec3> objVertices(const std::string& path) {
    std::ifstream in(path);
    std::vector<glm::dvec3> v;
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) != 0) continue;
        std::istringstream ls(line.substr(2));
        glm::dvec3 p;
        ls >> p.x >> p.y >> p.z;
        v.push_back(p);
    }
    return v;
}

// Frame `k` (0-based sample) of a PC2 file, read independently of the writer.
inline std::vector<glm::dvec3> pc2Frame(const std::string& path, int k) {
    std::ifstream in(path, std::ios::binary);
    const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= uint32_t(uint8_t(b[at + i])) << (8 * i);
        return v;
    };
    auto f32 = [&](size_t at) {
        const uint32_t v = u32(at);
        float f;
        std::memcpy(&f, &v, 4);
        return double(f);
    };
    const uint32_t points = u32(16);
    std::vector<glm::dvec3> out;
    for (uint32_t p = 0; p < points; ++p) {
        const size_t at = 32 + (size_t(k) * points + p) * 12;
        out.emplace_back(f32(at), f32(at + 4), f32(at + 8));
    }
    return out;
}

// Runs a bash script in `cwd`; its stdout + stderr go to `cwd`/shell.log, which is read back
// and removed.
inline CliRun runShell(const std::string& script, const std::filesystem::path& cwd) {
    const std::filesystem::path scriptFile = cwd / "shell.sh", log = cwd / "shell.log";
    std::ofstream(scriptFile) << script << '\n';
    const int status = std::system(("cd '" + cwd.string() + "' && bash shell.sh > shell.log 2>&1").c_str());
    CliRun r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(log);
    r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    in.close();
    std::filesystem::remove(scriptFile);
    std::filesystem::remove(log);
    return r;
}

}  // namespace knit::test
