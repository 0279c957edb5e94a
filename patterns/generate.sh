#!/usr/bin/env bash
# Regenerates the project's own patterns with the project's own generator (`knit generate`).
# Usage: patterns/generate.sh [path/to/knit]   (default: build/apps/knit/knit)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
knit=${1:-"$here/../build/apps/knit/knit"}
# Plain knit after K. Crane's parametric model; these are the generator's inputs (its defaults).
"$knit" generate stockinette --a 1.5 --h 4 --d 1 --row-gap 0.5 --model-radius 0.8 --radius 0.001 --samples 24 \
  -o "$here/stockinette.pyp"
