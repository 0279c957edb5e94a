#!/usr/bin/env bash
# Sets up, builds, and runs the main job on the built-in default scene:
# the project's stockinette on the built-in drape mesh, ply curves written to knit-plies.obj.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh"
"$root/build/apps/knit/knit" build --report knit-report.json "$@"
