#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (ctest).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh"
build="$root/build"
# The Khronos glTF-Validator (npm) that the export tests run on every glTF/GLB they write.
[ -d "$build/node/node_modules/gltf-validator" ] || cmake --build "$build" --target gltf_validator
# three.js (npm) for the real-client tests (tests/clients).
[ -d "$build/node/node_modules/three" ] || cmake --build "$build" --target three_js
# puppeteer-core (npm) drives Debian's Chromium through the page of `knit serve` (tests/serve).
[ -d "$build/node/node_modules/puppeteer-core" ] || cmake --build "$build" --target puppeteer_core
cd "$build"
ctest --output-on-failure -j"${KNIT_JOBS:-$(nproc)}"
