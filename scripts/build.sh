#!/usr/bin/env bash
# Configures and builds libknit (Release) into ${KNIT_BUILD_DIR:-build}.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${KNIT_BUILD_DIR:-"$root/build"}
jobs=${KNIT_JOBS:-$(nproc)}
source "$root/scripts/lib/ccache.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${ccache_launcher[@]}" "$@"
cmake --build "$build" -j"$jobs"
