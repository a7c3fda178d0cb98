#!/usr/bin/env bash
# Installs whatever Debian 12 packages trackbed needs and are missing (quick
# when all are there), then configures and builds into ./build.
# Run as root (or with sudo available) on Debian 12. Used by quickstart.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  g++ cmake ninja-build ccache pkg-config python3
  libbullet-dev libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libopencv-dev libosmesa6-dev libfuzzylite-dev libboost-math-dev
  pybind11-dev python3-dev python3-numpy libzstd-dev zlib1g-dev libgdal-dev
)
# `--tests`: what the test suite needs beyond the build (node and npm run the
# independent MCAP readers, tests/mcap/; xmllint checks JUnit XML), each unless its
# command is there already (a node installed another way brings its own npm).
if [ "${1:-}" = "--tests" ]; then
  command -v node >/dev/null || packages+=(nodejs)
  command -v npm >/dev/null || packages+=(npm)
  command -v xmllint >/dev/null || packages+=(libxml2-utils)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
cmake --build build -j2
