#!/usr/bin/env bash
# One whole LM calibration (11 parameters, 50 noiseless samples of the paper
# Table 5 robot, start from nominal) by gpm's calib/lm (Ceres, analytic
# Jacobians; the autodiff reference on the line above it) against
# scipy.optimize.least_squares(method="lm") on the same CSV, in the same run,
# for each cost J1, J2, J3, ML. Ratios: scipy time / gpm (analytic) time.
# Prints solve times (median and fastest of many repetitions: on a loaded
# machine the fastest is the fairer figure), their ratios and both final
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
printf "%-6s %-24s %11s %9s %11s %12s %13s %10s\n" cost solver "median ms" "min ms" "max err mm" "max err rad" "median ratio" "min ratio"
row() {  # cost, solver, median s, min s, err mm, err rad[, scipy median s, scipy min s]
  if [ $# -gt 6 ]; then
    printf "%-6s %-24s %11.3f %9.3f %11s %12s %12.1fx %9.1fx\n" "$1" "$2" "$(awk -v t="$3" 'BEGIN{print t*1000}')" \
      "$(awk -v t="$4" 'BEGIN{print t*1000}')" "$5" "$6" "$(awk -v a="$7" -v b="$3" 'BEGIN{print a/b}')" \
      "$(awk -v a="$8" -v b="$4" 'BEGIN{print a/b}')"
  else
    printf "%-6s %-24s %11.3f %9.3f %11s %12s\n" "$1" "$2" "$(awk -v t="$3" 'BEGIN{print t*1000}')" \
      "$(awk -v t="$4" 'BEGIN{print t*1000}')" "$5" "$6"
  fi
}
for cost in j1 j2 j3 ml; do
  a=$("$bench" "$tmp/samples.csv" "$reps" "$cost" autodiff)
  c=$("$bench" "$tmp/samples.csv" "$reps" "$cost")
  s=$("$py" "$here/calib_scipy.py" "$tmp/samples.csv" "$(( reps / 10 > 5 ? reps / 10 : 5 ))" "$cost")
  read -r _ am _ an _ ae _ ar _ <<<"$a"
  read -r _ cm _ cn _ ce _ cr _ <<<"$c"
  read -r _ sm _ sn _ se _ sr _ <<<"$s"
  # Ratios: on the scipy row scipy / gpm (analytic), as always; on the
  # autodiff row scipy / autodiff (what the analytic Jacobians gained).
  row "$cost" "gpm calib/lm autodiff" "$am" "$an" "$ae" "$ar" "$sm" "$sn"
  row "$cost" "gpm calib/lm (Ceres)" "$cm" "$cn" "$ce" "$cr"
  printf "%-6s %-24s %11.3f %9.3f %11s %12s %12.1fx %9.1fx\n" "$cost" "scipy least_squares lm" \
    "$(awk -v t="$sm" 'BEGIN{print t*1000}')" "$(awk -v t="$sn" 'BEGIN{print t*1000}')" "$se" "$sr" \
    "$(awk -v a="$sm" -v b="$cm" 'BEGIN{print a/b}')" "$(awk -v a="$sn" -v b="$cn" 'BEGIN{print a/b}')"
done
