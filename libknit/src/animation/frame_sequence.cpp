// frame_sequence.cpp — the files of a mesh sequence (printf pattern or numbered folder), each
// frame read and checked against the rest mesh's connectivity and UVs.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "knit/animation.hpp"
#include "knit/error.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

namespace fs = std::filesystem;

// A printf pattern split at its one integer conversion (%d, %4d, %04d).
struct NamePattern {
    std::string folder, prefix, spec, suffix;
};

bool splitPattern(const std::string& text, NamePattern& out) {
    const fs::path p(text);
    const std::string name = p.filename().string();
    size_t at = std::string::npos;
    for (size_t i = 0; i < name.size(); ++i) {
        if (name[i] != '%') continue;
        size_t j = i + 1;
        while (j < name.size() && std::isdigit(static_cast<unsigned char>(name[j]))) ++j;
        if (j >= name.size() || name[j] != 'd' || at != std::string::npos) return false;  // none or two
        at = i;
        out.spec = name.substr(i, j + 1 - i);
        i = j;
    }
    if (at == std::string::npos) return false;
    out.folder = p.parent_path().empty() ? "." : p.parent_path().string();
    out.prefix = name.substr(0, at);
    out.suffix = name.substr(at + out.spec.size());
    return true;
}

std::string format(const NamePattern& p, int number) {
    char buf[64];
    std::snprintf(buf, sizeof buf, p.spec.c_str(), number);
    return p.prefix + buf + p.suffix;
}

bool isMeshFile(const std::string& name) {
    for (const char* ext : {"obj", "ply", "off", "gltf", "glb"})
        if (util::lowerExtension(name) == ext) return true;
    return false;
}

// The number a file name carries: its last run of digits (-1: none).
long numberOf(const std::string& stem) {
    size_t e = stem.size();
    while (e > 0 && !std::isdigit(static_cast<unsigned char>(stem[e - 1]))) --e;
    size_t b = e;
    while (b > 0 && std::isdigit(static_cast<unsigned char>(stem[b - 1]))) --b;
    if (b == e || e - b > 9) return -1;
    return std::stol(stem.substr(b, e - b));
}

// Step: the numbered files that exist (pattern: names the pattern formats back exactly).
std::map<int, std::string> filesOfPattern(const NamePattern& p) {
    std::map<int, std::string> found;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(p.folder, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.size() <= p.prefix.size() + p.suffix.size() || name.compare(0, p.prefix.size(), p.prefix) != 0 ||
            name.compare(name.size() - p.suffix.size(), p.suffix.size(), p.suffix) != 0)
            continue;
        const long number = numberOf(name.substr(0, name.size() - p.suffix.size()));
        if (number >= 0 && format(p, static_cast<int>(number)) == name)
            found[static_cast<int>(number)] = entry.path().string();
    }
    return found;
}

std::map<int, std::string> filesOfFolder(const std::string& folder) {
    std::map<int, std::string> found;
    std::string extension;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() || !isMeshFile(name)) continue;
        const long number = numberOf(entry.path().stem().string());
        if (number < 0) continue;
        const std::string ext = util::lowerExtension(name);
        if (!extension.empty() && ext != extension)
            throw Error("the frame sequence: folder '" + folder + "' holds numbered meshes of two formats (" +
                        extension + " and " + ext + "); give a printf pattern such as frame_%04d." + extension);
        extension = ext;
        const auto [it, inserted] = found.emplace(static_cast<int>(number), entry.path().string());
        if (!inserted)
            throw Error("the frame sequence: folder '" + folder + "' holds two files numbered " +
                        std::to_string(number) + " ('" + it->second + "' and '" + entry.path().string() + "')");
    }
    return found;
}

}  // namespace

