// The export flags of `knit build` (apps/knit/export_flags.cpp): words to enums, ranges, and
// the flags that need or exclude each other.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "export_flags.hpp"

namespace knit::cli {
namespace {

ExportOptions parse(const std::vector<std::string>& args) {
    CLI::App app("test");
    ExportOptions o;
    addExportFlags(app, o);
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    app.parse(reversed);
    return o;
}

TEST(ExportFlags, parsesFormatOptions) {
    const ExportOptions o = parse({"--export", "tubes", "--sides", "12", "--draco", "--draco-bits", "16",
                                   "--yarn-colors", "--chunk-vertices", "5000", "--no-caps"});
    EXPECT_EQ(o.what, ExportWhat::Tubes);
    EXPECT_EQ(o.sides, 12);
    EXPECT_TRUE(o.draco);
    EXPECT_EQ(o.dracoBits, 16);
    EXPECT_TRUE(o.yarnColors);
    EXPECT_EQ(o.chunkVertices, 5000u);
    EXPECT_FALSE(o.caps);
    EXPECT_EQ(parse({"--export", "YARNS"}).what, ExportWhat::Yarns);
    EXPECT_TRUE(parse({"--export", "tubes", "--quantize"}).quantize);
}

TEST(ExportFlags, tubesOfTakesAnyCaseAndDefaultsToAuto) {
    EXPECT_EQ(parse({}).tubesOf, TubeSource::Auto);
    EXPECT_EQ(parse({"--tubes-of", "Yarns"}).tubesOf, TubeSource::Yarns);
    EXPECT_EQ(parse({"--tubes-of", "plies"}).tubesOf, TubeSource::Plies);
    EXPECT_EQ(parse({}).what, ExportWhat::Plies);
}

TEST(ExportFlags, rejectsBadValuesAndConflicts) {
    EXPECT_THROW(parse({"--export", "meshes"}), CLI::ValidationError);
    EXPECT_THROW(parse({"--sides", "2"}), CLI::ValidationError);
    EXPECT_THROW(parse({"--draco-bits", "12"}), CLI::RequiresError);  // needs --draco
    EXPECT_THROW(parse({"--draco", "--draco-bits", "31"}), CLI::ValidationError);
    EXPECT_THROW(parse({"--draco", "--quantize"}), CLI::ExcludesError);
}

}  // namespace
}  // namespace knit::cli
