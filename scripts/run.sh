#!/usr/bin/env bash
# Sets everything up, builds, and runs the main job on defaults.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/app/gpm kin home
