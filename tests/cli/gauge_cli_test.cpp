// --gauge on `knit build`: the report gives back the gauge achieved; --gauge with --repeats fails.
#include <gtest/gtest.h>

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "common/run_knit.hpp"
#include "test_util.hpp"

namespace knit {
namespace {

// A 2 x 2 chart records 2 stitches and 2 rows per period, so 4 x 6 per 10 cm on the 0.5 m plane
// are 10 x 15 periods and the report reads back 4 and 6.
TEST(GaugeCli, buildReportsTheGaugeAchievedForAChart) {
    test::TempDir dir;
    dir.write("seed.chart", "k p\np k\n");
    ::setenv("KNIT_CACHE_DIR", dir.file("cache").c_str(), 1);  // the child inherits it
    // --deform none: the placement alone (the default would make the chart's strain table first).
    const test::CliRun r = test::runKnit("build --pattern seed.chart --mesh plane --gauge 4x6/10cm --mesh-res 4 -q -o "
                                         "y.obj --export yarns --report r.json --deform none",
                                         dir.path());
    ::unsetenv("KNIT_CACHE_DIR");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(test::readText(dir.file("r.json")));
    const nlohmann::json& placement = j["placement"];
    EXPECT_NEAR(placement["repeats"][0].get<double>(), 10.0, 1e-9);
    EXPECT_NEAR(placement["repeats"][1].get<double>(), 15.0, 1e-9);
    EXPECT_NEAR(placement["gauge"]["stitches_per_10cm"].get<double>(), 4.0, 1e-9);
    EXPECT_NEAR(placement["gauge"]["rows_per_10cm"].get<double>(), 6.0, 1e-9);
    EXPECT_EQ(placement["gauge"]["stitches_per_period"].get<int>(), 2);
    EXPECT_EQ(placement["gauge"]["rows_per_period"].get<int>(), 2);
}

TEST(GaugeCli, gaugeWithRepeatsOrMalformedFailsNamingTheFlags) {
    test::TempDir dir;
    const test::CliRun both =
        test::runKnit("build -q --mesh plane --repeats 4 4 --gauge 22x30/10cm -o y.obj --export yarns", dir.path());
    EXPECT_EQ(both.exitCode, 1);
    EXPECT_NE(both.output.find("--gauge and --repeats are mutually exclusive"), std::string::npos) << both.output;
    const test::CliRun bad =
        test::runKnit("build -q --mesh plane --gauge 22x30/10ft -o y.obj --export yarns", dir.path());
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.output.find("the gauge (--gauge) '22x30/10ft': unknown length unit 'ft'"), std::string::npos)
        << bad.output;
}

}  // namespace
}  // namespace knit
