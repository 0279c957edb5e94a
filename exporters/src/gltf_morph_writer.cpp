// gltf_morph_writer.cpp — MorphGlbWriter: one animated GLB, a morph target per frame (layout in
// knit/morph_gltf.hpp). The binary data grows in memory frame by frame; commit() writes the
// JSON chunk (nlohmann) and the BIN chunk through an AtomicFile.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "knit/budget.hpp"
#include "knit/error.hpp"
#include "knit/morph_gltf.hpp"
#include "material_extras.hpp"
#include "util/platform.hpp"

namespace knit {
namespace {

constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kModeLines = 1, kModeTriangles = 4;
constexpr double kGlbLimit = 4294967295.0;  // GLB lengths are uint32

// Exact float32 bounds of vec3 data, as glTF requires for POSITION (targets included).
nlohmann::json boundsJson(const std::vector<glm::vec3>& v, bool max) {
    glm::vec3 b(max ? -std::numeric_limits<float>::max() : std::numeric_limits<float>::max());
    for (const glm::vec3& p : v) b = max ? glm::max(b, p) : glm::min(b, p);
    if (v.empty()) b = glm::vec3(0.0f);
    return {b.x, b.y, b.z};
}

bool allFinite(const std::vector<glm::vec3>& v) {
    return std::all_of(v.begin(), v.end(), [](const glm::vec3& p) {
        return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    });
}

}  // namespace

double morphGlbBytes(size_t vertices, size_t indices, size_t frames, bool normals) {
    const double v = double(vertices), f = double(frames), perVertex = normals ? 24.0 : 12.0;
    const double base = v * (normals ? 24.0 : 16.0) + double(indices) * 4.0;
    return base + f * v * perVertex + f * 4.0 + f * f * 4.0 + 4096.0 + f * 400.0;
}

std::vector<uint32_t> segmentIndices(const std::vector<uint32_t>& offsets, const std::vector<uint8_t>& closed) {
    std::vector<uint32_t> out;
    for (size_t c = 0; c < closed.size(); ++c) {
        const uint32_t b = offsets[c], e = offsets[c + 1];
        if (e - b < 2) continue;
        for (uint32_t i = b; i + 1 < e; ++i) out.insert(out.end(), {i, i + 1});
        if (closed[c] != 0 && e - b > 2) out.insert(out.end(), {e - 1, b});
    }
    return out;
}

struct MorphGlbWriter::State {
    State(const std::string& p, MorphTopology t) : path(p), topology(std::move(t)) {}
    std::string path;
    MorphTopology topology;
    MorphGlbOptions options;
    size_t frames = 0, written = 0;
    glm::dvec3 origin{0.0};
    std::vector<glm::vec3> basePositions;  // float32, relative to origin
    std::vector<char> bin;
    nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array();
    nlohmann::json targets = nlohmann::json::array();

