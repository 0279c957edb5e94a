// Runs every case of the hard-case catalogue (catalogue.hpp) through the whole pipeline and
// checks the invariants (hard_cases.hpp) plus the case's own documented behaviour.
#include <gtest/gtest.h>

#include "catalogue.hpp"

namespace knit::hard {
namespace {

class Catalogue : public ::testing::TestWithParam<std::string> {};

TEST_P(Catalogue, pipelineKeepsInvariants) {
    const HardCase hc = catalogueCase(GetParam());
    std::optional<Scene> scene;
    ASSERT_NO_THROW(scene = runCase(hc)) << hc.name;
    if (!scene) return;  // an expected error, checked by runCase
    checkInvariants(hc.name, *scene, hc.options, hc.expect);
    if (hc.check) {
        SCOPED_TRACE("hard case " + hc.name);
        hc.check(*scene);
    }
}

INSTANTIATE_TEST_SUITE_P(Hard, Catalogue, ::testing::ValuesIn(catalogueNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace knit::hard
