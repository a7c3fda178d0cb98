#!/usr/bin/env bash
# The C++ and Python packages as a user gets them (docs/cpp_package.md): installs the
# build tree BUILD into a fresh prefix, builds examples/own_controller against it with
# find_package(trackbed), runs it on the outdoor scene, and imports the installed
# Python package. A ctest (label `package`) runs it after the build.
#   bash scripts/test_cpp_package.sh build [PYTHON]   (without PYTHON: no Python check)
set -euo pipefail
build=$(realpath "$1")
python=${2:-}
cd "$(dirname "$0")/.."
work=$(mktemp -d /tmp/trackbed_package.XXXXXX)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S examples/own_controller -B "$work/example" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" "${launcher[@]}" > "$work/configure.log"
cmake --build "$work/example" -j2 > "$work/build.log"
"$work/example/own_controller" scenes/outdoor.yaml "$work/run" 10
test -f "$work/run/own.tum"
grep -q '"own"' "$work/run/metrics.json"

if [ -z "$python" ]; then
  echo "test_cpp_package: the example built against the installed package and ran"
  exit 0
fi
site=$(find "$work/prefix" -path '*-packages/trackbed' -type d | head -n 1)
test -n "$site"
PYTHONPATH=$(dirname "$site") "$python" -c \
  'import trackbed, sys; sys.exit(0 if callable(trackbed.Simulation) else 1)'
echo "test_cpp_package: the example built against the installed package and ran; the installed Python package imports"
