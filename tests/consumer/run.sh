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
# The installed Python module (when the build has one) imports from the prefix, not from the build
# folder, and runs the pipeline.
site=$(find "$prefix/lib" -mindepth 2 -maxdepth 2 -type d -name dist-packages 2>/dev/null | head -1)
if grep -q '^KNIT_BUILD_PYTHON:BOOL=ON' "$build/CMakeCache.txt" && [ -f "$build/python/knit/__init__.py" ]; then
  [ -n "$site" ] && [ -d "$site/knit" ] || { echo "the knit Python package was not installed under $prefix/lib" >&2; exit 1; }
  python=$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  (cd "$work" && PYTHONPATH="$site" "${python:-python3}" -c "
import knit
assert knit.__file__.startswith('$site'), knit.__file__
scene = knit.build_scene('stockinette', 'plane', repeats=(2, 2))
assert len(scene.plies.points) > 0
print('installed Python module:', knit.__file__, len(scene.plies.points), 'ply points')
")
fi
