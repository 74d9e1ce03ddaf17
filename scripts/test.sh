#!/usr/bin/env bash
# Sets everything up, builds, and runs the default test suite (unit, cli and
# fast scenario tests; long studies carry a *long / montecarlo label and are
# excluded: run them with `ctest --test-dir build -L <label>`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" -LE 'long|montecarlo' "$@"
