#!/usr/bin/env bash
# Installs dependencies (idempotent) and builds everything into build/.
# GPM_PORTABLE=1 builds binaries without -march=native.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
portable=OFF
[[ "${GPM_PORTABLE:-0}" == 1 ]] && portable=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DGPM_PORTABLE=$portable >/dev/null
cmake --build build --parallel "$(nproc)"
