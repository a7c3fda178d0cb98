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
  pybind11-dev python3-dev python3-numpy libzstd-dev zlib1g-dev libgdal-dev libassimp-dev
  libsdformat-dev liburdfdom-dev libmeshoptimizer-dev
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

# The example elevation model of scenes/olinda_dem.yaml: the Olinda DEM and Landsat
# image Debian's r-cran-stars ships (Apache-2.0), taken from the package without
# installing R; its test skips where it is absent (no network to the archive).
stars=/usr/local/share/trackbed/r-cran-stars
if [ ! -f "$stars/tif/olinda_dem_utm25s.tif" ]; then
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  tmp=$(mktemp -d)
  if (cd "$tmp" && { apt-get download r-cran-stars >/dev/null 2>&1 ||
        { "${sudo_cmd[@]}" apt-get update -qq && apt-get download r-cran-stars >/dev/null 2>&1; }; }); then
    dpkg-deb -x "$tmp"/r-cran-stars_*.deb "$tmp/x"
    "${sudo_cmd[@]}" mkdir -p "$stars"
    "${sudo_cmd[@]}" cp -r "$tmp/x/usr/lib/R/site-library/stars/tif" \
      "$tmp/x/usr/share/doc/r-cran-stars/copyright" "$stars/"
  else
    echo "setup: r-cran-stars could not be downloaded: scenes/olinda_dem.yaml will not run"
  fi
  rm -rf "$tmp"
fi

# Textured mesh files for scenes/mesh_props.yaml: models Debian's assimp-testmodels
# ships (BSD-3-clause, the ASSIMP Development Team), taken from the package without
# installing it; the scene's test skips where they are absent.
models=/usr/local/share/trackbed/assimp-testmodels
if [ ! -f "$models/OBJ/spider.obj" ]; then
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  tmp=$(mktemp -d)
  if (cd "$tmp" && { apt-get download assimp-testmodels >/dev/null 2>&1 ||
        { "${sudo_cmd[@]}" apt-get update -qq && apt-get download assimp-testmodels >/dev/null 2>&1; }; }); then
    dpkg-deb -x "$tmp"/assimp-testmodels_*.deb "$tmp/x"
    src="$tmp/x/usr/share/assimp/models"
    "${sudo_cmd[@]}" mkdir -p "$models/OBJ" "$models/glTF2"
    "${sudo_cmd[@]}" cp "$src"/OBJ/spider.obj "$src"/OBJ/spider.mtl "$src"/OBJ/*.jpg "$models/OBJ/"
    "${sudo_cmd[@]}" cp -r "$src"/glTF2/BoxTextured-glTF "$src"/glTF2/BoxTextured-glTF-Binary \
      "$models/glTF2/"
    "${sudo_cmd[@]}" cp "$tmp/x/usr/share/doc/assimp-testmodels/copyright" "$models/"
  else
    echo "setup: assimp-testmodels could not be downloaded: scenes/mesh_props.yaml will not run"
  fi
  rm -rf "$tmp"
fi

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
cmake --build build -j2
