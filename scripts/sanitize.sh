#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the test suite (-DKNIT_SANITIZE=ON) in
# build-asan (the folder scripts/fuzz.sh builds its fuzzers in, configured by scripts/lib/asan_tree.sh),
# then ctest over the core, mesh, plies, cli, export, hard and serve tests. Any sanitizer
# report fails the test that triggered it (UBSan is built with -fno-sanitize-recover).
#
# Usage: scripts/sanitize.sh [extra ctest arguments]
# Environment: KNIT_ASAN_BUILD_DIR (default build-asan), KNIT_JOBS (default 2),
#   KNIT_SANITIZE_STEP=build (configure and build only) or test (run the built suite only;
#   .ci/run times the two apart), default both,
#   KNIT_SANITIZE_CXX (the compiler, default clang++: it builds the instrumented code in about half
#   gcc's time),
#   KNIT_SANITIZE_RENDER=ON to also build and run the render tests (slow under ASan: chi-square
#   tests draw millions of samples), KNIT_BUILD_RENDER_CHECK=OFF to skip render_check entirely
#   (then the hard tests' ray cases are not built).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/lib/asan_tree.sh"
build=${KNIT_ASAN_BUILD_DIR:-"$root/build-asan"}
jobs=${KNIT_JOBS:-2}
render_check=${KNIT_BUILD_RENDER_CHECK:-ON}
step=${KNIT_SANITIZE_STEP:-all}
cxx=${KNIT_SANITIZE_CXX:-clang++}
case "$step" in build|test|all) ;; *) echo "sanitize: KNIT_SANITIZE_STEP must be build, test or all, got '$step'" >&2; exit 2 ;; esac

build_suite() {
  bash "$root/scripts/setup.sh" || echo "sanitize: warning: scripts/setup.sh failed; continuing with the installed packages"
  configure_asan_tree "$build" "$cxx" "$render_check"
  local targets=(knit_core_tests knit_mesh_tests knit_plies_tests knit_cli_tests knit_export_tests knit_hard_tests
                 knit_serve_tests)
  [ "${KNIT_SANITIZE_RENDER:-OFF}" = ON ] && [ "$render_check" = ON ] && targets+=(knit_render_tests)
  cmake --build "$build" -j"$jobs" --target "${targets[@]}"
  # The export tests run the Khronos glTF-Validator (npm) from this build folder.
  [ -d "$build/node/node_modules/gltf-validator" ] || cmake --build "$build" --target gltf_validator
  # `knit serve` (ServeCommand.ctrlCStopsItCleanly) starts only with three.js (npm) to serve.
  [ -d "$build/node/node_modules/three" ] || cmake --build "$build" --target three_js
}
[ "$step" = test ] || build_suite
[ "$step" = build ] && exit 0

# Leaks are errors; the watchdog of the hard cases allows for the slower instrumented code.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export KNIT_HARD_TIMEOUT=${KNIT_HARD_TIMEOUT:-1200}
cd "$build"
# Test binaries that were not built register as <name>_NOT_BUILT: leave them out; so is the
# export test that measures the process's peak memory (ASan's shadow memory and quarantine
# change what it measures), and the tests that drive outside programs over a whole installed or
# Release build (python, the Blender add-on, three.js / Blender clients, the installed package,
# the page of knit serve in Chromium): scripts/test.sh runs those.
# Also left to the Release suite: the tests that relax whole built-in charts or intarsia motifs, or make strain
# tables. The relaxation runs ~70x slower instrumented (Relax.everyBuiltinChartTilesSeamlessly: 8.4 s
# in Release, over its 600 s timeout here on a loaded machine); its code is run instrumented by the
# smaller cells of Relax.plainBuiltins*, Relax.isDeterministic, Intarsia.*, StrainTable.* and the rest.
heavy=(Relax.everyBuiltinChartTilesSeamlessly Relax.basketweaveAndCableRelaxApartAndKeepTheirCrossings
       Relax.hessianPreconditionerSettlesSlowCellsWellWithinTheCap Relax.ribsRelaxApartAndKeepTheirCrossings
       ChartConstructsRelaxed.roundTwoBuiltinsAfterRelaxation
       ChartConstructsRelaxed.loopsHeldThreeRowsKeepTheYarnsApart
       ChartCommand.longFloatsAreWarnedAboutAndReported ChartCommand.intarsiaMotifYarnsKeepTheirColourThroughTheExport
       Intarsia.aMotifRelaxesWithItsBoundaryClosed Cli.everySharedPatternBuildsOnAPlane
       Intarsia.aDiagonalsCarriedTurnsHookThroughTheNeighboursAndTheBoundaryStaysClosed
       DeformChoice.autoIsStrainWhereTheTableIsQuickOrCachedElseNoneWithAnEstimate
       DeformChoice.aTableIsTheSameBytesWithAnyThreadCountAndFromTheCache
       StrainCli.defaultDeformMakesCachesAndReadsThePatternsTable
       StrainCli.defaultDeformIsNoneWhereMakingTheTableIsSlow)
heavy_regex=$(IFS='|'; echo "${heavy[*]}" | sed 's/\./\\./g')
ctest --output-on-failure -j"$jobs" \
  -E "_NOT_BUILT|Streaming.peakMemory|^python_tests$|^blender_addon(_deform)?$|^consumer_package$|^clients_|^serve_page$|^($heavy_regex)$" "$@"
