#!/usr/bin/env bash
# Quick start, command 2: set up, build, and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
# Tests carry their own per-label time limits; --timeout bounds any test without one.
ctest --test-dir build --output-on-failure -j2 --timeout 1800 "$@"
