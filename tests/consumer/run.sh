#!/usr/bin/env bash
# Installs a build into a temporary prefix, then configures, builds and runs tests/consumer
# against it: run.sh BUILD_DIR [WORK_DIR]. (ctest: consumer_package.)
set -euo pipefail
build=$(realpath "$1")
work=${2:-$(mktemp -d)}
here=$(cd "$(dirname "$0")" && pwd)
prefix="$work/prefix"
rm -rf "$prefix" "$work/consumer" "$work/consumer-render"
mkdir -p "$work"
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
# Every public header of the installed targets is there.
for h in knit/scene.hpp knit/export.hpp knit/render.hpp knit/error.hpp; do
  [ -f "$prefix/include/$h" ] || { echo "missing installed header $h" >&2; exit 1; }
done
cmake -S "$here" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/consumer" -j"${KNIT_JOBS:-2}" > "$work/build.log"
"$work/consumer/consumer" "$work/plies.obj"
# The render component is found on request (with Embree), with its former name too.
cmake -S "$here" -B "$work/consumer-render" -DCMAKE_PREFIX_PATH="$prefix" -DCONSUMER_WITH_RENDER=ON > "$work/configure-render.log"
