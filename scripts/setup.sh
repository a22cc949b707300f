#!/usr/bin/env bash
# Installs the Debian packages Sierra needs (when missing), then configures and
# builds it in build/ (Release). Sourced by run-default.sh and test.sh; can be
# run on its own. BUILD_DIR and BUILD_TYPE override the defaults;
# SIERRA_SANITIZE=ON builds with AddressSanitizer and UBSan (the CI's second run).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
build_type="${BUILD_TYPE:-Release}"
sanitize="${SIERRA_SANITIZE:-OFF}"

packages=(
  build-essential cmake pkg-config
  libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libglm-dev libstb-dev libimgui-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev glslang-tools clang-format
  libspng-dev libjpeg62-turbo-dev libgdal-dev
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev ffmpeg
  libopenexr-dev
  python-matplotlib-data
  fonts-dejavu-core
  python3-dev python3-numpy python3-pytest pybind11-dev
  gdal-bin python3-gdal
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  if [ "$(id -u)" -eq 0 ]; then
    echo "sierra setup: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "sierra setup: missing Debian packages. Install them with:" >&2
    echo "  sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

jobs="$(nproc 2>/dev/null || echo 2)"
echo "sierra setup: configuring $build_type build in $build_dir (sanitizers $sanitize)"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" -DSIERRA_SANITIZE="$sanitize" >/dev/null
echo "sierra setup: building with $jobs jobs"
cmake --build "$build_dir" -j "$jobs"
