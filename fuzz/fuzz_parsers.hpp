// fuzz_parsers.hpp — one entry point per parser, shared by the libFuzzer targets (fuzz/*_fuzzer.cpp)
// and by the corpus replay test (tests/hard/fuzz_corpus_test.cpp).
//
// Contract under test: any byte string either parses into a value that passes validation and the
// cheap downstream steps, or raises knit::Error. Anything else — another exception type, a crash,
// a sanitizer report, a hang — is a bug. The harnesses catch knit::Error only, so any other
// exception escapes to libFuzzer (reported as a crash) or to GoogleTest (reported as a failure).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include <boost/crc.hpp>

#include "knit/animation.hpp"
#include "knit/base_mesh.hpp"
#include "knit/bound_scene.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/error.hpp"
#include "knit/pattern.hpp"
#include "knit/strain.hpp"
#include "knit/uv_grid.hpp"
#ifdef KNIT_FUZZ_HAVE_RENDER_CHECK
#include <stdexcept>

#include "knit/ply_material.hpp"
#endif

namespace knit::fuzz {

enum class Outcome { Parsed, Rejected };

// Inputs larger than this are skipped (keeps every run fast; parsers are linear in the input).
constexpr size_t kMaxInput = 1 << 16;

// .pyp text -> Pattern; on success also the topology and the curves-only split (which may
// refuse a pattern with knit::Error: a loop without a periodic edge has no curves-only form).
inline Outcome runPyp(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    Pattern p;
    try {
        p = parsePyp(in, "fuzz.pyp");
        validatePattern(p, p.name);
        describePattern(p);
    } catch (const Error&) {
        return Outcome::Rejected;
    }
    try {
        splitAtPeriodicEdges(p);
    } catch (const Error&) {
    }
    return Outcome::Parsed;
}

// Strain table: the input is the axes text, then the .npy bytes from their "\x93NUMPY" magic on
// (no magic: all axes text, no .npy). On success, lookups anywhere (inside, outside, NaN) are
// finite and the table describes itself consistently.
inline Outcome runStrainTable(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    const std::string all(reinterpret_cast<const char*>(data), size);
    const size_t magic = all.find("\x93NUMPY");
    const std::string axes = all.substr(0, magic), npy = magic == std::string::npos ? "" : all.substr(magic);
    StrainTable t;
    try {
        t = parseStrainTable(npy, axes, "fuzz.npy");
    } catch (const Error&) {
        return Outcome::Rejected;
    }
    if (t.data.size() != 4 * t.vertexCount * t.samples()) throw std::logic_error("table size does not match its axes");
    const double nan = std::nan("");
    for (const Strain s : {Strain{0, 0, 0}, Strain{-5, 2, 9}, Strain{nan, nan, nan}, Strain{1e300, -1e300, 0.5}}) {
        bool clamped = false;
        const glm::dvec4 d = lookupStrainTable(t, uint32_t(t.vertexCount - 1), s, &clamped);
        if (!std::isfinite(d.x + d.y + d.z + d.w)) throw std::logic_error("non-finite lookup");
    }
    return Outcome::Parsed;
}

// Curves JSON -> CurveCell -> Pattern (partner search).
inline Outcome runCurvesJson(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    try {
        const CurveCell cell = parseCurvesJson(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
        patternFromCurves(cell);  // the partner search is sub-quadratic (a point grid): any size
        PartnerOptions absurd;    // and bounded for absurd tolerances
        absurd.tolerance = 1e300;
        patternFromCurves(cell, absurd);
        return Outcome::Parsed;
    } catch (const Error&) {
        return Outcome::Rejected;
    }
}

// A file named for this process in the temp folder, removed on exit.
class TempFile {
public:
    explicit TempFile(const std::string& extension) {
        path_ =
            (std::filesystem::temp_directory_path() / ("knit_fuzz_" + std::to_string(::getpid()) + extension)).string();
    }
    ~TempFile() { std::remove(path_.c_str()); }
    const std::string& write(const uint8_t* data, size_t size) {
        // Unlink, then create: rewriting a non-empty file through truncation makes ext4 flush it
        // (auto_da_alloc), ~4 ms per input instead of ~0.1 ms.
        std::remove(path_.c_str());
        std::ofstream(path_, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
        return path_;
    }

private:
    std::string path_;
};

// A loaded mesh through the cheap downstream steps: validation, normals, UV scale, a UV grid
// (capped at 2^16 cells, larger grids are rejected with knit::Error) and one point location.
inline void checkMesh(const BaseMesh& m) {
    validateMesh(m);
    vertexNormals(m.positions, m.faces);
    const glm::dvec2 scale = uvToMetreScale(m);
    (void)scale;
    UvGridOptions o;
    o.cellSize = glm::dvec2(1.0 / 8);
    o.maxCells = 1 << 16;
    o.maxEntries = 1 << 20;  // a 64 KB file of stacked huge triangles may not ask for 10^8 entries
    const UvGrid grid = buildUvGrid(m, o);
    locatePoint(m, grid, glm::dvec2(0.5), 1e-3);
}

// Mesh bytes written to a temp file with the format's extension (.obj, .ply, .off) -> loadMesh,
// then checkMesh.
inline Outcome runMesh(const uint8_t* data, size_t size, TempFile& file) {
    if (size > kMaxInput) return Outcome::Rejected;
    const std::string& path = file.write(data, size);
    try {
        checkMesh(loadMesh(path));
        return Outcome::Parsed;
    } catch (const Error&) {
        return Outcome::Rejected;
    }
}

// glTF (JSON or GLB) from memory, external files refused, at most 2^20 vertices / triangles ->
// parseGltfMesh, then checkMesh.
inline Outcome runGltf(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    try {
        MeshLoadOptions options;
        options.maxElements = 1 << 20;  // instancing may not blow a 64 KB input up beyond this
        checkMesh(parseGltfMesh(std::string(reinterpret_cast<const char*>(data), size), "fuzz.gltf", "", options));
        return Outcome::Parsed;
    } catch (const Error&) {
        return Outcome::Rejected;
    }
}

// glTF with animation (from memory, external files refused) -> GltfAnimation -> its first
// four samples (at most 2^20 vertices / triangles each) through checkMesh.
inline Outcome runGltfAnimation(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    try {
        const auto anim = GltfAnimation::fromBytes(std::string(reinterpret_cast<const char*>(data), size), "fuzz.gltf");
        MeshLoadOptions options;
        options.maxElements = 1 << 20;
        for (size_t i = 0; i < anim->times().size() && i < 4; ++i) checkMesh(anim->sample(i, options));
        return Outcome::Parsed;
    } catch (const Error&) {
        return Outcome::Rejected;
    }
}

inline Outcome runObj(const uint8_t* data, size_t size) {
    static TempFile file(".obj");
    return runMesh(data, size, file);
}
inline Outcome runPly(const uint8_t* data, size_t size) {
    static TempFile file(".ply");
    return runMesh(data, size, file);
}
inline Outcome runOff(const uint8_t* data, size_t size) {
    static TempFile file(".off");
    return runMesh(data, size, file);
}

// Stitch chart text -> Chart (every stitch's source column inside the chart) -> initial cell
// (validated by chartToCell) for charts of at most 64 stitches.
inline Outcome runChart(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    try {
        const Chart chart = parseChart(std::string(reinterpret_cast<const char*>(data), size), "fuzz.chart");
        if (chart.width <= 0 || chart.height <= 0 || chart.kind.size() != size_t(chart.width) * size_t(chart.height))
            throw std::logic_error("chart: inconsistent size");
        for (int r = 0; r < chart.height; ++r)
            for (int c = 0; c < chart.width; ++c)
                for (const int j : chart.sources(r, c))
                    if (j < 0 || j >= chart.width) throw std::logic_error("chart: source column outside");
        if (chart.width * chart.height <= 64) chartToCell(chart, ChartCellOptions{0.001, 8});
        return Outcome::Parsed;
    } catch (const Error&) {
        return Outcome::Rejected;
    }
}

#ifdef KNIT_FUZZ_HAVE_RENDER_CHECK
// Render material JSON (the --material file of `knit render`) through loadMaterialFile. A
// material it accepts must also come out of the same bytes as text (parseMaterialJson) and
// survive materialJsonText -> parseMaterialJson unchanged; a difference, or a knit::Error in
// those steps, is a bug (std::logic_error).
inline Outcome runMaterial(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    static TempFile file(".json");
    const std::string& path = file.write(data, size);
    PlyMaterial m;
    try {
        m = loadMaterialFile(path);
        validateMaterial(m);
    } catch (const Error&) {
        return Outcome::Rejected;
    }
    try {
        const std::string text = materialJsonText(m);
        const std::string bytes(reinterpret_cast<const char*>(data), size);
        if (materialJsonText(parseMaterialJson(bytes, "text")) != text)
            throw std::logic_error("material: the file and the same text parse differently");
        if (materialJsonText(parseMaterialJson(text, "round trip")) != text)
            throw std::logic_error("material: materialJsonText does not read back: " + text);
    } catch (const Error& e) {
        throw std::logic_error(std::string("material: accepted as a file, refused as text: ") + e.what());
    }
    return Outcome::Parsed;
}
#endif

// Bound scene file bytes -> Scene -> an Animator evaluating the rest pose. An input starting
// with 'P' is a payload: it gets a valid header and checksum first, so the fuzzer reaches the
// field reader and the consistency checks behind the CRC (any other input is a whole file). The
// Animator adopts the file's stored bind-time state (format version 2: resampling layout, phases,
// frame seeds) and replays it on the pose, so a state the checks let through must be safe to use.
inline Outcome runBoundScene(const uint8_t* data, size_t size) {
    if (size > kMaxInput) return Outcome::Rejected;
    std::string bytes(reinterpret_cast<const char*>(data), size);
    if (!bytes.empty() && bytes[0] == 'P') {
        const std::string payload = bytes.substr(1);
        boost::crc_32_type crc;
        crc.process_bytes(payload.data(), payload.size());
        const uint32_t head[6] = {kBoundSceneFormatVersion,
                                  32,
                                  static_cast<uint32_t>(payload.size()),
                                  0,
                                  static_cast<uint32_t>(crc.checksum()),
                                  0};
        bytes = std::string("KNITBIND") + std::string(reinterpret_cast<const char*>(head), sizeof head) + payload;
    }
    try {
        const MemoryBudget budget(uint64_t(64) << 20);
        // Owned bytes: the Animator state's largest arrays are used in place, as readBoundScene
        // uses them in its map of a file.
        const auto owned = std::make_shared<const std::string>(std::move(bytes));
        const BoundScene b = decodeBoundScene(*owned, owned, "fuzz.knitbind", budget);
        AnimatorOptions options;
        options.budget = budget;
        const Animator animator(b.scene, options);
        AnimationFrame frame;
        animator.evaluate(b.scene.mesh().positions, frame);
    } catch (const Error&) {
        return Outcome::Rejected;
    }
    return Outcome::Parsed;
}

}  // namespace knit::fuzz
