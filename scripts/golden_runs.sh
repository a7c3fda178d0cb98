#!/usr/bin/env bash
# Runs the scenarios whose run folders a refactor must leave byte-identical
# (corridor, outdoor, tr_lab, nav_outdoor, a kinematic navigation run and the CI
# sweep) into OUT, with the given trackbed binary. Compare two such folders with
# scripts/compare_run_folders.py.
# Further arguments are overrides for every run and sweep cell, e.g. the realism profile
# that reproduces the runs before it existed:
#   bash scripts/golden_runs.sh build/apps/trackbed runs/golden_after
#   bash scripts/golden_runs.sh build/apps/trackbed runs/ideal robot.realism=ideal
set -euo pipefail
bin=$(realpath "$1")
out=$2
shift 2
sets=()
for s in "$@"; do sets+=(--set "$s"); done
cd "$(dirname "$0")/.."
rm -rf "$out"
mkdir -p "$out"
out=$(realpath "$out")
for scene in corridor outdoor tr_lab nav_outdoor nav_paper_left; do
  "$bin" run "scenes/$scene.yaml" --out "$out/$scene" "${sets[@]}" > "$out/$scene.log" 2>&1
done
sweep=scenes/sweeps/ci.yaml
if [ $# -gt 0 ]; then
  # The CI sweep with the overrides added to its `set` list, written into OUT; its
  # scenarios are still found beside the original (base_dir).
  sweep="$out/ci_sweep.yaml"
  extra=$(printf ', "%s"' "$@")
  { echo "base_dir: $(realpath scenes/sweeps)"
    sed "s/^set: \[\(.*\)\]$/set: [\1$extra]/" scenes/sweeps/ci.yaml; } > "$sweep"
fi
"$bin" sweep "$sweep" --out "$out/ci_sweep" --jobs 2 > "$out/ci_sweep.log" 2>&1
