#!/usr/bin/env bash
# Fuzzes every parser a user feeds (fuzz/CMakeLists.txt lists the targets):
#   scripts/fuzz.sh [SECONDS] [TARGET...]     (default: 60 s each, every target)
# Configures build-fuzz/ with clang (libFuzzer, ASan, UBSan), builds the fuzz targets only,
# and runs each for SECONDS from a working corpus under build-fuzz/corpus/ seeded from
# tests/fuzz_corpus/<name>/ (which is never grown here). A crash, sanitizer report,
# timeout (10 s per input), out-of-memory (2 GB) or leak is copied to
# tests/fuzz_corpus/<name>/ and makes the script exit 1, naming target and file: fix it,
# then rename the file crash-<what> so that ctest's fuzz_replay_<name> replays it.
# FUZZ_PARALLEL=N runs N targets at a time (default 1; each target uses one core).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

seconds=${1:-60}
shift || true
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -eq 0 ]; then
  echo "usage: scripts/fuzz.sh [SECONDS] [TARGET...]" >&2
  exit 2
fi
parallel=${FUZZ_PARALLEL:-1}
build=$root/build-fuzz

command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (Debian: clang)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  "${launcher[@]}" -DTRACKBED_FUZZ=ON -DTRACKBED_BUILD_TESTS=OFF -DTRACKBED_BUILD_BENCH=OFF \
  -DTRACKBED_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" -j2 --target fuzz_targets

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$root"/fuzz/*_fuzz.cpp; do
    n=$(basename "$f" _fuzz.cpp)
    targets+=("$n")
  done
fi

# The sanitizers' reports end the run with a stack; the temporary files of the targets
# (fuzz inputs written as files) go under the build folder.
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TMPDIR=$build/tmp
mkdir -p "$TMPDIR"

# Runs target $1; writes its one-line result to $build/results/$1.
run_target() {
  local name=$1
  local exe=$build/fuzz/${name}_fuzz
  local seeds=$root/tests/fuzz_corpus/$name
  local corpus=$build/corpus/$name artifacts=$build/artifacts/$name/ log=$build/logs/$name.log
  local result=$build/results/$name
  if [ ! -x "$exe" ]; then
    echo "$name: FAILED: no such fuzz target ($exe)" >"$result"
    return
  fi
  mkdir -p "$corpus" "$artifacts" "$build/logs"
  rm -f "$artifacts"/*
  [ -d "$seeds" ] && cp -n "$seeds"/* "$corpus"/ 2>/dev/null || true
  local status=0
  "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$artifacts" "$corpus" >"$log" 2>&1 || status=$?
  local execs
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
  local found
  found=$(find "$artifacts" -type f | head -1)
  if [ "$status" -eq 0 ] && [ -z "$found" ]; then
    echo "$name: ok, ${execs:-?} executions in ${seconds} s" >"$result"
    return
  fi
  if [ -n "$found" ]; then
    mkdir -p "$seeds"
    cp "$found" "$seeds/"
    echo "$name: FINDING after ${execs:-?} executions: tests/fuzz_corpus/$name/$(basename "$found")" \
         "(log: ${log#"$root"/})" >"$result"
  else
    echo "$name: FAILED (exit $status, no input saved; log: ${log#"$root"/})" >"$result"
  fi
}

rm -rf "$build/results"
mkdir -p "$build/results"
running=0
for name in "${targets[@]}"; do
  echo "fuzzing $name for ${seconds} s ..."
  run_target "$name" &
  running=$((running + 1))
  if [ "$running" -ge "$parallel" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait

echo
echo "fuzz results (${seconds} s per target):"
failed=0
for name in "${targets[@]}"; do
  cat "$build/results/$name"
  grep -q ": ok," "$build/results/$name" || failed=1
done
for name in "${targets[@]}"; do
  if ! grep -q ": ok," "$build/results/$name"; then
    echo
    echo "--- $name: end of $build/logs/$name.log ---"
    tail -40 "$build/logs/$name.log" 2>/dev/null || true
  fi
done
exit "$failed"
