// mesh_test_util.hpp — the mesh tests' names (knit_test::) for the shared helpers of
// test_util.hpp: the per-test temporary folder and errorOf.
#pragma once
#include "test_util.hpp"

namespace knit_test {

using knit::test::errorOf;
using knit::test::TempDir;

}  // namespace knit_test