FrameSequence::FrameSequence(const std::string& source, const FrameRange& range) {
    // Step 1: the numbered files that exist (or the samples of one animated glTF).
    if (range.step < 1) throw Error("the frame step must be >= 1, got " + std::to_string(range.step));
    std::error_code ec;
    NamePattern pattern;
    const bool folder = fs::is_directory(source, ec);
    std::map<int, std::string> samples;
    if (isGltfAnimationSource(source)) {
        try {
            animation_ = std::make_shared<const GltfAnimation>(source, range.fps);
        } catch (const Error& e) {
            throw Error("the frame sequence '" + source + "': " + e.what());
        }
        for (size_t k = 0; k < animation_->times().size(); ++k) samples[int(k) + 1] = source;
    }
    if (!folder && !animation_ && !splitPattern(source, pattern))
        throw Error("the frame sequence: '" + source +
                    "' is neither a folder nor a file pattern with one integer conversion (e.g. frame_%04d.obj)");
    if (!folder && !animation_ && !fs::is_directory(pattern.folder, ec))
        throw Error("the frame sequence: folder '" + pattern.folder + "' of '" + source + "' does not exist");
    const std::map<int, std::string> found =
        animation_ ? samples : (folder ? filesOfFolder(source) : filesOfPattern(pattern));
    if (found.empty() && (range.first < 0 || range.last < 0))
        throw Error("the frame sequence: no numbered mesh files match '" + source + "'");

    // Step 2: the range; every frame in it must exist.
    const int first = range.first >= 0 ? range.first : found.begin()->first;
    const int last = range.last >= 0 ? range.last : found.rbegin()->first;
    if (last < first)
        throw Error("the frame sequence: the range " + std::to_string(first) + ".." + std::to_string(last) + " of '" +
                    source + "' is empty");
    for (long k = first; k <= last; k += range.step) {
        const int number = static_cast<int>(k);
        const auto it = found.find(number);
        if (it == found.end() && animation_)
            throw Error("frame " + std::to_string(number) + " is missing: '" + source + "' has " +
                        std::to_string(found.size()) + " samples (frames 1.." + std::to_string(found.size()) + ")");
        if (it == found.end())
            throw Error(
                "frame " + std::to_string(number) + " is missing: " +
                (folder ? "no mesh file numbered " + std::to_string(number) + " in folder '" + source + "'"
                        : "'" + (fs::path(pattern.folder) / format(pattern, number)).string() + "' does not exist"));
        frames_.push_back({number, it->second});
    }
}

BaseMesh FrameSequence::load(size_t i, const BaseMesh& rest) const {
    const FrameFile& f = frames_.at(i);
    std::string name = "frame " + std::to_string(f.number) + " ('" + f.path + "')";
    if (animation_)
        name = "frame " + std::to_string(f.number) + " ('" + f.path +
               "' at t = " + std::to_string(animation_->times()[size_t(f.number - 1)]) + " s)";
    BaseMesh mesh;
    try {
        mesh = animation_ ? animation_->sample(size_t(f.number - 1)) : loadMesh(f.path);
    } catch (const Error& e) {
        throw Error(name + ": " + e.what());
    }
    checkFrame(rest, mesh, name);
    return mesh;
}

void checkFrame(const BaseMesh& rest, const BaseMesh& frame, const std::string& name) {
    const auto count = [&](const char* what, size_t a, size_t b) {
        if (a != b)
            throw Error(name + ": has " + std::to_string(b) + " " + what + " but the rest mesh " + std::to_string(a) +
                        " (a sequence must keep the rest mesh's connectivity and UVs)");
    };
    const auto triple = [](const glm::uvec3& t) {
        return "(" + std::to_string(t.x) + ", " + std::to_string(t.y) + ", " + std::to_string(t.z) + ")";
    };
    // Step 1: counts; step 2: faces and UV faces; step 3: UV coordinates.
    count("vertices", rest.positions.size(), frame.positions.size());
    count("faces", rest.faces.size(), frame.faces.size());
    count("UVs", rest.uvs.size(), frame.uvs.size());
    for (size_t f = 0; f < rest.faces.size(); ++f) {
        if (rest.faces[f] != frame.faces[f])
            throw Error(name + ": face " + std::to_string(f) + " has vertices " + triple(frame.faces[f]) +
                        " but the rest mesh " + triple(rest.faces[f]));
        if (rest.faceUvs[f] != frame.faceUvs[f])
            throw Error(name + ": face " + std::to_string(f) + " has UV indices " + triple(frame.faceUvs[f]) +
                        " but the rest mesh " + triple(rest.faceUvs[f]));
    }
    for (size_t i = 0; i < rest.uvs.size(); ++i)
        if (rest.uvs[i] != frame.uvs[i])
            throw Error(name + ": UV " + std::to_string(i) + " is (" + std::to_string(frame.uvs[i].x) + ", " +
                        std::to_string(frame.uvs[i].y) + ") but (" + std::to_string(rest.uvs[i].x) + ", " +
                        std::to_string(rest.uvs[i].y) + ") in the rest mesh");
}

}  // namespace knit
