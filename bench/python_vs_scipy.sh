#!/usr/bin/env bash
# gpm.calibrate (the Python module) in a Python loop against
# scipy.optimize.least_squares on the same 50 noiseless samples of the paper
# Table 5 robot, in the same process (bench/python_calib_vs_scipy.py). Uses
# Debian's /usr/bin/python3 (python3-scipy, python3-numpy; scripts/setup.sh),
# the interpreter the module is built for. Not part of ctest.
#   bash bench/python_vs_scipy.sh [BUILD_DIR] [REPETITIONS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
reps=${2:-100}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$build/app/gpm" study samples --actual table5 --n 50 --radius 120 --seed 1 -o "$tmp/samples.csv" >/dev/null
PYTHONPATH="$build/python" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 "$here/python_calib_vs_scipy.py" "$tmp/samples.csv" "$reps"
