#!/usr/bin/env bash
# Style and static checks of the C++ code, in two steps:
#   1. format: clang-format --dry-run --Werror over every tracked .cpp/.hpp file (.clang-format at
#      the root); prints the files that differ. See a file's changes with
#      `clang-format FILE | diff FILE -`, or rewrite them all with --fix-format.
#   2. tidy: clang-tidy (.clang-tidy at the root) with every warning an error, over the sources of
#      the libraries, the CLI and the tools (libknit/src, exporters/src, render_check/src,
#      apps/knit, tools). It reads the compile database of a configure-only CMake run in
#      build-lint (nothing is compiled; tests and benchmarks are left out). Clean results are
#      cached outside the checkout (scripts/lib/tidy_cache.py: keyed on the preprocessed file with
#      its comments, its flags, .clang-tidy and the clang-tidy version, with the checkout's path
#      left out so a clone elsewhere shares it; a file with findings is always checked again), so a
#      run after a small change checks only the files it affects.
# Both steps always run; the script exits non-zero when either found something. The result
# depends on the tool versions: CI uses Debian 12's clang-format and clang-tidy 14, installed
# here through scripts/setup.sh.
#
# Usage: scripts/lint.sh [--fix-format] [--format-only | --tidy-only]
#   --fix-format   rewrite the files that differ in place (then check as usual)
#   --format-only  skip clang-tidy (seconds instead of minutes)
#   --tidy-only    skip the format check
# Environment: KNIT_LINT_BUILD_DIR (default build-lint), KNIT_JOBS (parallel clang-tidy runs,
#   default 2), KNIT_TIDY_CACHE=OFF (no cache), KNIT_TIDY_CACHE_DIR (default
#   ${XDG_CACHE_HOME:-~/.cache}/knit-clang-tidy).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${KNIT_LINT_BUILD_DIR:-"$root/build-lint"}
jobs=${KNIT_JOBS:-2}
fix_format=0 run_format=1 run_tidy=1
for arg in "$@"; do
  case "$arg" in
    --fix-format) fix_format=1 ;;
    --format-only) run_tidy=0 ;;
    --tidy-only) run_format=0 ;;
    *) echo "usage: scripts/lint.sh [--fix-format] [--format-only | --tidy-only]" >&2; exit 2 ;;
  esac
done

bash "$root/scripts/setup.sh" || echo "lint: warning: scripts/setup.sh failed; continuing with the installed packages"
cd "$root"
failed=()

# 1. Format.
if [ "$run_format" = 1 ]; then
  mapfile -t sources < <(git ls-files '*.cpp' '*.hpp')
  [ "$fix_format" = 1 ] && clang-format -i "${sources[@]}"
  echo "== clang-format ($(clang-format --version | grep -oE '[0-9]+\.[0-9.]+' | head -1)): ${#sources[@]} files"
  mapfile -t unformatted < <(clang-format --dry-run --Werror "${sources[@]}" 2>&1 |
                               grep -oE '^[^ :]+\.[ch]pp:[0-9]+:[0-9]+: error' | cut -d: -f1 | sort -u)
  if [ ${#unformatted[@]} -gt 0 ]; then
    printf '  not formatted: %s\n' "${unformatted[@]}"
    echo "  ${#unformatted[@]} files differ from .clang-format (scripts/lint.sh --fix-format rewrites them)"
    failed+=(format)
  fi
fi

# 2. Tidy.
if [ "$run_tidy" = 1 ]; then
  cmake -S "$root" -B "$build" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DCMAKE_BUILD_TYPE=Release \
    -DKNIT_BUILD_TESTS=OFF -DKNIT_BUILD_BENCH=OFF -DKNIT_BUILD_TOOLS=ON > "$build.configure.log" 2>&1 ||
    { cat "$build.configure.log"; exit 1; }
  mapfile -t units < <(git ls-files 'libknit/src/*.cpp' 'exporters/src/*.cpp' 'render_check/src/*.cpp' \
                                    'apps/knit/*.cpp' 'apps/serve/src/*.cpp' 'tools/*.cpp')
  echo "== clang-tidy ($(clang-tidy --version | grep -oE '[0-9]+\.[0-9.]+' | head -1)): ${#units[@]} files, $jobs at a time"
  logs=$(mktemp -d)
  trap 'rm -rf "$logs"' EXIT
  # One log per file clang-tidy fails on, printed once all have run. Files found clean before with
  # the same preprocessed source, flags, .clang-tidy and clang-tidy are not checked again
  # (scripts/lib/tidy_cache.py; KNIT_TIDY_CACHE=OFF checks every file).
  python3 "$root/scripts/lib/tidy_cache.py" --build "$build" --logs "$logs" --root "$root" --jobs "$jobs" "${units[@]}" ||
    failed+=(tidy-cache)
  mapfile -t tidy_logs < <(find "$logs" -name '*.log' | sort)
  if [ ${#tidy_logs[@]} -gt 0 ]; then
    grep -hv 'warnings\? generated\.$' "${tidy_logs[@]}" || true
    # A finding in a header shows up once per file that includes it: the summary lists it once.
    echo "  clang-tidy failed on ${#tidy_logs[@]} of ${#units[@]} files; distinct findings:"
    grep -hE '^[^ ]+:[0-9]+:[0-9]+: error: ' "${tidy_logs[@]}" | sed "s|^$root/||; s/^/    /" | sort -u || true
    failed+=(tidy)
  fi
fi

if [ ${#failed[@]} -gt 0 ]; then
  echo "lint: FAILED: ${failed[*]}"
  exit 1
fi
echo "lint: clean"
