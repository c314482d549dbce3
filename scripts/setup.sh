#!/usr/bin/env bash
# setup.sh - installs passgraph's Debian build/run dependencies that are missing, then configures
# and builds into build/ (or $PG_BUILD_DIR). Safe to run repeatedly. Needs root or sudo for
# apt-get only when something is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

PKGS=(
  build-essential cmake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools
  libtinygltf-dev libmeshoptimizer-dev libdraco-dev nlohmann-json3-dev libcjson-dev libstb-dev libwebp-dev
  valgrind curl xz-utils
  libglfw3-dev libimgui-dev xvfb xauth graphviz
  libopencolorio-dev libopenexr-dev
  python3-numpy python3-skimage
  renderdoccmd python3-renderdoc librenderdoc-dev
)

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

BUILD_DIR=${PG_BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=${PG_BUILD_TYPE:-RelWithDebInfo} ${PG_CMAKE_ARGS:-} >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)"
echo "setup: built $BUILD_DIR/passgraph"
