#!/usr/bin/env bash
# Sets up, builds, and starts `knit serve`: a local web page to write a chart and see it knitted
# in 3D (docs/serve.md). Open the address it prints; Ctrl-C stops it. Flags go to `knit serve`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh"
build="$root/build"
# three.js (npm, once per build folder): the page's 3D view, served by knit serve itself.
[ -f "$build/node/node_modules/three/build/three.module.js" ] || cmake --build "$build" --target three_js
exec "$build/apps/knit/knit" serve "$@"
