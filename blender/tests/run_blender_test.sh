#!/usr/bin/env bash
# Runs a headless Blender test script: run_blender_test.sh SCRIPT (KNIT_PYTHONPATH set by ctest).
# Without Blender the test is skipped (exit 77, ctest's SKIP_RETURN_CODE), except with CI=true.
set -euo pipefail
blender=${KNIT_BLENDER:-blender}
if ! command -v "$blender" >/dev/null 2>&1; then
  if [ "${CI:-}" = "true" ]; then
    echo "blender not found (install it with scripts/setup.sh); CI=true makes this a failure" >&2
    exit 1
  fi
  echo "SKIPPED: blender not found (install it with scripts/setup.sh)"
  exit 77
fi
exec "$blender" -b --factory-startup --python-exit-code 1 --python "$1"
