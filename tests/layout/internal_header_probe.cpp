// Compiled by the Layout.* tests with another target's include paths: the public headers and
// libknit's internal folder (io + util) are what other targets may include.
#include "io/atomic_file.hpp"
#include "knit/error.hpp"
#include "util/checks.hpp"
#include "util/math.hpp"
