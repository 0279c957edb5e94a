#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer) in
# build-asan, the sanitizer suite's folder (scripts/lib/asan_tree.sh configures it for both, so the
# instrumented library is compiled once), and runs each one for a bounded time, starting from the regression corpus in
# tests/fuzz_corpus/<parser>/. A crash, sanitizer report, leak, timeout or out-of-memory stops
# that target; its input is saved as tests/fuzz_corpus/<parser>/crash-<sha1> (or timeout-/oom-/
# leak-): fix the parser and commit the file, the corpus replay test (tests/hard) keeps it fixed.
# New interesting inputs go to build-asan/corpus/<parser>/ (not committed).
#
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET ...]
#   SECONDS_PER_TARGET  default 60 (or $KNIT_FUZZ_SECONDS)
#   TARGET              pyp curves_json obj ply off gltf gltf_animation chart strain_table bound_scene
#                       serve_request material (default: all)
# Environment: KNIT_FUZZ_BUILD_DIR (default KNIT_ASAN_BUILD_DIR, else build-asan), KNIT_JOBS (build jobs, and fuzzers run
#   side by side, default 2: each fuzzer is one process on one core, so two cores fuzz two targets
#   at once for the same time each), KNIT_FUZZ_SEED (libFuzzer -seed, default 1),
#   KNIT_FUZZ_STEP=build (configure and build only) or run (run the built targets only), default both,
#   KNIT_FUZZ_RENDER_CHECK=OFF to skip the material parser (and the Embree build it needs; the
#   default is KNIT_BUILD_RENDER_CHECK's, as scripts/sanitize.sh, so the two share one configuration).
# Exits non-zero when any target failed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/lib/asan_tree.sh"
seconds=${1:-${KNIT_FUZZ_SECONDS:-60}}
[ $# -gt 0 ] && shift
build=${KNIT_FUZZ_BUILD_DIR:-${KNIT_ASAN_BUILD_DIR:-"$root/build-asan"}}
jobs=${KNIT_JOBS:-2}
render=${KNIT_FUZZ_RENDER_CHECK:-${KNIT_BUILD_RENDER_CHECK:-ON}}
# A fixed seed makes a run repeatable: the same corpus and seed explore the same inputs first.
seed=${KNIT_FUZZ_SEED:-1}
step=${KNIT_FUZZ_STEP:-all}
case "$step" in build|run|all) ;; *) echo "fuzz: KNIT_FUZZ_STEP must be build, run or all, got '$step'" >&2; exit 2 ;; esac
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(pyp curves_json obj ply off gltf gltf_animation chart strain_table bound_scene serve_request)
  [ "$render" = ON ] && targets+=(material)
fi

# clang + libclang-rt-14-dev (libFuzzer) are in setup.sh's package list; a failure there for an
# unrelated package does not stop the fuzzing when clang is present (the build says what is missing).
build_targets() {
  bash "$root/scripts/setup.sh" || echo "fuzz: warning: scripts/setup.sh failed; continuing with the installed packages"
  mkdir -p "$(dirname "$build")"
  configure_asan_tree "$build" clang++ "$render" > "$build.configure.log" 2>&1 ||
    { cat "$build.configure.log"; exit 1; }
  cmake --build "$build" -j"$jobs" --target "${targets[@]/%/_fuzzer}"
}

# Runs one target for $seconds; its log in $build/$t.log, its verdict in $build/$t.status.
fuzz_one() {
  local t=$1 corpus="$root/tests/fuzz_corpus/$1" work="$build/corpus/$1" dict=()
  mkdir -p "$work" "$corpus"
  [ -f "$root/fuzz/dict/$t.dict" ] && dict=(-dict="$root/fuzz/dict/$t.dict")
  if "$build/fuzz/${t}_fuzzer" "$work" "$corpus" "${dict[@]}" -seed="$seed" -max_total_time="$seconds" -timeout=10 \
       -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$corpus/" -print_final_stats=1 \
       > "$build/$t.log" 2>&1; then
    echo ok > "$build/$t.status"
  else
    echo failed > "$build/$t.status"
  fi
}

run_targets() {
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  local t running=0 failed=()
  echo "== fuzz ${targets[*]}: ${seconds}s each, $jobs at a time"
  for t in "${targets[@]}"; do
    rm -f "$build/$t.status"
    fuzz_one "$t" &
    running=$((running + 1))
    if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
  done
  wait
  # Reported in the order of the targets, whatever order they finished in.
  for t in "${targets[@]}"; do
    if [ "$(cat "$build/$t.status" 2>/dev/null)" = ok ]; then
      echo "== $t"
      grep -aE "^(stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb)" "$build/$t.log" || true
    else
      echo "!! $t failed (log: $build/$t.log); reproducer saved in $root/tests/fuzz_corpus/$t/:"
      grep -aE "^(==[0-9]+==ERROR|SUMMARY|.*runtime error|artifact_prefix|Test unit written)" "$build/$t.log" | head -5 || true
      failed+=("$t")
    fi
  done
  if [ ${#failed[@]} -gt 0 ]; then
    echo "fuzz: FAILED: ${failed[*]}"
    exit 1
  fi
  echo "fuzz: all ${#targets[@]} targets ran ${seconds}s without a crash"
}

[ "$step" = run ] || build_targets
[ "$step" = build ] || run_targets
