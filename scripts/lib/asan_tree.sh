# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: configures the one instrumented build folder
# both use (AddressSanitizer + UndefinedBehaviorSanitizer; with clang also the libFuzzer targets),
# so the library is compiled once for the sanitizer suite and the fuzzers.
#
# configure_asan_tree BUILD_DIR CXX RENDER_CHECK(ON|OFF)
#   clang, -O1 and line tables only, as the sanitizers' own documentation suggests for tests:
#   reports keep file:line stack traces, and the instrumented build needs far less compiler time
#   than gcc at -O2 -g (the hard-case catalogue test: 9.8 s of CPU instead of 37 s; gcc -O1 -g1:
#   18 s). A build folder configured with another compiler is started afresh. The Python module is
#   not built: an ASan-instrumented extension cannot load into Debian's uninstrumented python3
#   without preloading the runtime (the Release suite tests it).
configure_asan_tree() {
  local build=$1 cxx=$2 render=$3 fuzzers=OFF
  case "$cxx" in *clang*) fuzzers=ON ;; esac
  if [ -f "$build/CMakeCache.txt" ] && ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=.*$cxx\$" "$build/CMakeCache.txt"; then
    rm -rf "$build"
  fi
  cmake -S "$ASAN_TREE_ROOT" -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
    -DKNIT_SANITIZE=ON -DKNIT_BUILD_FUZZERS="$fuzzers" -DKNIT_BUILD_BENCH=OFF \
    -DKNIT_BUILD_RENDER_CHECK="$render" -DKNIT_BUILD_PYTHON=OFF "${ccache_launcher[@]}"
}
ASAN_TREE_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
source "$ASAN_TREE_ROOT/scripts/lib/ccache.sh"
# The instrumented objects carry line tables (debug info), for which ccache also hashes the
# folder it compiles in, so a clone at another path (a CI checkout) missed every object and rebuilt
# the tree (14 min 48 s in the CI run of 2026-11-27 against 36 s at the same path). Not hashing the
# folder lets any clone hit; the cost: a sanitizer report's paths may start with the folder of
# the clone that compiled the object first (the rest of the path is the file in this checkout).
export CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-true}
