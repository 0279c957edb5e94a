#!/usr/bin/env bash
# scripts/lib/tidy_cache.py never hides a finding: on a two-file project with its own .clang-tidy,
# a file found clean is taken from the cache on the next run, and is checked again (and fails)
# once a header it includes gains a finding, once a NOLINT comment that hid a finding is removed,
# or once .clang-tidy turns on a check that finds something; a failing file is never cached. A copy
# of the project at another path (a CI clone) finds the results of the first, and still fails once
# its header gains a finding.
# Usage: tidy_cache_test.sh SCRIPTS_LIB_DIR
set -euo pipefail
lib=$(cd "$1" && pwd)
work=$(mktemp -d)
clone=$(mktemp -d)
trap 'rm -rf "$work" "$clone"' EXIT
cd "$work"
mkdir src
printf "Checks: '-*,modernize-use-nullptr'\nHeaderFilterRegex: '.*'\n" > src/.clang-tidy
echo 'inline int* first() { return nullptr; }' > src/h.hpp
printf '#include "h.hpp"\nint main() { return first() == nullptr ? 0 : 1; }\n' > src/a.cpp
echo 'int other() { return 1; }' > src/b.cpp
cat > compile_commands.json <<JSON
[{"directory": "$work/src", "command": "c++ -std=c++17 -c a.cpp -o a.o", "file": "a.cpp"},
 {"directory": "$work/src", "command": "c++ -std=c++17 -c b.cpp -o b.o", "file": "b.cpp"}]
JSON

step=0
# run EXPECTED_SUMMARY EXPECTED_FAILING_FILES...: runs the cached check, compares the summary's
# counts and the set of files with a log.
run() {
  local want=$1 got logs
  shift
  step=$((step + 1))
  rm -rf logs && mkdir logs
  got=$(python3 "$lib/tidy_cache.py" --build "$PWD" --logs logs --cache "$work/cache" --jobs 2 src/a.cpp src/b.cpp)
  logs=$(cd logs && ls | sed 's/\.log$//' | tr '\n' ' ')
  if [[ "$got" != *"$want"* ]] || [ "$logs" != "$*${*:+ }" ]; then
    echo "step $step: expected '$want' and failing files '$*', got '$got' and '$logs'"
    cat logs/* 2>/dev/null || true
    exit 1
  fi
}

run "2 files: 0 clean in the cache, 2 checked"
run "2 files: 2 clean in the cache, 0 checked"
echo 'inline int* first() { return 0; }' > src/h.hpp     # a finding in an included header
run "2 files: 1 clean in the cache, 1 checked" src_a.cpp
run "2 files: 1 clean in the cache, 1 checked" src_a.cpp  # a failing file is not cached
echo 'inline int* first() { return 0; }  // NOLINT' > src/h.hpp
run "2 files: 1 clean in the cache, 1 checked"
run "2 files: 2 clean in the cache, 0 checked"
echo 'inline int* first() { return 0; }' > src/h.hpp     # the NOLINT removed again
run "2 files: 1 clean in the cache, 1 checked" src_a.cpp
printf "Checks: '-*,modernize-use-bool-literals'\nHeaderFilterRegex: '.*'\n" > src/.clang-tidy
run "2 files: 0 clean in the cache, 2 checked"
printf "Checks: '-*,modernize-use-nullptr'\nHeaderFilterRegex: '.*'\n" > src/.clang-tidy
run "2 files: 1 clean in the cache, 1 checked" src_a.cpp
echo 'int other() { int* p = 0; return p ? 1 : 0; }' > src/b.cpp  # the checked file itself
run "2 files: 0 clean in the cache, 2 checked" src_a.cpp src_b.cpp
echo 'int other() { return 1; }' > src/b.cpp
echo 'inline int* first() { return nullptr; }' > src/h.hpp
run "2 files: 2 clean in the cache, 0 checked"           # both as in the first run
cp -r src "$clone/"
sed "s|$work|$clone|g" compile_commands.json > "$clone/compile_commands.json"
cd "$clone"
run "2 files: 2 clean in the cache, 0 checked"           # the clone elsewhere hits
echo 'inline int* first() { return 0; }' > src/h.hpp
run "2 files: 1 clean in the cache, 1 checked" src_a.cpp
echo "tidy cache: $step runs as expected"
