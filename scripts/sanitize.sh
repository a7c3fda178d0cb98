#!/usr/bin/env bash
# The sanitizer jobs of CI (docs/architecture.md), each in its own build folder, built only for the
# targets its tests need:
#   scripts/sanitize.sh address   build-asan/: every test labelled unit under
#                                 AddressSanitizer + UndefinedBehaviorSanitizer
#                                 (LeakSanitizer included)
#   scripts/sanitize.sh thread    build-tsan/: under ThreadSanitizer, the closed-loop test
#                                 that runs the robot software on its second thread
#                                 (the localization worker) with the camera on
# Extra arguments go to ctest. Any sanitizer report fails the test that made it.
# Needs what scripts/setup.sh installs (gcc's sanitizer runtimes come with g++).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

usage() { echo "usage: scripts/sanitize.sh address|thread [CTEST_ARGS...]" >&2; exit 2; }
[ $# -ge 1 ] || usage
kind=$1
shift

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
suppressions=$root/tests/sanitizers
case "$kind" in
  address)
    build=$root/build-asan
    sanitize=address,undefined
    targets=(unit_tests)
    tests=(-L '^unit$')
    # Leaks are checked in trackbed's code; Mesa's OSMesa keeps a few allocations past
    # its context's destruction, suppressed by library (tests/sanitizers/lsan.supp).
    export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=1}
    export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$suppressions/lsan.supp:print_suppressions=0}
    export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
    ;;
  thread)
    build=$root/build-tsan
    sanitize=thread
    targets=(localization_closed_loop_test)
    tests=(-R '^LocalizationClosedLoopTest\.VisionSeesTheSameImagesWhicheverThreadRunsTheSensorModel$')
    # llvmpipe rasterises on threads of its own, in a library built without TSan: its
    # synchronisation is invisible to TSan. LP_NUM_THREADS=0 makes it draw on the calling
    # thread, so that the only threads are trackbed's (no suppression file needed).
    export LP_NUM_THREADS=0
    export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}
    ;;
  *) usage ;;
esac

# -O1 with line tables (-g1): what the sanitizers' documentation recommends for readable
# stacks at a tolerable speed; NDEBUG as in the release build, so that the same code runs.
# Warnings are not errors here: under instrumentation gcc warns falsely in its own
# headers (-Wmaybe-uninitialized in <regex>); the release build keeps -Werror. A unity
# build compiles each library's sources a few at a time, parsing their heavy headers
# (Eigen, OpenCV, Bullet) once per batch.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -g1 -DNDEBUG" "${launcher[@]}" -DCMAKE_UNITY_BUILD=ON \
  -DTRACKBED_SANITIZE="$sanitize" -DTRACKBED_WERROR=OFF -DTRACKBED_BUILD_BENCH=OFF \
  -DTRACKBED_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" -j2 --target "${targets[@]}"
ctest --test-dir "$build" --output-on-failure -j2 --timeout 1800 "${tests[@]}" "$@"
