#!/usr/bin/env bash
# Whole processes: `gpm calibrate` (start-up, CSV and robot file read,
# identifiability, Ceres LM, covariance, result YAML written) against the
# scipy script bench/calib_scipy.py run as a process with one solve
# (interpreter start-up, numpy/scipy import, CSV read,
# scipy.optimize.least_squares(method="lm")), on the same CSV: 50 noiseless
# samples of the paper Table 5 robot, 11 free parameters, start nominal with
# xa1, ya1, xa2, ya2 at their true values, for each cost J1, J2, J3, ML.
# Each process runs REPETITIONS times, alternating gpm and scipy; prints the
# median and fastest wall time of each, the final errors against Table 5 and
# the ratios scipy / gpm (goal >= 10x), with the load average before and
# after (the machine may be shared: judge the figures by it).
#   bash bench/calib_process_vs_scipy.sh [BUILD_DIR] [REPETITIONS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
reps=${2:-20}
gpm=$build/app/gpm
py=/usr/bin/python3   # Debian's python3 with python3-scipy (scripts/setup.sh)
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$gpm" study samples --actual table5 --n 50 --radius 120 --seed 1 -o "$tmp/samples.csv" >/dev/null
# The start: nominal, with the four fixed base coordinates at their Table 5
# values (as bench/calib_scipy.py starts).
sed -e 's/^  ya2: 0$/  ya2: 0.3/' "$here/../models/gpm2002.yaml" >"$tmp/start.yaml"
grep -q '^  ya2: 0.3$' "$tmp/start.yaml" || { echo "calib_process_vs_scipy: models/gpm2002.yaml has no 'ya2: 0' line to set" >&2; exit 2; }

# median and minimum of the numbers on stdin (seconds), as "median min".
stats() { sort -g | awk '{t[NR] = $1} END {print t[int((NR + 1) / 2)], t[1]}'; }
# largest |estimate - Table 5| over lengths (mm) and offsets (rad) of a result YAML.
errors() {
  awk 'BEGIN {split("xa1 0 ya1 250 xa2 433 ya2 0.3 xa3 433.5 ya3 499.4 la1 244.1 la2 244.2 la3 243.5 lb1 243.8 lb2 244.2 lb3 244.6 dth1 0.01 dth2 -0.01 dth3 0.01", v, " ")
              for (i = 1; i < 30; i += 2) truth[v[i] ":"] = v[i + 1]}
       /^geometry:/ {on = 1; next} /^[^ ]/ {on = 0}
       on && ($1 in truth) {e = $2 - truth[$1]; if (e < 0) e = -e
                            if ($1 ~ /^dth/) {if (e > rad) rad = e} else if (e > mm) mm = e}
       END {printf "%.3g %.3g\n", mm, rad}' "$1"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) cores)"
printf "%-6s %-28s %11s %9s %11s %12s %13s %10s\n" cost program "median ms" "min ms" "max err mm" "max err rad" "median ratio" "min ratio"
for cost in j1 j2 j3 ml; do
  : >"$tmp/gpm.t"
  : >"$tmp/py.t"
  for ((k = 0; k < reps; ++k)); do
    t0=$EPOCHREALTIME
    "$gpm" calibrate --data "$tmp/samples.csv" --model "$tmp/start.yaml" --cost "$cost" -o "$tmp/result.yaml" >/dev/null
    t1=$EPOCHREALTIME
    "$py" "$here/calib_scipy.py" "$tmp/samples.csv" 1 "$cost" >"$tmp/py.out"
    t2=$EPOCHREALTIME
    echo "$t1 $t0" | awk '{print $1 - $2}' >>"$tmp/gpm.t"
    echo "$t2 $t1" | awk '{print $1 - $2}' >>"$tmp/py.t"
  done
  read -r gm gn <<<"$(stats <"$tmp/gpm.t")"
  read -r sm sn <<<"$(stats <"$tmp/py.t")"
  read -r ge gr <<<"$(errors "$tmp/result.yaml")"
  read -r _ _ _ _ _ se _ sr _ <<<"$(cat "$tmp/py.out")"
  printf "%-6s %-28s %11.1f %9.1f %11s %12s\n" "$cost" "gpm calibrate" \
    "$(awk -v t="$gm" 'BEGIN{print t*1000}')" "$(awk -v t="$gn" 'BEGIN{print t*1000}')" "$ge" "$gr"
  printf "%-6s %-28s %11.1f %9.1f %11s %12s %12.1fx %9.1fx\n" "$cost" "python3 bench/calib_scipy.py" \
    "$(awk -v t="$sm" 'BEGIN{print t*1000}')" "$(awk -v t="$sn" 'BEGIN{print t*1000}')" "$se" "$sr" \
    "$(awk -v a="$sm" -v b="$gm" 'BEGIN{print a/b}')" "$(awk -v a="$sn" -v b="$gn" 'BEGIN{print a/b}')"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