    // Appends `bytes` to the BIN data (4-byte aligned) as a bufferView; returns its index.
    int addView(const void* data, size_t bytes, int target) {
        const size_t offset = bin.size();
        bin.insert(bin.end(), static_cast<const char*>(data), static_cast<const char*>(data) + bytes);
        bin.resize((bin.size() + 3) & ~size_t(3), 0);
        nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
        if (target != 0) v["target"] = target;
        views.push_back(v);
        return int(views.size()) - 1;
    }
    int addAccessor(int view, int componentType, size_t count, const char* type) {
        accessors.push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
        return int(accessors.size()) - 1;
    }
    int addVec3(const std::vector<glm::vec3>& v, bool bounds) {
        const int a =
            addAccessor(addView(v.data(), v.size() * sizeof(glm::vec3), kArrayBuffer), kFloat, v.size(), "VEC3");
        if (bounds) {
            accessors[size_t(a)]["min"] = boundsJson(v, false);
            accessors[size_t(a)]["max"] = boundsJson(v, true);
        }
        return a;
    }
};

MorphGlbWriter::MorphGlbWriter(const std::string& path, MorphTopology base, size_t frames,
                               const MorphGlbOptions& options) {
    // Step 1: the path, the counts and the size a GLB can hold.
    if (util::lowerExtension(path) != "glb")
        throw Error("cannot write animated glTF '" + path + "': the extension must be .glb");
    impl::checkOutputFolder(path);
    if (frames == 0) throw Error("cannot write animated glTF '" + path + "': no frames");
    if (!(options.fps > 0 && std::isfinite(options.fps)))
        throw Error("cannot write animated glTF '" + path + "': the frame rate must be a positive number");
    const size_t n = base.positions.size();
    const double bytes = morphGlbBytes(n, base.indices.size(), frames, base.triangles);
    if (bytes > kGlbLimit)
        throw Error("cannot write animated glTF '" + path + "': needs about " + formatGiB(bytes) + " for " +
                    std::to_string(frames) + " frames of " + std::to_string(n) +
                    " vertices, over the 4 GiB a GLB holds; raise the frame step or lower the last frame for fewer " +
                    "frames, or write a point cache (.pc2)");
    if (base.triangles && base.normals.size() != n)
        throw Error("cannot write animated glTF '" + path + "': triangles need one normal per vertex");
    if (!base.colours.empty() && base.colours.size() != n)
        throw Error("cannot write animated glTF '" + path + "': " + std::to_string(base.colours.size()) +
                    " colours for " + std::to_string(n) + " vertices");
    state_ = std::make_unique<State>(path, std::move(base));
    State& s = *state_;
    s.options = options;
    s.frames = frames;
    s.bin.reserve(size_t(bytes));
    // Step 2: the local origin (centre of the first frame's bounds) and the base attributes.
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec3& p : s.topology.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (n > 0) s.origin = 0.5 * (lo + hi);
    s.basePositions.reserve(n);
    for (const glm::dvec3& p : s.topology.positions) s.basePositions.emplace_back(p - s.origin);
    if (!allFinite(s.basePositions)) throw Error("cannot write animated glTF '" + path + "': non-finite positions");
    s.addVec3(s.basePositions, true);                                // accessor 0: POSITION
    if (s.topology.triangles) s.addVec3(s.topology.normals, false);  // accessor 1: NORMAL
    else {
        const std::vector<float> radius(n, float(s.topology.radius));
        s.addAccessor(s.addView(radius.data(), n * 4, kArrayBuffer), kFloat, n, "SCALAR");  // accessor 1: _RADIUS
    }
    // Step 3: the indices, 16-bit where every index fits (65535 is the restart value).
    const std::vector<uint32_t>& idx = s.topology.indices;
    if (n <= 65535) {
        const std::vector<uint16_t> shorts(idx.begin(), idx.end());
        s.addAccessor(s.addView(shorts.data(), shorts.size() * 2, kElementArrayBuffer), kUnsignedShort, idx.size(),
                      "SCALAR");
    } else {
        s.addAccessor(s.addView(idx.data(), idx.size() * 4, kElementArrayBuffer), kUnsignedInt, idx.size(), "SCALAR");
    }
    // Step 4: COLOR_0 (accessor 3), the colours as normalized RGBA8, opaque; not morphed.
    if (!s.topology.colours.empty()) {
        std::vector<uint8_t> rgba(4 * n, 255);
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k)
                rgba[4 * i + k] = uint8_t(std::lround(255.0f * std::clamp(s.topology.colours[i][k], 0.0f, 1.0f)));
        s.addAccessor(s.addView(rgba.data(), rgba.size(), kArrayBuffer), kUnsignedByte, n, "VEC4");
        s.accessors[3]["normalized"] = true;
    }
}

MorphGlbWriter::~MorphGlbWriter() = default;

