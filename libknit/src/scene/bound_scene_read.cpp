// bound_scene_read.cpp — a bound scene file (knit/bound_scene.hpp) back into a Scene: the header
// (magic, format version, size, CRC-32), the payload walked in boundSceneLayout's order with
// every count checked against the bytes left before anything is allocated, the invariants the
// evaluation relies on, then what is a pure function of the stored parts (rest normals, UV grid,
// strain deformer) rebuilt with the pipeline's own calls, and the stored Animator state checked
// against the binding and handed to the scene. The rest yarns are not evaluated here: the scene
// evaluates them on first use (Scene::yarns, SceneParts::lazyYarns), since its Animators need
// none of them (their stretch references are stored) and they were a quarter of the memory a
// load allocates (allocating it was most of a load's cost: docs/scale-out.md). For the same
// reason the Animator state's largest arrays (rest arc lengths, twist phases, segment lengths)
// are not copied at all when the bytes have an owner (readBoundScene's memory map): they stay in
// place, as views that keep the map open; every value in them is still checked here, before any
// use (reading the map allocates nothing).
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <type_traits>
#include <utility>

#include "knit/bound_scene.hpp"
#include "knit/error.hpp"
#include "knit/uv_grid.hpp"
#include "scene/bound_scene_format.hpp"
#include "scene/scene_budget.hpp"
#include "util/checks.hpp"
#include "util/shared_array.hpp"

