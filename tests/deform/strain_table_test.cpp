// Strain tables: the strain convention, tables made by relaxing the cell on deformed lattices
// (zero strain, stretch, compression and shear), their files (own format and MADYPG's folder)
// and the refusals of bad tables.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/global_control.h>

#include "test_util.hpp"
#include "knit/chart.hpp"
#include "knit/chart_topology.hpp"
#include "knit/error.hpp"
#include "knit/generator.hpp"
#include "knit/strain.hpp"
#include "chart/relax_lattice.hpp"
#include "deform/strain_lookup.hpp"

namespace knit {
namespace {

// A table of one sample per axis (or a few) for the project's stockinette.
StrainTable tableAt(const Strain& s, StrainTableStats* stats = nullptr) {
    StrainTableOptions o;
    o.samples = {1, 1, 1};
    o.sxRange = {s.sx, s.sx};
    o.saRange = {s.sa, s.sa};
    o.syRange = {s.sy, s.sy};
    return makeStrainTable(generateStockinette(), o, stats);
}

// The cell's vertices at sample `s` of a table: X + D, in pattern space.
std::vector<glm::dvec3> displaced(const Pattern& p, const StrainTable& t, size_t s = 0) {
    std::vector<glm::dvec3> x = p.points;
    for (size_t v = 0; v < x.size(); ++v) {
        const float* row = &t.data[4 * (s + t.samples() * v)];
        x[v] += glm::dvec3(row[0], row[1], row[2]);
    }
    return x;
}

// The cell's extent across the courses (y), deformed.
double extentAcross(const std::vector<glm::dvec3>& x, const glm::dmat2& F) {
    double lo = 1e9, hi = -1e9;
    for (const glm::dvec3& p : x) {
        const double y = (F * glm::dvec2(p.x, p.y)).y;
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    }
    return hi - lo;
}

TEST(StrainTable, latticeMapHasTheStrainItIsMadeFor) {
    for (const Strain s : {Strain{0.3, -0.5, -0.1}, Strain{-0.2, 0.7, 1.0}, Strain{0, 0, 0}}) {
        const glm::dmat2 F = latticeMap(s);
        const Strain back = strainOf(glm::transpose(F) * F);
        EXPECT_NEAR(back.sx, s.sx, 1e-12);
        EXPECT_NEAR(back.sa, s.sa, 1e-12);
        EXPECT_NEAR(back.sy, s.sy, 1e-12);
    }
}

TEST(StrainTable, zeroStrainSampleRecordsNoDisplacement) {
    StrainTableStats stats;
    const StrainTable t = tableAt({0, 0, 0}, &stats);
    ASSERT_EQ(t.vertexCount, generateStockinette().points.size());
    for (float v : t.data) EXPECT_EQ(v, 0.0F);
    EXPECT_GE(stats.restMinDistance, 1.9);  // the relaxed rest cell: yarns in contact, not through each other
}

// Stretch along the courses: the yarn slides and the loops straighten, so the cell's extent
// across the courses shrinks and the yarn lengthens far less than the surface mapping makes it.
TEST(StrainTable, stretchAlongCoursesShortensLoopsAcrossThem) {
    const Pattern p = generateStockinette();
    StrainTableStats stats;
    const Strain s{0.5, 0, 0};
    const StrainTable t = tableAt(s, &stats);
    const glm::dmat2 F = latticeMap(s);
    const std::vector<glm::dvec3> x = displaced(p, t);
    EXPECT_LT(extentAcross(x, F), extentAcross(p.points, F) - 0.2 * p.radius);
    const double rest = impl::cellYarnLength(p, p.points, glm::dmat2(1.0));
    const double mapped = impl::cellYarnLength(p, p.points, F) / rest, relaxed = impl::cellYarnLength(p, x, F) / rest;
    EXPECT_GT(mapped, 1.15);
    EXPECT_LT(relaxed - 1, 0.6 * (mapped - 1));
    EXPECT_GE(stats.minDistance, 1.0);
}

// Compression and shear: the yarns keep their distance (the mapping alone presses them together).
TEST(StrainTable, compressionAndShearKeepYarnsApart) {
    StrainTableStats stats;
    tableAt({-0.2, 0.7, -0.2}, &stats);
    EXPECT_GE(stats.minDistance, 1.5);
}

TEST(StrainTable, samplesWarmStartFromZeroAndMatchSingleRuns) {
    // A 3 x 1 x 1 table: its sx = 0 sample is zero and its others are displaced.
    StrainTableOptions o;
    o.samples = {3, 1, 1};
    o.sxRange = {-0.1, 0.1};
    o.saRange = {0, 0};
    o.syRange = {0, 0};
    const StrainTable t = makeStrainTable(generateStockinette(), o);
    ASSERT_EQ(t.axes[0].size(), 3U);
    double moved = 0;
    for (size_t v = 0; v < t.vertexCount; ++v) {
        for (int c = 0; c < 4; ++c) EXPECT_EQ(t.data[4 * (1 + 3 * v) + size_t(c)], 0.0F);
        moved = std::max(moved, double(std::abs(t.data[4 * (0 + 3 * v)])) + std::abs(t.data[4 * (2 + 3 * v)]));
    }
    EXPECT_GT(moved, 1e-5);
}

// Contact pairs surely apart (their distance when the pair list was built, less twice the
// largest vertex move since, at least the contact distance) are not measured: the relaxation is
// the same to the bit, on the dense Newton path (the stockinette) and the sparse one (the
// basketweave's 384-vertex cell), for far fewer closest-point measurements.
TEST(StrainTable, skippingContactPairsSurelyApartChangesNothingButTheWork) {
    const Pattern stockinette = generateStockinette(),
                  basketweave = chartToCell(builtinChart("chart:basketweave")).pattern;
    for (const Pattern* p : {&stockinette, &basketweave}) {
        impl::LatticeRelaxOptions skip;
        skip.maxIterations = 24;
        impl::LatticeRelaxOptions every = skip;
        every.skipPairsSurelyApart = false;
        const glm::dmat2 F = latticeMap({0.2, 0.3, -0.15});
        const impl::LatticeRelaxResult a = impl::LatticeCell(*p, skip).relax(F, {}),
                                       b = impl::LatticeCell(*p, every).relax(F, {});
        ASSERT_EQ(a.points.size(), b.points.size());
        for (size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << p->name << " vertex " << i;
        EXPECT_EQ(a.iterations, b.iterations);
        EXPECT_EQ(a.energy, b.energy);
        EXPECT_EQ(a.minDistance, b.minDistance);
        std::printf("%s: %zu of %zu pair measurements\n", p->name.c_str(), a.pairsMeasured, b.pairsMeasured);
        EXPECT_LT(double(a.pairsMeasured), 0.8 * double(b.pairsMeasured)) << p->name;
    }
}

// A cell of 65-200 vertices takes the sparse path with conjugate gradients solved far enough
// to follow the dense Cholesky steps: seed's 96-vertex cell, compressed across the courses and
// sheared (where the looser solve of larger cells took other branches, up to 6 r away), stays
// within a thousandth of a radius of the dense path's relaxation, for a fraction of its CPU.
TEST(StrainTable, midSizeCellsSparseStepsFollowTheDenseOnes) {
    const Pattern seed = chartToCell(builtinChart("chart:seed")).pattern;
    ASSERT_GT(seed.points.size(), 64u);
    ASSERT_LE(seed.points.size(), 200u);
    impl::LatticeRelaxOptions bySize;
    bySize.maxIterations = 40;
    impl::LatticeRelaxOptions dense = bySize;
    dense.newton = impl::LatticeRelaxOptions::Newton::Dense;
    const glm::dmat2 F = latticeMap({-0.2, -0.175, 0.1});
    const impl::LatticeRelaxResult a = impl::LatticeCell(seed, bySize).relax(F, {}),
                                   b = impl::LatticeCell(seed, dense).relax(F, {});
    double worst = 0;
    for (size_t i = 0; i < a.points.size(); ++i) worst = std::max(worst, glm::length(a.points[i] - b.points[i]));
    std::printf("seed: largest difference %.2e r, %d and %d iterations\n", worst / seed.radius, a.iterations,
                b.iterations);
    EXPECT_LT(worst, 1e-3 * seed.radius);
}

// Each sample starts only from samples already relaxed, whatever the threads do: one thread and
// all of them make the same table to the bit.
TEST(StrainTable, oneThreadAndAllMakeTheSameTable) {
    StrainTableOptions o;
    o.samples = {3, 3, 2};
    o.sxRange = {-0.1, 0.3};
    o.saRange = {-0.3, 0.3};
    o.syRange = {0.0, 0.2};
    o.maxIterations = 60;
    size_t calls = 0;
    o.progress = [&calls](size_t, size_t) { ++calls; };
    const StrainTable all = makeStrainTable(generateStockinette(), o);
    EXPECT_EQ(calls, 18u);
    StrainTable one;
    {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = makeStrainTable(generateStockinette(), o);
    }
    ASSERT_EQ(one.data.size(), all.data.size());
    EXPECT_EQ(std::memcmp(one.data.data(), all.data.data(), all.data.size() * sizeof(float)), 0);
}

// A table's work is counted in lattice stages (each changes the map by at most a tenth of its
// smallest singular value): the counts below were worked out independently from that rule for
// the default ranges. A coarse grid takes larger steps, in more stages per sample, so the
// estimate follows the stages, not the samples (it used to scale by the samples: 27 / 729 of the
// default table's time for 3 x 3 x 3, which took 13 % of its CPU time).
TEST(StrainTable, estimateCountsLatticeStagesNotSamples) {
    StrainTableOptions o;
    EXPECT_EQ(strainTableStages(o), 1791U);
    o.samples = {5, 5, 5};
    EXPECT_EQ(strainTableStages(o), 633U);
    o.samples = {3, 3, 3};
    EXPECT_EQ(strainTableStages(o), 320U);
    // The count is the stages a table relaxes (a small one, a few iterations per stage).
    StrainTableOptions small;
    small.samples = {2, 3, 2};
    small.maxIterations = 3;
    StrainTableStats stats;
    makeStrainTable(generateStockinette(), small, &stats);
    EXPECT_EQ(stats.stages, strainTableStages(small));
    EXPECT_GT(stats.stages, 12U);  // more than one per sample
    // The estimate follows them (3 x 3 x 3: 18 % of the default table's stages, 3.7 % of its samples).
    const Pattern p = generateStockinette();
    const double ratio = estimateStrainTableSeconds(p, o) / estimateStrainTableSeconds(p, {});
    EXPECT_GT(ratio, 0.1);
    EXPECT_LT(ratio, 0.4);
}

// The built-in stockinette is the tables' rest cell: Crane's curve, whose yarns press 0.16 radii
// into each other, brought to rest under the tables' energy (period fixed). Relaxing it again
// moves it by no more than the solver's tolerance, so a table's zero strain is the pattern.
TEST(StrainTable, builtInStockinetteIsTheTablesRestCell) {
    StockinetteParams craneOnly;
    craneOnly.relax = false;
    const Pattern crane = generateStockinette(craneOnly), rest = generateStockinette();
    const auto largestMove = [](const Pattern& p) {
        const std::vector<glm::dvec3> again = impl::restCell(p);
        double m = 0;
        for (size_t i = 0; i < again.size(); ++i) m = std::max(m, glm::length(again[i] - p.points[i]));
        return m / p.radius;
    };
    EXPECT_LT(largestMove(rest), 5e-3);  // the solver's tolerance: a few thousandths of a radius
    EXPECT_GT(largestMove(crane), 0.05);
    const auto closest = [](const Pattern& p) {
        impl::LatticeRelaxOptions o;
        o.maxIterations = 0;  // measured as it is
        return impl::LatticeCell(p, o).relax(glm::dmat2(1.0), {}).minDistance;
    };
    EXPECT_LT(closest(crane), 1.9);
    EXPECT_GE(closest(rest), 1.98);
    EXPECT_EQ(crane.px, rest.px);
    EXPECT_EQ(crane.py, rest.py);
}

TEST(StrainTable, refusesBadOptionsNamingThem) {
    StrainTableOptions o;
    o.samples = {0, 9, 9};
    EXPECT_THROW(makeStrainTable(generateStockinette(), o), Error);
    o = {};
    o.saRange = {-1.0, 0.5};
    EXPECT_NE(test::errorOf([&] { makeStrainTable(generateStockinette(), o); }).find("sa range"), std::string::npos);
}

// ---- files ----------------------------------------------------------------------------------

StrainTable syntheticTable(size_t vertices) {
    StrainTable t;
    t.axes = {std::vector<double>{-0.2, 0.4, 1.0}, std::vector<double>{-0.5, 0.5},
              std::vector<double>{-0.2, 0.2, 0.6, 1.0}};
    t.vertexCount = vertices;
    t.pattern = "stockinette";
    t.px = 0.0078539816339744835;
    t.py = 0.005625;
    t.radius = 0.001;
    t.data.resize(4 * vertices * t.samples());
    for (size_t i = 0; i < t.data.size(); ++i) t.data[i] = float(i % 1000) * 1e-6F - 3e-4F;
    return t;
}

TEST(StrainTable, writtenTableReadsBackExactly) {
    const test::TempDir dir;
    const StrainTable t = syntheticTable(24);
    const std::string path = dir.file("t.npy");
    writeStrainTable(t, path);
    EXPECT_TRUE(std::filesystem::exists(dir.file("t.axes.txt")));
    const std::string bytes = test::readText(path);
    // NumPy format 1.0: magic, version, header length, dict; data at a multiple of 64 bytes.
    ASSERT_EQ(bytes.compare(0, 6, "\x93NUMPY"), 0);
    const size_t headerLen = size_t(uint8_t(bytes[8])) | size_t(uint8_t(bytes[9])) << 8;
    EXPECT_EQ((10 + headerLen) % 64, 0U);
    EXPECT_NE(bytes.find("'shape': (" + std::to_string(24 * t.samples()) + ", 4)"), std::string::npos);
    const StrainTable back = loadStrainTable(path);
    EXPECT_EQ(back.axes, t.axes);
    EXPECT_EQ(back.data, t.data);
    EXPECT_EQ(back.vertexCount, 24U);
    EXPECT_EQ(back.px, t.px);
    EXPECT_EQ(back.pattern, "stockinette");
    checkStrainTable(back, generateStockinette());
}

// MADYPG's layout, written here byte by byte: axes.txt and data.npy with row
// isx + Nx isa + Nx Na isy + Nx Na Ny vertex, columns dx dy dz dtwist.
TEST(StrainTable, madypgFolderIsReadWithTheDocumentedLayout) {
    const test::TempDir dir;
    std::filesystem::create_directories(dir.path() / "sxsasy");
    const std::vector<double> sx{-0.2, 0.1, 0.4, 1.0}, sa{-0.7, 0.0, 0.7}, sy{-0.2, 0.4};
    const size_t nv = 5, nx = sx.size(), na = sa.size(), ny = sy.size();
    std::string axes = "-0.2 0.1 0.4 1.0\n-0.7 0.0 0.7\n-0.2 0.4\n";
    dir.write("sxsasy/axes.txt", axes);
    const auto value = [](size_t v, size_t ix, size_t ia, size_t iy, size_t c) {
        return float(v) + 0.1F * float(ix) + 0.01F * float(ia) + 0.001F * float(iy) + 10.0F * float(c);
    };
    std::string dict =
        "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(nv * nx * na * ny) + ", 4), }";
    dict.append(118 - dict.size(), ' ');
    dict.push_back('\n');
    std::string npy = std::string("\x93NUMPY\x01\x00", 8) + char(dict.size()) + char(0) + dict;
    for (size_t v = 0; v < nv; ++v)
        for (size_t iy = 0; iy < ny; ++iy)
            for (size_t ia = 0; ia < na; ++ia)
                for (size_t ix = 0; ix < nx; ++ix)
                    for (size_t c = 0; c < 4; ++c) {
                        const float f = value(v, ix, ia, iy, c);
                        npy.append(reinterpret_cast<const char*>(&f), 4);
                    }
    dir.write("sxsasy/data.npy", npy);
    const StrainTable t = loadStrainTable(dir.file("sxsasy"));
    EXPECT_EQ(t.vertexCount, nv);
    EXPECT_EQ(t.px, 0.0);  // no period: only the vertex count is checked
    for (size_t v = 0; v < nv; ++v)
        for (size_t iy = 0; iy < ny; ++iy)
            for (size_t ia = 0; ia < na; ++ia)
                for (size_t ix = 0; ix < nx; ++ix) {
                    bool clamped = true;
                    const glm::dvec4 d = lookupStrainTable(t, uint32_t(v), {sx[ix], sa[ia], sy[iy]}, &clamped);
                    EXPECT_FALSE(clamped);
                    for (int c = 0; c < 4; ++c) EXPECT_NEAR(d[c], value(v, ix, ia, iy, size_t(c)), 1e-5);
                }
    // Between samples: trilinear; beyond them: clamped and counted.
    bool clamped = false;
    const glm::dvec4 mid = lookupStrainTable(t, 2, {0.25, 0.35, 0.1}, &clamped);
    EXPECT_FALSE(clamped);
    EXPECT_NEAR(mid.x, 2 + 0.1 * 1.5 + 0.01 * 1.5 + 0.001 * 0.5, 1e-5);
    lookupStrainTable(t, 2, {1.0 + 1e-12, 0.7 + 1e-12, -0.2 - 1e-12}, &clamped);  // round-off at the ends
    EXPECT_FALSE(clamped);
    const glm::dvec4 far = lookupStrainTable(t, 2, {3.0, 0.0, 0.4}, &clamped);
    EXPECT_TRUE(clamped);
    EXPECT_NEAR(far.x, value(2, 3, 1, 1, 0), 1e-5);
    // A pattern with another vertex count is refused, naming the folder.
    const std::string msg = test::errorOf([&] { checkStrainTable(t, generateStockinette()); });
    EXPECT_NE(msg.find("sxsasy"), std::string::npos) << msg;
    EXPECT_NE(msg.find("5 cell vertices"), std::string::npos) << msg;
}

// The prepared lookup (the deformer's) agrees with the plain one, for even and uneven axes.
TEST(StrainTable, preparedLookupAgreesWithThePlainOne) {
    StrainTable t = syntheticTable(3);
    for (int uneven = 0; uneven < 2; ++uneven) {
        if (uneven) t.axes[0] = {-0.2, 0.1, 1.0};
        const StrainLookup prepared(t);
        uint32_t seed = 1;
        const auto rnd = [&seed](double lo, double hi) {
            seed = seed * 1664525U + 1013904223U;
            return lo + (hi - lo) * double(seed >> 8) / double(1 << 24);
        };
        for (int k = 0; k < 500; ++k) {
            const Strain s{rnd(-0.5, 1.3), rnd(-0.9, 0.9), rnd(-0.5, 1.3)};
            bool c1 = false, c2 = false;
            const glm::dvec4 a = lookupStrainTable(t, uint32_t(k % 3), s, &c1), b = prepared(uint32_t(k % 3), s, c2);
            EXPECT_EQ(c1, c2);
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(a[c], b[c], 1e-12);
        }
    }
}

TEST(StrainTable, refusesAPeriodMismatch) {
    StrainTable t = syntheticTable(24);
    t.source = "other.npy";
    t.px *= 1.5;
    const std::string msg = test::errorOf([&] { checkStrainTable(t, generateStockinette()); });
    EXPECT_NE(msg.find("other.npy"), std::string::npos) << msg;
    EXPECT_NE(msg.find("period"), std::string::npos) << msg;
}

// A line of the axes file holding only white space other than blanks (a form feed, found by the
// fuzzer) is blank: before, it counted as an axis of no samples, and the row count was divided
// by zero samples.
TEST(StrainTable, anAxesLineOfOnlyAFormFeedIsBlankNotAnAxisOfNoSamples) {
    const test::TempDir dir;
    const std::string path = dir.file("t.npy");
    writeStrainTable(syntheticTable(3), path);
    const std::string npy = test::readText(path), axes = test::readText(dir.file("t.axes.txt"));
    const StrainTable plain = parseStrainTable(npy, axes, "t.npy");
    EXPECT_EQ(parseStrainTable(npy, "\f\n" + axes + "\f\n", "t.npy").axes, plain.axes);
    std::string two = axes.substr(0, axes.find_last_not_of('\n'));  // without its last value line
    two = two.substr(0, two.rfind('\n') + 1) + "\f\n";
    const std::string msg = test::errorOf([&] { parseStrainTable(npy, two, "t.npy"); });
    EXPECT_NE(msg.find("need three"), std::string::npos) << msg;
}

// Each damaged file is refused with a message naming the file and what is wrong.
TEST(StrainTable, refusesDamagedFilesNamingThem) {
    const test::TempDir dir;
    const std::string path = dir.file("t.npy");
    writeStrainTable(syntheticTable(3), path);
    const std::string good = test::readText(path), axes = test::readText(dir.file("t.axes.txt"));
    const auto refuse = [&](const std::string& npy, const std::string& ax, const std::string& what) {
        const std::string msg = test::errorOf([&] { parseStrainTable(npy, ax, "bad.npy"); });
        EXPECT_NE(msg.find("bad.npy"), std::string::npos) << msg;
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
    };
    refuse(good.substr(0, good.size() - 4), axes, "bytes of data");  // truncated
    refuse("PK\x03\x04 not npy", axes, "magic");
    std::string f8 = good;
    f8.replace(f8.find("<f4"), 3, "<i4");
    refuse(f8, axes, "data type");
    std::string shape = good;
    shape.replace(shape.find(", 4)"), 4, ", 3)");
    refuse(shape, axes, "shape");
    std::string nan = good;
    const float q = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&nan[nan.size() - 4], &q, 4);
    refuse(nan, axes, "not finite");
    std::string fortran = good;
    fortran.replace(fortran.find("False"), 5, "True ");
    refuse(fortran, axes, "Fortran");
    refuse(good, "0 1\n0\n", "three");
    refuse(good, "0 1 1\n0\n0\n", "increase");
    refuse(good, "0 x\n0\n0\n", "'x'");
    // Rows not a multiple of the sample count.
    refuse(good, "0 1 2 3 4 5 6\n0\n0\n", "multiple");
    EXPECT_NE(test::errorOf([&] { loadStrainTable(dir.file("missing.npy")); }).find("missing.npy"), std::string::npos);
}

