// bound_scene_write.cpp — a bound rest scene as the bytes of a bound scene file
// (knit/bound_scene.hpp): the payload walked in boundSceneLayout's order, then the header with its
// size and CRC-32 in front.
#include <cstring>
#include <type_traits>

#include "knit/bound_scene.hpp"
#include "knit/error.hpp"
#include "knit/output_file.hpp"
#include "scene/bound_scene_format.hpp"
#include "scene/scene_budget.hpp"

namespace knit {
namespace {

// Appends the fields to a byte string.
class PayloadWriter {
public:
    explicit PayloadWriter(std::string& out) : out_(out) {}
    template <class T>
    void value(const T& v, const char*) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    // A std::vector or a util::SharedArray: its count, the zero padding that puts its first
    // element at a file offset multiple of 64 (format version 5), its elements.
    template <class Array>
    void array(const Array& v, const char* what) {
        value(static_cast<uint64_t>(v.size()), what);
        out_.append(impl::arrayPadding(impl::kBoundSceneHeaderBytes + out_.size()), '\0');
        out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(*v.data()));
    }
    void text(const std::string& s, const char* what) {
        value(static_cast<uint64_t>(s.size()), what);
        out_ += s;
    }
    void blocks(const std::map<std::string, std::vector<std::vector<double>>>& b, const char* what) {
        value(static_cast<uint64_t>(b.size()), what);
        for (const auto& [name, rows] : b) {
            text(name, what);
            value(static_cast<uint64_t>(rows.size()), what);
            for (const std::vector<double>& row : rows) array(row, what);
        }
    }

private:
    std::string& out_;
};

template <class T>
void put(std::string& out, T v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

// The deformation the scene was built with (format version 3): with strain, its table whole and
// the binding's pattern vertices; with none, neither.
void deformParts(const Scene& rest, impl::BoundSceneParts& parts) {
    const DeformOptions& d = rest.deformOptions();
    parts.deformReason = static_cast<uint32_t>(d.reason);
    parts.tableSeconds = d.tableSeconds;
    if (!rest.deformer()) {  // geometric (a view's scene without yarns never reaches here)
        parts.deformMode = static_cast<uint32_t>(DeformMode::None);
        parts.binding.source.clear();
        return;
    }
    parts.deformMode = static_cast<uint32_t>(DeformMode::Strain);
    parts.table = rest.deformer()->table();
    if (parts.strainTable.empty()) parts.strainTable = parts.table.source;  // where it came from
    if (parts.binding.source.size() != parts.binding.vertexCount())
        throw Error("a bound scene file of a strain-deformed scene needs the binding's pattern vertices");
}

}  // namespace

std::string encodeBoundScene(const Scene& rest, const BoundSceneInfo& info, const MemoryBudget& budget) {
    // Step 1: only a scene the pipeline bound (its pattern and placement) can be rebuilt.
    if (rest.pattern().name.empty() || rest.pattern().points.empty())
        throw Error("a bound scene file needs a scene built from a pattern and a mesh (this one was made from parts)");
    if (rest.detail()) throw Error("a bound scene file holds the whole scene; this one was built for a view");
    impl::BoundSceneParts parts;
    parts.settings = info.settings;
    parts.strainTable = info.strainTable;
    parts.pattern = rest.pattern();
    parts.placement = rest.placement();
    parts.mesh = rest.mesh();
    parts.binding = rest.binding();
    deformParts(rest, parts);
    parts.stats = rest.bindStats();
    parts.deformStats = rest.deformStats();
    parts.plies = rest.plyOptions();
    // The Animator's bind-time work, as every Animator of the rest scene does it (or the state a
    // loaded scene brought along).
    if (rest.animatorState()) {
        parts.animator = *rest.animatorState();
    } else {
        const PlyGenerator generator(rest.yarns(), rest.plyOptions());
        impl::checkPlyBudget(rest.yarns(), generator.options(), budget);
        parts.animator = computeAnimatorBindState(rest, generator);
    }
    // Step 2: the payload, then the header in front of it.
    std::string payload;
    PayloadWriter writer(payload);
    const impl::BoundSceneParts& constParts = parts;
    impl::boundSceneLayout(writer, constParts);
    std::string bytes(impl::kBoundSceneMagic, sizeof impl::kBoundSceneMagic);
    put(bytes, kBoundSceneFormatVersion);
    put(bytes, static_cast<uint32_t>(impl::kBoundSceneHeaderBytes));
    put(bytes, static_cast<uint64_t>(payload.size()));
    put(bytes, impl::payloadCrc32(payload.data(), payload.size()));
    put(bytes, uint32_t(0));
    return bytes + payload;
}

void writeBoundScene(const std::string& path, const Scene& rest, const BoundSceneInfo& info,
                     const MemoryBudget& budget) {
    requireWritableFolder(path, "bound scene");
    const std::string bytes = encodeBoundScene(rest, info, budget);
    writeFileAtomically(
        path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }, true);
}

}  // namespace knit
