// Bound scene files (knit/bound_scene.hpp): a loaded scene evaluates frames to the same bytes as
// the scene that was saved, with its strain table when it has one, and its lazily evaluated rest
// yarns equal the saved scene's; other versions and damaged files are refused saying which.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include <boost/crc.hpp>

#include "knit/animation.hpp"
#include "knit/bound_scene.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/scene.hpp"
#include "knit/strain.hpp"
#include "scene/bound_scene_file.hpp"
#include "scene/bound_scene_format.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

Scene restScene() {
    SceneOptions o;
    o.pattern = "stockinette";
    o.mesh = "drape";
    o.meshOptions.resU = o.meshOptions.resV = 8;
    o.placement.repeats = {4, 4};
    o.buildPlies = false;
    o.plies.count = 3;
    return buildScene(o);
}

// The rest positions moved by a wave (a frame of the same connectivity).
std::vector<glm::dvec3> waved(const BaseMesh& m) {
    std::vector<glm::dvec3> p = m.positions;
    for (glm::dvec3& x : p) x.z += 0.01 * std::sin(40 * x.x) + 0.003 * x.y;
    return p;
}

std::string errorOf(const std::string& bytes) {
    try {
        decodeBoundScene(bytes, "g.knitbind");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// `bytes` with the header's checksum recomputed over its (edited) payload.
std::string resealed(std::string bytes) {
    boost::crc_32_type crc;
    crc.process_bytes(bytes.data() + 32, bytes.size() - 32);
    const uint32_t c = crc.checksum();
    std::memcpy(bytes.data() + 24, &c, 4);
    return bytes;
}

// Where each field's first element lies in a bound scene file (the payload walked with the
// format's own field list, boundSceneLayout).
class FieldOffsets {
public:
    explicit FieldOffsets(const std::string& file) : bytes_(file) {
        impl::BoundSceneParts parts;
        impl::boundSceneLayout(*this, parts);
    }
    size_t operator[](const std::string& what) const { return where_.at(what); }
    // Where an array's or a text's count lies.
    size_t countOf(const std::string& what) const { return counts_.at(what); }

    template <class T>
    void value(T& v, const char* what) {
        note(what);
        take(&v, sizeof v);
    }
    template <class T>
    void array(std::vector<T>& v, const char* what) {
        uint64_t n = 0;
        counts_.emplace(what, at_);
        take(&n, sizeof n);
        at_ += impl::arrayPadding(at_);  // the elements start at a file offset multiple of 64
        note(what);
        v.resize(n);
        take(v.data(), n * sizeof(T));
    }
    template <class T>
    void array(util::SharedArray<T>& v, const char* what) {
        std::vector<T> copy;
        array(copy, what);
        v = std::move(copy);
    }
    void text(std::string& s, const char* what) {
        uint64_t n = 0;
        counts_.emplace(what, at_);
        take(&n, sizeof n);
        note(what);
        s.resize(n);
        take(s.data(), n);
    }
    void blocks(std::map<std::string, std::vector<std::vector<double>>>& b, const char* what) {
        uint64_t n = 0;
        take(&n, sizeof n);
        for (uint64_t i = 0; i < n; ++i) {
            std::string key;
            text(key, what);
            uint64_t rows = 0;
            take(&rows, sizeof rows);
            b[key].resize(rows);
            for (std::vector<double>& row : b[key]) array(row, what);
        }
    }

private:
    void note(const char* what) { where_.emplace(what, at_); }
    void take(void* to, size_t n) {
        ASSERT_LE(at_ + n, bytes_.size());
        if (n == 0) return;  // an empty array's data() may be null, which memcpy must not get
        std::memcpy(to, bytes_.data() + at_, n);
        at_ += n;
    }
    const std::string& bytes_;
    size_t at_ = 32;  // the payload follows the header
    std::map<std::string, size_t> where_, counts_;
};

template <class T>
std::string withValue(std::string bytes, size_t at, T v) {
    std::memcpy(bytes.data() + at, &v, sizeof v);
    return resealed(bytes);
}

TEST(BoundScene, loadedSceneEvaluatesFramesToTheSameBytes) {
    const Scene rest = restScene();
    BoundSceneInfo info;
    info.settings = R"({"writer":"test"})";
    info.strainTable = "tables/wool.strain";
    const std::string bytes = encodeBoundScene(rest, info);
    const BoundScene loaded = decodeBoundScene(bytes, "g.knitbind");
    EXPECT_EQ(loaded.info.settings, info.settings);
    EXPECT_EQ(loaded.info.strainTable, info.strainTable);
    EXPECT_EQ(loaded.scene.pattern().name, rest.pattern().name);
    EXPECT_EQ(loaded.scene.yarnRadius(), rest.yarnRadius());
    EXPECT_EQ(loaded.scene.yarnMargin(), rest.yarnMargin());
    EXPECT_EQ(loaded.scene.bindStats().openEnds, rest.bindStats().openEnds);
    EXPECT_EQ(loaded.scene.grid().cells, rest.grid().cells);
    ASSERT_EQ(loaded.scene.yarns().curves.points, rest.yarns().curves.points);
    // The same frame through an Animator of each: the plies bit for bit.
    const Animator a(rest), b(loaded.scene);
    AnimationFrame fa, fb;
    const std::vector<glm::dvec3> frame = waved(rest.mesh());
    a.evaluate(frame, fa);
    b.evaluate(frame, fb);
    ASSERT_GT(fa.plies.curves.pointCount(), 1000u);
    EXPECT_EQ(fa.plies.curves.points, fb.plies.curves.points);
    EXPECT_EQ(fa.plies.curves.offsets, fb.plies.curves.offsets);
    EXPECT_EQ(fa.stats.maxStretch, fb.stats.maxStretch);
    // And the file round-trips to the same bytes.
    EXPECT_EQ(encodeBoundScene(loaded.scene, loaded.info), bytes);
}

TEST(BoundScene, otherVersionsAndDamagedFilesAreRefusedSayingWhich) {
    const std::string bytes = encodeBoundScene(restScene(), {});
    std::string v = bytes;
    v[8] = 7;  // format version 7
    EXPECT_NE(errorOf(v).find("has format version 7 (written by a newer knit); this knit reads version 5 only: bind "
                              "the scene again with this knit (`knit bind --mesh REST ... -o g.knitbind`)"),
              std::string::npos)
        << errorOf(v);
    v[8] = 4;  // a file of the previous format (arrays not aligned: they were copied out on loading)
    EXPECT_NE(errorOf(v).find("has format version 4 (written by an older knit); this knit reads version 5 only"),
              std::string::npos)
        << errorOf(v);
    v[8] = 3;  // no stretch references: the rest yarns were evaluated on loading
    EXPECT_NE(errorOf(v).find("has format version 3 (written by an older knit); this knit reads version 5 only"),
              std::string::npos)
        << errorOf(v);
    v[8] = 1;  // a file of the first format (no Animator state)
    EXPECT_NE(errorOf(v).find("has format version 1 (written by an older knit); this knit reads version 5 only"),
              std::string::npos)
        << errorOf(v);
    EXPECT_NE(errorOf(bytes.substr(0, bytes.size() - 100)).find("is truncated"), std::string::npos);
    EXPECT_NE(errorOf(bytes.substr(0, 20)).find("is truncated"), std::string::npos);
    EXPECT_NE(errorOf(bytes + "x").find("is damaged: 1 bytes follow"), std::string::npos);
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    EXPECT_NE(errorOf(flipped).find("is damaged: its checksum does not match"), std::string::npos);
    EXPECT_NE(errorOf("PK\3\4 a zip file").find("is not a bound scene file"), std::string::npos);
    // A count beyond the file (checksum valid): refused before allocating.
    std::string huge = bytes;
    const uint64_t n = uint64_t(1) << 60;
    std::memcpy(huge.data() + 32, &n, 8);  // the settings' length
    EXPECT_NE(errorOf(resealed(huge)).find("is damaged: the settings claim"), std::string::npos);
}

TEST(BoundScene, theAnimatorStateIsStoredAndAdoptedNotRecomputed) {
    const Scene rest = restScene();
    const std::string bytes = encodeBoundScene(rest, {});
    const BoundScene loaded = decodeBoundScene(bytes, "g.knitbind");
    ASSERT_TRUE(loaded.scene.animatorState());
    EXPECT_FALSE(rest.animatorState());
    // What the file holds is what an Animator computes on the rest scene.
    const PlyGenerator generator(rest.yarns(), rest.plyOptions());
    const AnimatorBindState fresh = computeAnimatorBindState(rest, generator);
    const AnimatorBindState& stored = *loaded.scene.animatorState();
    EXPECT_EQ(stored.kept, fresh.kept);
    EXPECT_EQ(stored.pieces, fresh.pieces);
    EXPECT_EQ(stored.centreOffsets, fresh.centreOffsets);
    EXPECT_EQ(stored.restArc, fresh.restArc);
    EXPECT_EQ(stored.restPhase, fresh.restPhase);
    EXPECT_EQ(stored.restPitch, fresh.restPitch);
    ASSERT_EQ(stored.seeds.size(), fresh.seeds.size());
    EXPECT_EQ(std::memcmp(stored.seeds.data(), fresh.seeds.data(), fresh.seeds.size() * sizeof fresh.seeds[0]), 0);
    // The loaded scene's Animator uses the stored twist phases: one changed in the file (and the
    // checksum resealed) changes that yarn's plies, and only when the phase is the stored one.
    const FieldOffsets at(bytes);
    const BoundScene edited =
        decodeBoundScene(withValue(bytes, at["the rest twist phases"] + 16 * 5, glm::dvec2(0.0, 1.0)), "g.knitbind");
    const Animator a(loaded.scene), b(edited.scene);
    AnimationFrame fa, fb;
    a.evaluate(rest.mesh().positions, fa);
    b.evaluate(rest.mesh().positions, fb);
    ASSERT_EQ(fa.plies.curves.points.size(), fb.plies.curves.points.size());
    EXPECT_NE(fa.plies.curves.points, fb.plies.curves.points);
    // An Animator of the yarns alone, of the statistics alone and with radial directions works on
    // the stored state as on a computed one.
    for (const bool plies : {false, true}) {
        AnimatorOptions options;
        options.plies = plies;
        options.radial = plies;
        const Animator c(rest, options), d(loaded.scene, options);
        AnimationFrame fc, fd;
        const std::vector<glm::dvec3> frame = waved(rest.mesh());
        c.evaluate(frame, fc);
        d.evaluate(frame, fd);
        EXPECT_EQ(fc.plies.curves.points, fd.plies.curves.points);
        EXPECT_EQ(fc.plies.radial, fd.plies.radial);
        EXPECT_EQ(fc.stats.minYarnDistance, fd.stats.minYarnDistance);
        EXPECT_EQ(fc.stats.maxStretch, fd.stats.maxStretch);
    }
}

TEST(BoundScene, anInconsistentAnimatorStateIsRefusedNamingTheYarn) {
    const std::string bytes = encodeBoundScene(restScene(), {});
    const FieldOffsets at(bytes);
    const std::string prefix = "bound scene 'g.knitbind' is inconsistent: its Animator state: ";
    // A kept point beyond its yarn (resampling would read past the yarn's points).
    std::string e = errorOf(withValue(bytes, at["the resampling layout's kept points"], uint32_t(1) << 30));
    EXPECT_NE(e.find(prefix + "yarn 0: kept point 0 (1073741824) is not increasing within its"), std::string::npos)
        << e;
    // More pieces than the resampled points the yarn has room for (it would write past them).
    e = errorOf(withValue(bytes, at["the resampling layout's pieces"], uint32_t(1000)));
    EXPECT_NE(e.find(prefix + "yarn 0: its layout makes"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the resampling layout's pieces"], uint32_t(0)));
    EXPECT_NE(e.find(prefix + "yarn 0: a segment has 0 pieces"), std::string::npos) << e;
    // Offsets that do not cover the arrays.
    e = errorOf(withValue(bytes, at["the resampled point offsets"] + 4, uint32_t(0xFFFFFFFF)));
    EXPECT_NE(e.find(prefix), std::string::npos) << e;
    // Values evaluation cannot use.
    e = errorOf(withValue(bytes, at["the rest twist phases"], std::numeric_limits<double>::quiet_NaN()));
    EXPECT_NE(e.find(prefix + "a rest arc length, twist phase, pitch or length is not finite"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the frame seeds"] + 120, uint8_t(2)));
    EXPECT_NE(e.find(prefix + "yarn 0: its frame seed has a bad flag"), std::string::npos) << e;
    // A count beyond the file in the new fields: refused before allocating.
    e = errorOf(withValue(bytes, at.countOf("the rest twist phases"), uint64_t(1) << 50));
    EXPECT_NE(e.find("is damaged: the rest twist phases claim 1125899906842624 elements of 16 bytes"),
              std::string::npos)
        << e;
}

// A strain table written here (the default pattern's vertex count, no period: any stockinette
// fits): displacements and a twist that grow with the strain, different per cell vertex.
std::shared_ptr<const StrainTable> testTable() {
    auto t = std::make_shared<StrainTable>();
    t->source = "tables/test.npy";
    t->axes = {std::vector<double>{-0.2, 0.3, 1.0}, std::vector<double>{-0.7, 0.7}, std::vector<double>{-0.2, 1.0}};
    const Pattern p = generateStockinette();
    t->vertexCount = p.points.size();
    const size_t nx = 3, na = 2, ny = 2;
    for (size_t row = 0; row < t->vertexCount * nx * na * ny; ++row) {
        const size_t isx = row % nx, isa = row / nx % na, isy = row / (nx * na) % ny, v = row / (nx * na * ny);
        const double k = 0.5 + double(v % 5) / 4;
        t->data.insert(t->data.end(), {float(0.03 * p.px * k * double(isx)), float(0.02 * p.py * k * double(isy)),
                                       float(0.01 * p.px * k * double(isa)), float(0.2 * double(isx))});
    }
    return t;
}

// The default pattern on the drape, placed more densely along u than v (a strained layout).
Scene strainedRestScene(const std::shared_ptr<const StrainTable>& table) {
    SceneOptions o;
    o.meshOptions.resU = o.meshOptions.resV = 8;
    o.placement.repeats = {4, 7};
    o.buildPlies = false;
    o.plies.count = 3;
    o.deform.mode = table ? DeformMode::Strain : DeformMode::None;
    o.deform.table = table;
    o.deform.reason = DeformReason::TableGiven;
    return buildScene(o);
}

TEST(BoundScene, aStrainSceneCarriesItsTableAndDeformsFramesToTheSameBytes) {
    const Scene rest = strainedRestScene(testTable()), geometric = strainedRestScene(nullptr);
    ASSERT_TRUE(rest.deformer());
    ASSERT_GT(rest.deformStats().vertices, 0u);  // the layout is strained: the table moves the yarns
    const std::string bytes = encodeBoundScene(rest, {});
    const BoundScene loaded = decodeBoundScene(bytes, "g.knitbind");
    // The table itself is in the file (the one given is not read again), and why it was used.
    ASSERT_TRUE(loaded.scene.deformer());
    const StrainTable& t = loaded.scene.deformer()->table();
    EXPECT_EQ(t.data, testTable()->data);
    EXPECT_EQ(t.axes, testTable()->axes);
    EXPECT_EQ(t.source, "tables/test.npy");
    EXPECT_EQ(loaded.info.strainTable, "tables/test.npy");
    EXPECT_EQ(loaded.scene.deformOptions().mode, DeformMode::Strain);
    EXPECT_EQ(loaded.scene.deformOptions().reason, DeformReason::TableGiven);
    EXPECT_EQ(loaded.scene.deformStats().vertices, rest.deformStats().vertices);
    EXPECT_EQ(loaded.scene.yarns().curves.points, rest.yarns().curves.points);
    EXPECT_EQ(loaded.scene.yarns().twist, rest.yarns().twist);
    EXPECT_GT(bytes.size(), encodeBoundScene(geometric, {}).size() + t.data.size() * sizeof(float));
    // A frame through an Animator of each: the yarns and plies bit for bit, and not the
    // geometric ones.
    const Animator a(rest), b(loaded.scene), g(geometric);
    AnimationFrame fa, fb, fg;
    const std::vector<glm::dvec3> frame = waved(rest.mesh());
    a.evaluate(frame, fa);
    b.evaluate(frame, fb);
    g.evaluate(frame, fg);
    ASSERT_GT(fa.deform.vertices, 0u);
    EXPECT_EQ(fa.yarns.curves.points, fb.yarns.curves.points);
    EXPECT_EQ(fa.plies.curves.points, fb.plies.curves.points);
    EXPECT_EQ(fa.deform.clamped, fb.deform.clamped);
    ASSERT_EQ(fa.yarns.curves.points.size(), fg.yarns.curves.points.size());
    EXPECT_NE(fa.yarns.curves.points, fg.yarns.curves.points);
    // A geometric scene stores no table nor pattern vertices, and loads without a deformer.
    const BoundScene none = decodeBoundScene(encodeBoundScene(geometric, {}), "n.knitbind");
    EXPECT_FALSE(none.scene.deformer());
    EXPECT_TRUE(none.scene.binding().source.empty());
    // The file round-trips to the same bytes.
    EXPECT_EQ(encodeBoundScene(loaded.scene, loaded.info), bytes);
}

TEST(BoundScene, aDamagedOrMismatchedEmbeddedTableIsRefusedNamingTheFile) {
    const std::string bytes = encodeBoundScene(strainedRestScene(testTable()), {});
    const FieldOffsets at(bytes);
    const size_t data = at["the strain table's data"];
    // A flipped bit in the table: the checksum covers it.
    std::string flipped = bytes;
    flipped[data + 5] ^= 0x04;
    std::string e = errorOf(flipped);
    EXPECT_NE(e.find("bound scene 'g.knitbind' is damaged: its checksum does not match"), std::string::npos) << e;
    // Checksum resealed: values, shape and fit are checked.
    const std::string prefix = "bound scene 'g.knitbind' is inconsistent: its strain table ('tables/test.npy'): ";
    e = errorOf(withValue(bytes, data + 4 * 9, std::numeric_limits<float>::quiet_NaN()));
    EXPECT_NE(e.find(prefix + "the strain table's value 9 (vertex 0) is not finite"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the strain table's vertex count"], uint64_t(7)));
    EXPECT_NE(e.find(prefix + "the strain table's data holds"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the strain table's sa samples"], 0.9));
    EXPECT_NE(e.find(prefix + "the strain table's sa samples are not finite and increasing"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the strain table's period"], 0.5));  // made for another period
    EXPECT_NE(e.find(prefix + "the strain table 'tables/test.npy' was made for the period"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the deform mode"], uint32_t(7)));
    EXPECT_NE(e.find("is inconsistent: the deform mode 7 is unknown"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the deform mode"], uint32_t(0)));  // none, with a table
    EXPECT_NE(e.find("is inconsistent: the deform mode is none, but a strain table"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at.countOf("the binding's pattern vertices"), uint64_t(3)));
    EXPECT_NE(e.find("bound scene 'g.knitbind' is"), std::string::npos) << e;  // the fields after it no longer line up
    // A file of the previous format (before the table was stored) says so.
    std::string v2 = bytes;
    v2[8] = 2;
    EXPECT_NE(errorOf(v2).find("has format version 2 (written by an older knit); this knit reads version 5 only"),
              std::string::npos)
        << errorOf(v2);
}

// The rest yarns of a loaded scene are evaluated lazily (Scene::yarns), from the binding, mesh
// and deformer; they must equal the bound scene's bit for bit, and what the Animator and the
// scene would have derived from them at load is stored instead, equal to what they derive.
void expectLazyRestYarnsEqual(const Scene& rest) {
    const BoundScene loaded = decodeBoundScene(encodeBoundScene(rest, {}), "g.knitbind");
    // An Animator with plies and statistics evaluating a frame asks nothing of the rest yarns.
    EXPECT_FALSE(loaded.scene.yarnsEvaluated());
    const Animator a(rest), b(loaded.scene);
    AnimationFrame fa, fb;
    const std::vector<glm::dvec3> frame = waved(rest.mesh());
    a.evaluate(frame, fa);
    b.evaluate(frame, fb);
    EXPECT_FALSE(loaded.scene.yarnsEvaluated());
    EXPECT_EQ(fa.plies.curves.points, fb.plies.curves.points);
    EXPECT_EQ(fa.plies.curves.closed, fb.plies.curves.closed);
    EXPECT_EQ(fa.stats.maxStretch, fb.stats.maxStretch);
    EXPECT_EQ(fa.stats.yarnLengthRatio, fb.stats.yarnLengthRatio);
    EXPECT_EQ(fa.stats.minYarnDistance, fb.stats.minYarnDistance);
    // The stored stretch references and deform statistics are what the rest scene gives.
    const PlyGenerator generator(rest.yarns(), rest.plyOptions());
    const AnimatorBindState fresh = computeAnimatorBindState(rest, generator);
    ASSERT_EQ(fresh.restSegment.size(), rest.yarns().curves.pointCount());
    EXPECT_EQ(loaded.scene.animatorState()->restSegment, fresh.restSegment);
    EXPECT_EQ(loaded.scene.animatorState()->restTotalLength, fresh.restTotalLength);
    EXPECT_EQ(std::memcmp(&loaded.scene.deformStats(), &rest.deformStats(), sizeof(DeformStats)), 0);
    // A copy made before the first call shares the evaluation; both give the bound yarns.
    const Scene copy = loaded.scene;
    const MappedYarns& y = loaded.scene.yarns();
    EXPECT_TRUE(loaded.scene.yarnsEvaluated());
    EXPECT_TRUE(copy.yarnsEvaluated());
    EXPECT_EQ(&copy.yarns(), &y);
    const MappedYarns& r = rest.yarns();
    EXPECT_EQ(y.curves.points, r.curves.points);
    EXPECT_EQ(y.curves.offsets, r.curves.offsets);
    EXPECT_EQ(y.curves.closed, r.curves.closed);
    EXPECT_EQ(y.normals, r.normals);
    EXPECT_EQ(y.colour, r.colour);
    EXPECT_EQ(y.twist, r.twist);
}

TEST(BoundScene, restYarnsAreEvaluatedOnFirstUseAndEqualTheBoundOnes) {
    expectLazyRestYarnsEqual(restScene());
    const Scene strained = strainedRestScene(testTable());
    ASSERT_FALSE(strained.yarns().twist.empty());  // the deformer's part of the yarns is compared too
    expectLazyRestYarnsEqual(strained);
}

TEST(BoundScene, badStretchReferencesOrDeformStatisticsAreRefused) {
    const std::string bytes = encodeBoundScene(restScene(), {});
    const FieldOffsets at(bytes);
    const std::string prefix = "bound scene 'g.knitbind' is inconsistent: ";
    std::string e = errorOf(withValue(bytes, at["the rest segment lengths"] + 8, -1.0));
    EXPECT_NE(e.find(prefix + "its Animator state: a rest segment length or the rest yarns' total length is negative"),
              std::string::npos)
        << e;
    e = errorOf(withValue(bytes, at["the rest yarns' total length"], std::numeric_limits<double>::infinity()));
    EXPECT_NE(e.find(prefix + "its Animator state: a rest segment length"), std::string::npos) << e;
    e = errorOf(withValue(bytes, at["the deform statistics"], uint64_t(5)));
    EXPECT_NE(e.find(prefix + "the deform mode is none, but deform statistics follow"), std::string::npos) << e;
}

// The frame and statistics of an Animator of `loaded` equal those of `bound` bit for bit.
void expectSameFrame(const Animator& bound, const Scene& loaded) {
    const Animator b(loaded);
    AnimationFrame fa, fb;
    const std::vector<glm::dvec3> frame = waved(bound.rest().mesh());
    bound.evaluate(frame, fa);
    b.evaluate(frame, fb);
    ASSERT_GT(fa.plies.curves.pointCount(), 1000u);
    EXPECT_EQ(fa.plies.curves.points, fb.plies.curves.points);
    EXPECT_EQ(fa.centres.points, fb.centres.points);
    EXPECT_EQ(fa.stats.maxStretch, fb.stats.maxStretch);
    EXPECT_EQ(fa.stats.yarnLengthRatio, fb.stats.yarnLengthRatio);
    EXPECT_EQ(fa.stats.minYarnDistance, fb.stats.minYarnDistance);
}

// Format version 5: readBoundScene maps the file and the loaded scene uses the Animator state's
// largest arrays in place (views sharing the map), read back into memory where mapping is not
// possible; either way frames are the bound scene's bit for bit, also through a copy of the
// scene that outlives the loaded original (the views keep the map open).
TEST(BoundScene, aMappedFileIsUsedInPlaceAndEvaluatesFramesToTheSameBytes) {
    const test::TempDir dir;
    const Scene rest = strainedRestScene(testTable());  // strain: the twist turns the stored phases
    const std::string path = dir.write("g.knitbind", encodeBoundScene(rest, {}));
    const Animator bound(rest);
    const auto expectInPlace = [](const Scene& s) {
        const AnimatorBindState& b = *s.animatorState();
        EXPECT_TRUE(b.restPhase.isView());
        EXPECT_TRUE(b.restArc.isView());
        EXPECT_TRUE(b.restSegment.isView());
        EXPECT_FALSE(b.restPhase.empty());
    };
    {  // mapped; a copy evaluates after the original and its map's first owner are gone
        const impl::BoundSceneFile file = impl::openBoundSceneFile(path, {});
        EXPECT_TRUE(file.mapped);
        std::optional<BoundScene> loaded = readBoundScene(path);
        expectInPlace(loaded->scene);
        expectSameFrame(bound, loaded->scene);
        const Scene copy = loaded->scene;
        loaded.reset();
        expectInPlace(copy);
        expectSameFrame(bound, copy);
    }
    {  // read into memory (what a failed map falls back to)
        impl::BoundSceneFile file = impl::openBoundSceneFile(path, {}, impl::BoundSceneAccess::Read);
        EXPECT_FALSE(file.mapped);
        const BoundScene loaded = decodeBoundScene(file.bytes, std::move(file.owner), path);
        expectInPlace(loaded.scene);
        expectSameFrame(bound, loaded.scene);
    }
    // Bytes without an owner are copied.
    const BoundScene copied = decodeBoundScene(encodeBoundScene(rest, {}), "g.knitbind");
    EXPECT_FALSE(copied.scene.animatorState()->restPhase.isView());
    expectSameFrame(bound, copied.scene);
}

// A version 5 file truncated, with an array not at its aligned offset (no padding: a version 4
// payload, or a byte lost), or with a value left in place in the map that evaluation cannot use
// is refused naming the file, through the map as from bytes.
TEST(BoundScene, aTruncatedMisalignedOrBadMappedFileIsRefusedNamingTheFile) {
    const test::TempDir dir;
    const std::string bytes = encodeBoundScene(restScene(), {});
    const FieldOffsets at(bytes);
    const auto readError = [&](const std::string& content) {
        const std::string path = dir.write("f.knitbind", content);
        try {
            readBoundScene(path);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string name = "bound scene '" + dir.file("f.knitbind") + "' ";
    std::string e = readError(bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(e.find(name + "is truncated: it holds"), std::string::npos) << e;
    // The padding before the pattern points taken out (the header's payload size and checksum
    // made to match): the reader meets the points where the zero padding belongs.
    const size_t count = at.countOf("the pattern points"), padding = at["the pattern points"] - count - 8;
    ASSERT_GT(padding, 0u);
    std::string unpadded = bytes;
    unpadded.erase(count + 8, padding);
    const uint64_t payload = unpadded.size() - 32;
    std::memcpy(unpadded.data() + 16, &payload, 8);
    e = readError(resealed(unpadded));
    EXPECT_NE(e.find(name + "is damaged: the padding before the pattern points is not zero"), std::string::npos) << e;
    // Values in the arrays used in place are checked on loading too.
    e = readError(withValue(bytes, at["the rest arc lengths"] + 8, std::numeric_limits<double>::quiet_NaN()));
    EXPECT_NE(e.find(name + "is inconsistent: its Animator state: a rest arc length, twist phase, pitch or length is "
                            "not finite"),
              std::string::npos)
        << e;
    e = readError(withValue(bytes, at["the rest segment lengths"], -1.0));
    EXPECT_NE(e.find(name + "is inconsistent: its Animator state: a rest segment length"), std::string::npos) << e;
}

TEST(BoundScene, aSceneMadeFromPartsIsNotSaved) {
    SceneParts parts;
    parts.yarnRadius = 0.001;
    EXPECT_THROW(encodeBoundScene(Scene::fromParts(parts), {}), Error);
}

}  // namespace
}  // namespace knit
