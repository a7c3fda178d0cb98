#!/usr/bin/env bash
# Runs the scenarios whose run folders a refactor must leave byte-identical
# (corridor, outdoor, tr_lab, nav_outdoor, a kinematic navigation run and the CI
# sweep) into OUT, with the given trackbed binary. Compare two such folders with
# scripts/compare_run_folders.py.
#   bash scripts/golden_runs.sh build/apps/trackbed runs/golden_after
set -euo pipefail
bin=$(realpath "$1")
out=$2
cd "$(dirname "$0")/.."
rm -rf "$out"
mkdir -p "$out"
for scene in corridor outdoor tr_lab nav_outdoor nav_paper_left; do
  "$bin" run "scenes/$scene.yaml" --out "$out/$scene" > "$out/$scene.log" 2>&1
done
"$bin" sweep scenes/sweeps/ci.yaml --out "$out/ci_sweep" --jobs 2 > "$out/ci_sweep.log" 2>&1
