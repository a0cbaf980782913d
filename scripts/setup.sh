#!/usr/bin/env bash
# Installs carbtf's Debian 12 build dependencies (only when something is missing), then configures and
# builds in Release. Idempotent: on a machine where everything is present it costs one dpkg query and
# an incremental build.
#
# Usage: scripts/setup.sh [BUILD_DIR]      (default: build)
# Environment: CARBTF_CMAKE_ARGS  extra arguments for the CMake configure step.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-$repo_root/build}"

# Why each package is here:
#   build-essential cmake pkg-config ninja-build   toolchain and build system
#   libvulkan-dev                                   Vulkan headers + loader (engine/)
#   mesa-vulkan-drivers                             lavapipe: Vulkan on the CPU when no GPU driver is present
#   vulkan-validationlayers                         validation in every test
#   glslang-tools                                   GLSL -> SPIR-V at build time
#   libeigen3-dev libopenimageio-dev                analysis/ (model fitting, image I/O)
#   libimath-dev                                    half floats for linear BTF images
#   libzip-dev                                      BTF archives (.zip) read and written by analysis/
#   zlib1g-dev                                      deflated chunks of the material file (engine/)
#   nlohmann-json3-dev                              sample-material recipes (assets/materials/*.json)
#   libcli11-dev                                    command-line parsing
#   libglm-dev                                      vector/matrix maths of the render pass (engine/)
#   libtinyobjloader-dev                            OBJ meshes for `carbtf render --mesh file.obj` (host/)
#   catch2                                          tests
#   clang libclang-rt-14-dev                        libFuzzer and the sanitized test tree (tests/fuzz)
#   clang-format                                    the format test (tests/format): every C/C++ file clean
packages=(
  build-essential cmake pkg-config ninja-build
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libeigen3-dev libopenimageio-dev libimath-dev libzip-dev zlib1g-dev nlohmann-json3-dev
  libcli11-dev libglm-dev libtinyobjloader-dev
  catch2 clang libclang-rt-14-dev clang-format
)

missing=()
for p in "${packages[@]}"; do
  status="$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)"
  [ "$status" = "installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "carbtf setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  # shellcheck disable=SC2086
  cmake -S "$repo_root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCARBTF_WERROR=ON ${CARBTF_CMAKE_ARGS:-}
fi
cmake --build "$build_dir" --parallel "$(nproc)"