namespace knit {
namespace {

std::string boundName(const std::string& name) { return "bound scene '" + name + "'"; }

// The packed elements of an array in the payload (at any byte: the payload is not aligned), as
// a random-access iterator, so that vector::assign allocates once and copies without zeroing.
template <class T>
struct Unaligned {
    static_assert(std::is_trivially_copyable_v<T>);
    using iterator_category = std::random_access_iterator_tag;
    using value_type = T;
    using difference_type = std::ptrdiff_t;
    using pointer = const T*;
    using reference = T;
    const char* at;
    T operator*() const {
        T v;
        std::memcpy(static_cast<void*>(&v), at, sizeof(T));
        return v;
    }
    Unaligned& operator++() {
        at += sizeof(T);
        return *this;
    }
    Unaligned operator++(int) {
        Unaligned old = *this;
        at += sizeof(T);
        return old;
    }
    Unaligned& operator--() {
        at -= sizeof(T);
        return *this;
    }
    Unaligned& operator+=(difference_type n) {
        at += n * static_cast<difference_type>(sizeof(T));
        return *this;
    }
    difference_type operator-(const Unaligned& o) const {
        return static_cast<difference_type>((at - o.at) / static_cast<difference_type>(sizeof(T)));
    }
    bool operator==(const Unaligned& o) const { return at == o.at; }
    bool operator!=(const Unaligned& o) const { return at != o.at; }
};

// Reads the fields from the payload; every count is checked against the bytes left. With an
// owner (it keeps the bytes valid and unchanged), the util::SharedArray fields are left in place
// as views into the bytes; otherwise, and for every std::vector field, the elements are copied.
class PayloadReader {
public:
    PayloadReader(std::string_view bytes, std::shared_ptr<const void> owner, const std::string& name)
        : bytes_(bytes), owner_(std::move(owner)), name_(name) {}
    template <class T>
    void value(T& v, const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        need(sizeof(T), what);
        std::memcpy(&v, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
    }
    template <class T>
    void array(std::vector<T>& v, const char* what) {
        const uint64_t n = count(sizeof(T), what);
        // Copied into fresh memory once (resize would zero it first: a fifth of a load's copy).
        const char* from = bytes_.data() + at_;
        v.assign(Unaligned<T>{from}, Unaligned<T>{from + n * sizeof(T)});
        at_ += n * sizeof(T);
    }
    template <class T>
    void array(util::SharedArray<T>& v, const char* what) {
        const size_t start = at_;
        const uint64_t n = count(sizeof(T), what);
        const char* from = bytes_.data() + at_;
        if (owner_ && reinterpret_cast<uintptr_t>(from) % alignof(T) == 0) {  // in place
            v = util::SharedArray<T>(owner_, reinterpret_cast<const T*>(from), n);
            at_ += n * sizeof(T);
        } else {
            at_ = start;
            std::vector<T> copy;
            array(copy, what);
            v = std::move(copy);
        }
    }
    void text(std::string& s, const char* what) {
        const uint64_t n = length(what);
        s.assign(bytes_.data() + at_, n);
        at_ += n;
    }
    void blocks(std::map<std::string, std::vector<std::vector<double>>>& b, const char* what) {
        const uint64_t n = length(what, 2 * sizeof(uint64_t));  // each block: a name and a row count at least
        for (uint64_t i = 0; i < n; ++i) {
            std::string key;
            text(key, what);
            std::vector<std::vector<double>>& rows = b[key];
            rows.resize(length(what, sizeof(uint64_t)));  // each row: its length at least
            for (std::vector<double>& row : rows) array(row, what);
        }
    }
    size_t left() const { return bytes_.size() - at_; }

private:
    // An array's count of elements of `size` bytes and the zero padding after it (format version
    // 5: elements at file offsets multiple of 64); refused when they would not fit in the bytes
    // left, or the padding is not zero (a payload written without it: an older format).
    uint64_t count(size_t size, const char* what) {
        uint64_t n = 0;
        value(n, what);
        const size_t padding = impl::arrayPadding(impl::kBoundSceneHeaderBytes + at_);
        need(padding, what);
        for (size_t i = 0; i < padding; ++i)
            if (bytes_[at_ + i] != 0)
                throw Error(boundName(name_) + " is damaged: the padding before " + what + " is not zero (byte " +
                            std::to_string(at_ + i) + " of the payload; arrays start at file offsets multiple of " +
                            std::to_string(impl::kBoundSceneArrayAlignment) + ")");
        at_ += padding;
        return checkedCount(n, size, what);
    }
    // A length (of a text, or of blocks of at least `size` bytes each: no padding), refused when
    // it would not fit in the bytes left.
    uint64_t length(const char* what, size_t size = 1) {
        uint64_t n = 0;
        value(n, what);
        return checkedCount(n, size, what);
    }
    uint64_t checkedCount(uint64_t n, size_t size, const char* what) const {
        if (n > left() / size)
            throw Error(boundName(name_) + " is damaged: " + what + " claim " + std::to_string(n) + " elements of " +
                        std::to_string(size) + " bytes, but only " + std::to_string(left()) + " bytes are left");
        return n;
    }
    void need(size_t n, const char* what) const {
        if (n > left())
            throw Error(boundName(name_) + " is damaged: it ends inside " + what + " (byte " + std::to_string(at_) +
                        " of the payload)");
    }
    std::string_view bytes_;
    std::shared_ptr<const void> owner_;
    std::string name_;
    size_t at_ = 0;
};

template <class T>
T get(std::string_view bytes, size_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    return v;
}

// Step 1: the header; returns the payload.
std::string_view checkHeader(std::string_view bytes, const std::string& name) {
    const size_t kHeader = impl::kBoundSceneHeaderBytes;
    if (bytes.size() < sizeof impl::kBoundSceneMagic ||
        std::memcmp(bytes.data(), impl::kBoundSceneMagic, sizeof impl::kBoundSceneMagic) != 0)
        throw Error("'" + name +
                    "' is not a bound scene file (it does not start with KNITBIND; write one with `knit bind`)");
    if (bytes.size() < kHeader)
        throw Error(boundName(name) + " is truncated: " + std::to_string(bytes.size()) + " bytes, shorter than its " +
                    std::to_string(kHeader) + "-byte header");
    const uint32_t version = get<uint32_t>(bytes, 8);
    if (version != kBoundSceneFormatVersion)
        throw Error(boundName(name) + " has format version " + std::to_string(version) + " (written by " +
                    (version < kBoundSceneFormatVersion ? "an older" : "a newer") + " knit); this knit reads version " +
                    std::to_string(kBoundSceneFormatVersion) +
                    " only: bind the scene again with this knit (`knit bind --mesh REST ... -o " + name + "`)");
    if (get<uint32_t>(bytes, 12) != kHeader || get<uint32_t>(bytes, 28) != 0)
        throw Error(boundName(name) + " is damaged: its header is not a version " +
                    std::to_string(kBoundSceneFormatVersion) + " header");
    const uint64_t payload = get<uint64_t>(bytes, 16), present = bytes.size() - kHeader;
    if (present < payload)
        throw Error(boundName(name) + " is truncated: it holds " + std::to_string(bytes.size()) + " bytes of the " +
                    std::to_string(kHeader + payload) + " its header announces");
    if (present > payload)
        throw Error(boundName(name) + " is damaged: " + std::to_string(present - payload) +
                    " bytes follow the payload its header announces");
    const std::string_view body = bytes.substr(kHeader);
    const uint32_t stored = get<uint32_t>(bytes, 24), computed = impl::payloadCrc32(body.data(), body.size());
    if (computed != stored) {
        std::ostringstream s;
        s << std::hex << "stored 0x" << stored << ", computed 0x" << computed;
        throw Error(boundName(name) + " is damaged: its checksum does not match its contents (CRC-32 " + s.str() + ")");
    }
    return body;
}

bool positiveFinite(double v) { return std::isfinite(v) && v > 0; }

// The embedded strain table in itself (what parseStrainTable checks of a table file): sample
// axes finite and increasing, data of the size they and the vertex count give, finite values.
void checkEmbeddedTable(const StrainTable& t) {
    static const char* const kAxis[3] = {"sx", "sa", "sy"};
    for (int a = 0; a < 3; ++a) {
        const std::vector<double>& v = t.axes[a];
        if (v.empty() || v.size() > 4096)
            throw Error("the strain table has " + std::to_string(v.size()) + " " + kAxis[a] + " samples (1 to 4096)");
        for (size_t i = 0; i < v.size(); ++i)
            if (!std::isfinite(v[i]) || (i > 0 && !(v[i] > v[i - 1])))
                throw Error(std::string("the strain table's ") + kAxis[a] + " samples are not finite and increasing");
    }
    if (t.vertexCount == 0 || t.vertexCount > t.data.size() / 4 / t.samples() ||
        t.data.size() != 4 * t.vertexCount * t.samples())
        throw Error("the strain table's data holds " + std::to_string(t.data.size()) + " values, not 4 x " +
                    std::to_string(t.vertexCount) + " vertices x " + std::to_string(t.samples()) + " samples");
    for (size_t i = 0; i < t.data.size(); ++i)
        if (!std::isfinite(t.data[i]))
            throw Error("the strain table's value " + std::to_string(i) + " (vertex " +
                        std::to_string(i / 4 / t.samples()) + ") is not finite");
    if (!(t.px >= 0 && t.py >= 0 && std::isfinite(t.px) && std::isfinite(t.py) && std::isfinite(t.radius)))
        throw Error("the strain table's period or radius is not finite and non-negative");
}

// Format version 3: the deform mode and why, and with strain the table (fitting the pattern) and
// a pattern vertex per yarn vertex; with none, neither.
void checkDeformParts(const impl::BoundSceneParts& p) {
    if (p.deformReason > static_cast<uint32_t>(DeformReason::CannotMake))
        throw Error("the deform reason " + std::to_string(p.deformReason) + " is unknown");
    if (!std::isfinite(p.tableSeconds)) throw Error("the strain table's seconds are not finite");
    const size_t n = p.binding.face.size();
    if (p.deformMode == static_cast<uint32_t>(DeformMode::None)) {
        const StrainTable& t = p.table;
        if (!p.binding.source.empty() || !t.data.empty() || t.vertexCount != 0 || !t.axes[0].empty() ||
            !t.axes[1].empty() || !t.axes[2].empty())
            throw Error("the deform mode is none, but a strain table or pattern vertices follow");
        const DeformStats& d = p.deformStats;
        if (d.vertices != 0 || d.clamped != 0 || d.degenerate != 0 || d.total != 0)
            throw Error("the deform mode is none, but deform statistics follow");
        return;
    }
    if (p.deformMode != static_cast<uint32_t>(DeformMode::Strain))
        throw Error("the deform mode " + std::to_string(p.deformMode) + " is unknown (0 none, 1 strain)");
    if (p.binding.source.size() != n)
        throw Error("the deform mode is strain, but " + std::to_string(p.binding.source.size()) +
                    " pattern vertices follow for " + std::to_string(n) + " yarn vertices");
    try {
        checkEmbeddedTable(p.table);
        checkStrainTable(p.table, p.pattern);
    } catch (const Error& e) {
        throw Error(std::string("its strain table ('") + p.table.source + "'): " + e.what());
    }
}

// Step 3: the invariants the evaluation relies on (a file with a valid checksum that another
// writer made inconsistent).
void checkParts(const impl::BoundSceneParts& p) {
    validatePattern(p.pattern, p.pattern.name);
    validateMesh(p.mesh);
    const PatternPlacement& pl = p.placement;
    if (!positiveFinite(pl.repeats.x) || !positiveFinite(pl.repeats.y) || !positiveFinite(pl.scale) ||
        !positiveFinite(p.pattern.radius * pl.scale))
        throw Error("the placement (repeats, scale) is not positive and finite");
    const Binding& b = p.binding;
    const size_t n = b.face.size();
    if (b.bary.size() != n || b.height.size() != n || (!b.twist.empty() && b.twist.size() != n) ||
        (!b.colour.empty() && b.colour.size() != n))
        throw Error("the binding's arrays differ in length (" + std::to_string(n) + " yarn vertices)");
    if (b.offsets.size() != b.closed.size() + 1 || b.offsets.front() != 0 || b.offsets.back() != n)
        throw Error("the yarn offsets do not cover the " + std::to_string(n) + " yarn vertices");
    for (size_t y = 0; y < b.closed.size(); ++y)
        if (b.offsets[y + 1] < b.offsets[y] || b.closed[y] > 1)
            throw Error("yarn " + std::to_string(y) + " has a bad offset or closed flag");
    for (size_t i = 0; i < n; ++i) {
        if (b.face[i] >= p.mesh.faces.size())
            throw Error("yarn vertex " + std::to_string(i) + " is bound to triangle " + std::to_string(b.face[i]) +
                        " of " + std::to_string(p.mesh.faces.size()));
        if (!util::finite(b.bary[i]) || !std::isfinite(b.height[i]) || (!b.twist.empty() && !std::isfinite(b.twist[i])))
            throw Error("yarn vertex " + std::to_string(i) + " has a coordinate that is not finite");
    }
    PlyOptions plies = p.plies;
    plies.yarnRadius = p.pattern.radius * pl.scale;
    (void)resolvePlyOptions(plies);  // throws for settings the evaluation would refuse
    checkDeformParts(p);
}

}  // namespace

BoundScene decodeBoundScene(std::string_view bytes, const std::string& name, const MemoryBudget& budget) {
    return decodeBoundScene(bytes, nullptr, name, budget);
}

BoundScene decodeBoundScene(std::string_view bytes, std::shared_ptr<const void> owner, const std::string& name,
                            const MemoryBudget& budget) {
    // Steps 1 and 2: the header, then the payload (sizes checked against the bytes present; the
    // Animator state's largest arrays left in place when `owner` keeps the bytes).
    const std::string_view payload = checkHeader(bytes, name);
    impl::BoundSceneParts p;
    PayloadReader reader(payload, std::move(owner), name);
    impl::boundSceneLayout(reader, p);
    if (reader.left() != 0)
        throw Error(boundName(name) + " is damaged: " + std::to_string(reader.left()) + " bytes follow its last field");
    // Step 3: the invariants, then what rebuilding needs, against the memory budget.
    try {
        checkParts(p);
    } catch (const Error& e) {
        throw Error(boundName(name) + " is inconsistent: " + e.what());
    }
    const double vertices = static_cast<double>(p.binding.face.size());
    const bool strain = p.deformMode == static_cast<uint32_t>(DeformMode::Strain);
    // The strain deformer: a pattern vertex per yarn vertex; per UV vertex its pattern-space
    // position, and per pose its strain and map.
    const double deformerBytes =
        strain ? 4.0 * vertices + 96.0 * static_cast<double>(p.mesh.uvs.size() + p.mesh.positions.size()) : 0.0;
    budget.require(static_cast<double>(payload.size()) + impl::kBytesPerYarnVertex * vertices +
                       48.0 * static_cast<double>(p.mesh.positions.size()) + deformerBytes,
                   "loading " + boundName(name), "the scene's size (bind fewer repeats)");
    impl::checkGridBudget(p.mesh, p.placement, false, budget);
    // Step 4: the rest normals and UV grid, as buildScene makes them; the rest yarns left to
    // Scene::yarns (lazily: evaluated from these parts on first use, bit for bit as here before).
    SceneParts parts;
    parts.yarnRadius = p.pattern.radius * p.placement.scale;
    parts.normals = vertexNormals(p.mesh.positions, p.mesh.faces);
    UvGridOptions gridOptions;
    gridOptions.cellSize = p.placement.cellSize();
    gridOptions.maxEntries = std::numeric_limits<uint64_t>::max();  // bounded by the memory budget above
    parts.grid = buildUvGrid(p.mesh, gridOptions);
    parts.lazyYarns = true;
    // Step 5: with strain, the deformer on the rest mesh, as buildScene's deform stage makes it
    // (Scene::yarns applies it to the rest yarns; what it did there is stored).
    parts.deformStats = p.deformStats;
    if (strain) {
        parts.deform = {DeformMode::Strain, std::make_shared<const StrainTable>(std::move(p.table)),
                        static_cast<DeformReason>(p.deformReason), p.tableSeconds};
        try {
            parts.deformer =
                std::make_shared<const StrainDeformer>(p.mesh, p.pattern, p.placement, p.binding, parts.deform.table);
        } catch (const Error& e) {
            throw Error(boundName(name) + " is inconsistent: its strain table: " + e.what());
        }
    } else {
        parts.deform.reason = static_cast<DeformReason>(p.deformReason);
        parts.deform.tableSeconds = p.tableSeconds;
    }
    try {
        checkAnimatorBindState(p.animator, p.binding);
    } catch (const Error& e) {
        throw Error(boundName(name) + " is inconsistent: its Animator state: " + e.what());
    }
    parts.animatorState = std::make_shared<const AnimatorBindState>(std::move(p.animator));
    parts.plyOptions = p.plies;
    parts.pattern = std::move(p.pattern);
    parts.placement = p.placement;
    parts.bindStats = p.stats;
    parts.mesh = std::move(p.mesh);
    parts.binding = std::move(p.binding);
    BoundScene out{Scene::fromParts(std::move(parts)),
                   {kBoundSceneFormatVersion, std::move(p.settings), std::move(p.strainTable)}};
    return out;
}

}  // namespace knit
