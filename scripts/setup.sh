#!/usr/bin/env bash
# Installs the Debian packages libknit needs (idempotent; runs apt-get only when something is missing).
# Usage: scripts/setup.sh [EXTRA_PACKAGE ...]   (extra packages a script needs, e.g. gnuplot-nox)
set -euo pipefail
packages=(
  build-essential cmake pkg-config ccache
  libcgal-dev libdraco-dev libtinygltf-dev libglm-dev libembree-dev libtbb-dev
  libgtest-dev libbenchmark-dev libstb-dev nlohmann-json3-dev libcli11-dev libtinyexr-dev
  libeigen3-dev libmeshoptimizer-dev libnlopt-dev zlib1g-dev libisal-dev
  clang libclang-rt-14-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed blender
  clang-format clang-tidy
  libcpp-httplib-dev chromium  # knit serve's HTTP server; the headless browser of its page tests
  "$@"
)
# The glTF-Validator runs on Node.js: use the machine's node/npm if present (a NodeSource
# install would conflict with Debian's npm package), otherwise Debian's.
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -q
  $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
# Blender (optional): the Mesh Cache integration test of `knit animate` runs when it is
# installed and is skipped otherwise (with CI=true it fails instead). A failed install does not
# stop the setup.
if ! command -v blender >/dev/null 2>&1; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends blender ||
    echo "setup: blender could not be installed; the Blender tests will be skipped"
fi
