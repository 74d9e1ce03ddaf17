#!/usr/bin/env bash
# Twin steps per second (servo drives and encoders included) against
# mujoco-testspeed (Debian libmujoco-samples) on the same model.xml, in the
# same run. Prints both rates and the overhead; the goal is at most 25 %.
#   bench/sim_vs_testspeed.sh [BUILD_DIR] [STEPS]
set -euo pipefail
BUILD=${1:-build}
STEPS=${2:-200000}
BENCH="$BUILD/bench/bench_sim"
[[ -x "$BENCH" ]] || { echo "sim_vs_testspeed: $BENCH not built (ninja -C $BUILD bench_sim)" >&2; exit 2; }
command -v mujoco-testspeed >/dev/null || { echo "sim_vs_testspeed: mujoco-testspeed missing (apt install libmujoco-samples)" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# Interleaved rounds (twin, then testspeed) so that load from other processes
# hits both alike; the best rate of each is kept.
best() { sort -n | tail -1; }
for round in 1 2 3; do
  "$BENCH" --steps "$STEPS" --write-model "$tmp/model.xml" >>"$tmp/twin.txt"
  mujoco-testspeed "$tmp/model.xml" "$STEPS" 1 0.01 | awk '/Steps per second/ {print $NF}' >>"$tmp/ts.txt"
done
best_ts=$(best <"$tmp/ts.txt")
twin=$(awk '$1 == "twin_step" {print $2}' "$tmp/twin.txt" | best)
bare=$(awk '$1 == "bare_mj_step" {print $2}' "$tmp/twin.txt" | best)
ctrl=$(awk '$1 == "twin_with_controller" {print $2}' "$tmp/twin.txt" | best)
echo "model                          $(grep -c '<body' "$tmp/model.xml") bodies, $STEPS steps, best of 3 interleaved rounds"
echo "mujoco-testspeed steps/s       $best_ts"
echo "bare mj_step (in bench) /s     $bare"
echo "twin steps/s                   $twin   (servo loop + encoders every step)"
echo "twin + controller IK steps/s   $ctrl"
awk -v t="$twin" -v s="$best_ts" 'BEGIN { printf "ratio testspeed / twin          %.3f   (overhead %.1f %%; goal <= 25 %%)\n", s / t, 100 * (s / t - 1) }'
awk -v t="$twin" -v b="$bare" 'BEGIN { printf "ratio bare mj_step / twin      %.3f   (same process, same mjModel)\n", b / t }'
