#!/usr/bin/env bash
# Installs dependencies (idempotent) and builds everything into build/.
# Portable x86-64 binaries by default. Environment switches:
#   GPM_NATIVE=1  build for this machine's instruction set (local binaries only)
#   GPM_WERROR=1  treat the project's warnings as errors (CI)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
onoff() { [[ "${1:-0}" == 1 ]] && echo ON || echo OFF; }
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DGPM_NATIVE="$(onoff "${GPM_NATIVE:-0}")" -DGPM_WERROR="$(onoff "${GPM_WERROR:-0}")" >/dev/null
cmake --build build --parallel "$(nproc)"