// A table written into a folder that does not exist fails before writing and leaves nothing.
TEST(StrainTable, failedWriteLeavesNoFile) {
    const test::TempDir dir;
    const std::string path = dir.file("no/such/folder/t.npy");
    EXPECT_THROW(writeStrainTable(syntheticTable(3), path), Error);
    EXPECT_FALSE(std::filesystem::exists(path));
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) ADD_FAILURE() << e.path();
}

}  // namespace
}  // namespace knit

namespace knit {
namespace {

// A pattern's table is made on first use and read from the cache folder afterwards; other options
// are another entry, a renamed pattern the same one, a damaged entry is made again and replaced.
TEST(StrainTable, cachedTableIsMadeOnceAndReadAfterwards) {
    const test::TempDir dir;
    const std::string cache = dir.file("cache");
    ::setenv("KNIT_CACHE_DIR", cache.c_str(), 1);
    StrainTableOptions o;
    o.samples = {2, 1, 2};
    o.sxRange = {0.0, 0.3};
    o.syRange = {0.0, 0.2};
    o.saRange = {0.0, 0.0};
    Pattern p = generateStockinette();
    int made = 0;
    const auto make = [&] {
        ++made;
        return makeStrainTable(p, o);
    };
    const CachedStrainTable first = cachedStrainTable(p, o, make);
    EXPECT_TRUE(first.made);
    EXPECT_EQ(first.path, cache + "/" + strainCacheKey(p, o));
    EXPECT_EQ(first.table->source, first.path);
    EXPECT_TRUE(std::filesystem::exists(first.path));
    EXPECT_TRUE(std::filesystem::exists(strainAxesPath(first.path)));
    p.name = "renamed";
    const CachedStrainTable second = cachedStrainTable(p, o, make);
    EXPECT_FALSE(second.made);
    EXPECT_EQ(made, 1);
    EXPECT_EQ(second.table->data, first.table->data);
    EXPECT_EQ(findCachedStrainTable(p, o).path, first.path);
    StrainTableOptions other = o;
    other.samples = {3, 1, 2};
    EXPECT_NE(strainCacheKey(p, other), strainCacheKey(p, o));
    EXPECT_EQ(findCachedStrainTable(p, other).table, nullptr);
    test::writeText(first.path, "damaged");
    const CachedStrainTable again = cachedStrainTable(p, o, make);
    EXPECT_TRUE(again.made);
    EXPECT_EQ(made, 2);
    EXPECT_EQ(loadStrainTable(first.path).data, first.table->data);
    ::unsetenv("KNIT_CACHE_DIR");
}

}  // namespace
}  // namespace knit