void MorphGlbWriter::writeFrame(const std::vector<glm::dvec3>& positions, const std::vector<glm::vec3>* normals) {
    State& s = *state_;
    const size_t n = s.basePositions.size();
    const std::string where = "animated glTF '" + s.path + "': frame " + std::to_string(s.written);
    if (s.written == s.frames) throw Error(where + ": more than the " + std::to_string(s.frames) + " frames announced");
    if (positions.size() != n)
        throw Error(where + " has " + std::to_string(positions.size()) + " vertices, the first frame " +
                    std::to_string(n));
    if (s.topology.triangles && (normals == nullptr || normals->size() != n))
        throw Error(where + ": one normal per vertex needed");
    // Step: POSITION (and NORMAL) deltas against the first frame, as float32.
    std::vector<glm::vec3> delta(n);
    for (size_t i = 0; i < n; ++i) delta[i] = glm::vec3(positions[i] - s.origin) - s.basePositions[i];
    if (!allFinite(delta)) throw Error(where + ": non-finite positions");
    nlohmann::json target = {{"POSITION", s.addVec3(delta, true)}};
    if (s.topology.triangles) {
        for (size_t i = 0; i < n; ++i) delta[i] = (*normals)[i] - s.topology.normals[i];
        target["NORMAL"] = s.addVec3(delta, false);
    }
    s.targets.push_back(target);
    ++s.written;
}

void MorphGlbWriter::commit() {
    State& s = *state_;
    if (s.written != s.frames)
        throw Error("animated glTF '" + s.path + "': " + std::to_string(s.written) + " of " + std::to_string(s.frames) +
                    " frames written");
    // Step 1: the animation: frame times and one-hot weights.
    const size_t f = s.frames;
    std::vector<float> times(f), weights(f * f, 0.0f);
    for (size_t k = 0; k < f; ++k) times[k] = float(double(k) / s.options.fps), weights[k * f + k] = 1.0f;
    const int input = s.addAccessor(s.addView(times.data(), f * 4, 0), kFloat, f, "SCALAR");
    s.accessors[size_t(input)]["min"] = {times.front()};
    s.accessors[size_t(input)]["max"] = {times.back()};
    const int output = s.addAccessor(s.addView(weights.data(), f * f * 4, 0), kFloat, f * f, "SCALAR");
    // Step 2: the JSON.
    nlohmann::json attributes = {{"POSITION", 0}};
    attributes[s.topology.triangles ? "NORMAL" : "_RADIUS"] = 1;
    if (!s.topology.colours.empty()) attributes["COLOR_0"] = 3;
    nlohmann::json extras = impl::parseMaterialExtras(s.options.extrasJson);
    if (extras.empty()) extras = {{"generator", "libknit"}};
    nlohmann::json j = {
        {"asset", {{"version", "2.0"}, {"generator", "libknit"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"name", "libknit"}, {"mesh", 0}, {"translation", {s.origin.x, s.origin.y, s.origin.z}}}}},
        {"materials", {{{"name", "yarn"}, {"extras", extras}}}},
        {"meshes",
         {{{"name", "knit"},
           {"weights", std::vector<float>(f, 0.0f)},
           {"primitives",
            {{{"attributes", attributes},
              {"indices", 2},
              {"material", 0},
              {"mode", s.topology.triangles ? kModeTriangles : kModeLines},
              {"targets", s.targets}}}}}}},
        {"animations",
         {{{"name", "frames"},
           {"samplers",
            {{{"input", input}, {"output", output}, {"interpolation", s.options.linear ? "LINEAR" : "STEP"}}}},
           {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}}},
        {"buffers", {{{"byteLength", s.bin.size()}}}},
        {"bufferViews", s.views},
        {"accessors", s.accessors}};
    if (!s.topology.triangles) j["asset"]["extras"] = {{"attributes", {{"_RADIUS", "curve radius (metres)"}}}};
    std::string text = j.dump();
    text.resize((text.size() + 3) & ~size_t(3), ' ');
    // Step 3: the GLB: header, JSON chunk, BIN chunk, through a temporary file.
    const uint64_t total = 12 + 8 + text.size() + 8 + s.bin.size();
    if (double(total) > kGlbLimit) throw Error("cannot write animated glTF '" + s.path + "': over 4 GiB");
    impl::AtomicFile file(s.path, true);
    auto u32 = [&](uint32_t v) { file.stream().write(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67), u32(2), u32(uint32_t(total));  // "glTF", version, length
    u32(uint32_t(text.size())), u32(0x4E4F534A), file.stream().write(text.data(), std::streamsize(text.size()));
    u32(uint32_t(s.bin.size())), u32(0x004E4942), file.stream().write(s.bin.data(), std::streamsize(s.bin.size()));
    file.commit();
}

}  // namespace knit
