#!/usr/bin/env bash
# Sets everything up, builds, and runs the main job on defaults: a simulated
# calibration of the GPM2002 (twin with perturbed parameters, encoder samples,
# maximum-likelihood calibration, compensation, before/after accuracy) with a
# short report. Output folder: out/main (or the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=${1:-out/main}
./build/app/gpm run scenarios/main.yaml -o "$out"
