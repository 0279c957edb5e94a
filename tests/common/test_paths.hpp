// Where the tests find the checkout, the build folder, the shared data (../shared) and the built
// `knit`. The paths are written at configure time into one generated source in the build folder
// (test_paths.cpp, library knit_test_paths), so no test source embeds a path of this machine: ccache
// (scripts/lib/ccache.sh) reuses the test objects in a clone at another path, as CI's is.
#pragma once

namespace knit::test {

const char* sourceDir();  // the checkout (CMake's PROJECT_SOURCE_DIR)
const char* binaryDir();  // the build folder (PROJECT_BINARY_DIR)
const char* sharedDir();  // the shared data folder (KNIT_SHARED_DIR, ../shared by default)
const char* knitCli();    // the built `knit` command line; empty when apps are not built

}  // namespace knit::test
