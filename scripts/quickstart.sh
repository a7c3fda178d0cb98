#!/usr/bin/env bash
# Quick start, command 1: set up, build, and run the default scenario (the
# indoor corridor) into runs/corridor, printing where its outputs went.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
out=runs/corridor
build/apps/trackbed run scenes/corridor.yaml --out "$out"
echo "quickstart: run folder $(pwd)/$out:"
ls "$out"
echo "quickstart: metrics in $(pwd)/$out/metrics.json"
