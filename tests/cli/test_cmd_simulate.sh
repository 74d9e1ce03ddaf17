#!/usr/bin/env bash
# Tests of app/cmd_simulate.cpp: gpm simulate writes the four files, the same
# seed gives identical files, bad input exits 2 with one line on stderr and
# leaves no output behind, a run the tracking watch stops exits 1 with one
# line and keeps its samples, a trajectory whose margin cannot be kept is
# refused (exit 2) before anything moves.
set -u
GPM="$1"
SCEN="$(cd "$(dirname "$0")/../../scenarios" && pwd)"
source "$(dirname "$0")/cli_lib.sh"

# A short scenario next to a copy of the robot file (relative robot path).
cp "$SCEN/../models/gpm2002.yaml" "$tmp/robot.yaml"
cat >"$tmp/short.yaml" <<'YAML'
name: short
robot: robot.yaml
seed: 11
actual: {perturb: {base_mm: 0.3, link_mm: 0.3, offset_rad: 0.01}}
encoder: {noise_rad: 1e-5}
sampling: {pattern: disc, radius: 50, count: 5, average_s: 0.02}
path: {shape: circle, radius: 30, period_s: 0.5}
YAML

check "simulate" 0 "$GPM" simulate "$tmp/short.yaml" -o "$tmp/a"
for f in samples.csv trajectory.csv actual.yaml model.xml; do holds "writes $f" test -s "$tmp/a/$f"; done
holds "samples header" grep -q '^sample,theta_m1,theta_m2,theta_m3,x,y' "$tmp/a/samples.csv"
holds "5 samples" test "$(wc -l <"$tmp/a/samples.csv")" -eq 6
holds "trajectory header" grep -q '^t,x_des,y_des,x,y,theta_m1,theta_m2,theta_m3,tau1,tau2,tau3,violation_m$' "$tmp/a/trajectory.csv"
holds "no temporary files" test -z "$(ls -A "$tmp/a" | grep '^\.')"
check "simulate again" 0 "$GPM" simulate "$tmp/short.yaml" -o "$tmp/b"
for f in samples.csv trajectory.csv actual.yaml model.xml; do holds "same seed, same $f" cmp -s "$tmp/a/$f" "$tmp/b/$f"; done
# The actual robot file and samples feed the other commands.
check "actual.yaml loads" 0 "$GPM" kin home --model "$tmp/a/actual.yaml"
check "example disc scenario" 0 "$GPM" simulate "$SCEN/simulate_disc.yaml" -o "$tmp/disc"

# Bad input: exit 2, one line, nothing written.
sed 's/radius: 50/radius: -50/' "$tmp/short.yaml" >"$tmp/neg.yaml"
check "negative radius" 2 "$GPM" simulate "$tmp/neg.yaml" -o "$tmp/neg"
expect_err "key path" "neg.yaml:6: sampling.radius: must be positive"
holds "nothing written" test ! -e "$tmp/neg"
printf 'sampeling: {}\n' >"$tmp/typo.yaml"
check "unknown key" 2 "$GPM" simulate "$tmp/typo.yaml" -o "$tmp/typo"
expect_err "suggestion" "did you mean sampling\?"
sed 's/sampling: .*/sampling: {pattern: list, poses: [[216.5, 250], [216.5, 720]]}/' "$tmp/short.yaml" >"$tmp/far.yaml"
check "unreachable pose" 2 "$GPM" simulate "$tmp/far.yaml" -o "$tmp/far"
expect_err "pose and reach" "sampling: pose 1 \(216.5000, 720.0000\): chain [0-9]: .* outside its reach"
holds "nothing written" test ! -e "$tmp/far"
sed 's/min_transmission: 0.15/min_transmission: 0.9/' "$tmp/robot.yaml" >"$tmp/strict.yaml"
sed 's/robot: robot.yaml/robot: strict.yaml/; s/sampling: .*/sampling: {pattern: list, poses: [[216.5, 250], [300, 250]]}/' "$tmp/short.yaml" >"$tmp/sing.yaml"
check "pose near a singularity" 2 "$GPM" simulate "$tmp/sing.yaml" -o "$tmp/sing"
expect_err "singularity margin" "sampling: pose [0-9] .*singularity.*below the margin 0.9"
sed 's/actual: .*/actual: {geometry: {lb2: 30}}/' "$tmp/short.yaml" >"$tmp/asm.yaml"
check "cannot assemble" 2 "$GPM" simulate "$tmp/asm.yaml" -o "$tmp/asm"
expect_err "assembly" "actual parameters cannot assemble"
check "missing scenario" 2 "$GPM" simulate "$tmp/none.yaml" -o "$tmp/none"
expect_err "missing file" "none.yaml: cannot open file"
check "missing -o" 2 "$GPM" simulate "$tmp/short.yaml"
mkdir -p "$tmp/keep" && echo old >"$tmp/keep/samples.csv"
check "bad run keeps old output" 2 "$GPM" simulate "$tmp/far.yaml" -o "$tmp/keep"
holds "old file untouched" grep -qx old "$tmp/keep/samples.csv"

# The tracking watch (servo.max_tracking_mm): joint 1 torque-off and encoder 2
# 0.1 rad off its zero: the five-bar puts the hub millimetres off the plan,
# the torque-off joint's reading shows it, and 1 mm stops the run.
sed 's/actual: .*/actual: {geometry: {dth2: 0.1}}/; s/path: .*/servo: {modes: [torque_off, position, position], max_tracking_mm: 1}/' \
  "$tmp/short.yaml" >"$tmp/track.yaml"
check "tracking stop" 1 "$GPM" simulate "$tmp/track.yaml" -o "$tmp/track" --progress=none  # the error line alone
expect_err "tracking stop line" "^gpm: error: tracking: at t = .* beyond servo.max_tracking_mm 1 mm: drives stopped$"
holds "one line" test "$(wc -l <"$tmp/err")" -eq 1
holds "samples kept" grep -q '^sample,theta_m1' "$tmp/track/samples.csv"
holds "trajectory kept" test -s "$tmp/track/trajectory.csv"
# A trajectory plan whose margin cannot be kept: exit 2 before anything moves.
sed 's/sampling: .*/sampling: {pattern: trajectory, count: 11, path_margin: {singularity: 0.85}}/; /^path:/d' \
  "$tmp/short.yaml" >"$tmp/margin.yaml"
check "margin refused" 2 "$GPM" simulate "$tmp/margin.yaml" -o "$tmp/margin"
expect_err "names the key" "sampling.path_margin: only 0 points"
holds "nothing written" test ! -e "$tmp/margin"

finish
