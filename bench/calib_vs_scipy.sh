#!/usr/bin/env bash
# One whole LM calibration (11 parameters, 50 noiseless samples of the paper
# Table 5 robot, start from nominal) by gpm's calib/lm (Ceres) against
# scipy.optimize.least_squares(method="lm") on the same CSV, in the same run.
# Prints solve times (median of many repetitions), their ratio and both final
# errors against the true values.
#   bench/calib_vs_scipy.sh [BUILD_DIR] [REPETITIONS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
reps=${2:-200}
gpm=$build/app/gpm
bench=$build/bench/bench_calib_lm
py=/usr/bin/python3   # Debian's python3 with python3-scipy (scripts/setup.sh)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$gpm" study samples --actual table5 --n 50 --radius 120 --seed 1 -o "$tmp/samples.csv" >/dev/null
printf "%-6s %-28s %12s %12s %12s %12s\n" cost solver "median (ms)" "max err mm" "max err rad" ratio
for cost in j2 ml; do
  c=$("$bench" "$tmp/samples.csv" "$reps" "$cost")
  s=$("$py" "$here/calib_scipy.py" "$tmp/samples.csv" "$(( reps / 10 > 5 ? reps / 10 : 5 ))" "$cost")
  ct=$(awk '{print $2}' <<<"$c"); st=$(awk '{print $2}' <<<"$s")
  printf "%-6s %-28s %12.3f %12s %12s %12s\n" "$cost" "gpm calib/lm (Ceres)" "$(awk -v t="$ct" 'BEGIN{print t*1000}')" \
    "$(awk '{print $6}' <<<"$c")" "$(awk '{print $8}' <<<"$c")" ""
  printf "%-6s %-28s %12.3f %12s %12s %12.1fx\n" "$cost" "scipy least_squares lm" "$(awk -v t="$st" 'BEGIN{print t*1000}')" \
    "$(awk '{print $6}' <<<"$s")" "$(awk '{print $8}' <<<"$s")" "$(awk -v a="$st" -v b="$ct" 'BEGIN{print a/b}')"
done
