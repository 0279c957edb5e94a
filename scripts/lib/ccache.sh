# Sourced by the build scripts: build reuse between runs through ccache (scripts/setup.sh installs
# it). A second build of the same sources with the same flags, in this checkout or in another
# clone at the same path (CI's), takes the objects from the cache instead of compiling them again;
# paths inside the checkout are hashed relative to it (CCACHE_BASEDIR), so a clone elsewhere
# still hits (the tests read their paths from one generated source, tests/common/test_paths.hpp).
# KNIT_CCACHE=OFF builds without it. Sets ccache_launcher: the CMake arguments to pass.
ccache_launcher=()
if [ "${KNIT_CCACHE:-ON}" != OFF ] && command -v ccache >/dev/null 2>&1; then
  ccache_launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  CCACHE_BASEDIR=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
  export CCACHE_BASEDIR
  # The Release, sanitizer and lint folders together; ccache evicts the oldest objects beyond it.
  export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-8G}
else
  # A folder configured with the launcher before is configured without it again.
  ccache_launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER= -DCMAKE_C_COMPILER_LAUNCHER=)
fi
