#!/usr/bin/env bash
# Tests of run/runner.cpp, sim/scenario.cpp and models/robot_yaml.cpp through
# gpm run and gpm monitor (issue 36, items 6 and 10): every target of a run is
# checked before anything moves and named by its scenario key; a robot file a
# scenario names by a number or a missing path is named with its key; a
# result whose 1-sigma is too large or infinite is refused by the monitor,
# not replaced by a default. Each case: one stderr line, exit 2, nothing written.
set -u
GPM="$1"
SCEN="$(cd "$(dirname "$0")/../../scenarios" && pwd)"
source "$(dirname "$0")/cli_lib.sh"

empty() { [[ -z "$(ls -A "$1" 2>/dev/null)" ]]; }  # absent, or a folder holding nothing

base() {  # a short calibration scenario; $1 is appended
  cat <<YAML
name: msg
robot: $SCEN/../models/gpm2002.yaml
seed: 5
actual: {perturb: {base_mm: 0.3, link_mm: 0.3, offset_rad: 0.01, keep: [xa1, ya1, xa2, ya2]}}
encoder: {bits: 17, noise_rad: 0}
sampling: {pattern: disc, radius: 100, count: 20, move_speed_mm_s: 250}
$1
YAML
}

refused() {  # NAME KEY-FRAGMENT SCENARIO-TAIL
  base "$3" >"$tmp/s.yaml"
  check "$1" 2 "$GPM" run "$tmp/s.yaml" -o "$tmp/rundir"
  expect_err "$1 names the key" "$2"
  expect_err "$1 says why" "out of reach|outside its reach|singularity"
  holds "$1 wrote nothing" empty "$tmp/rundir"
}

refused "compensation.path out of reach" "s.yaml: compensation.path: point at t = " \
  "calibration: {cost: ml, fix: [xa1, ya1, xa2, ya2]}
compensation: {path: {shape: circle, centre: [216.5, 250], radius: 400, period_s: 4}}"
refused "compensation.poses out of reach" "s.yaml: compensation.poses: pose 1 \(900.0000, 900.0000\)" \
  "calibration: {cost: ml, fix: [xa1, ya1, xa2, ya2]}
compensation: {poses: [[216.5, 250], [900, 900]]}"
refused "reference_at out of reach" "s.yaml: calibration.reference_at: pose 0 \(900.0000, 900.0000\)" \
  "calibration: {cost: ml, fix: [xa1, ya1, xa2, ya2], start: reference, reference_at: [900, 900]}"

# robot: 42 is a file name that does not exist: named with the key.
base "calibration: {cost: ml}" | sed 's|^robot: .*|robot: 42|' >"$tmp/s.yaml"
check "robot: 42" 2 "$GPM" run "$tmp/s.yaml" -o "$tmp/rundir"
expect_err "robot: 42 names file and key" "s.yaml:[0-9]+: robot: no robot file .*42"
holds "robot: 42 wrote nothing" empty "$tmp/rundir"

# A result whose 1-sigma cannot be used: the monitor refuses it (it used to
# run blind, estimates NaN, PASSED).
cat >"$tmp/op.yaml" <<YAML
name: op
robot: $SCEN/../models/gpm2002.yaml
encoder: {bits: 17}
operation:
  path: {shape: circle, centre: [216.5, 250], radius: 40, period_s: 2}
  duration_s: 1
YAML
"$GPM" kin home >/dev/null  # the command line works at all
for bad in 1e300 .inf; do
  { sed -n '/^name:/,/^  dth3:/p' "$SCEN/../models/gpm2002.yaml"; echo "std: {la2: $bad}"; echo "fixed: [xa1, ya1, xa2, ya2]"; } >"$tmp/r.yaml"
  check "monitor with std $bad" 2 "$GPM" monitor "$tmp/op.yaml" --model "$tmp/r.yaml" -o "$tmp/mon"
  expect_err "std $bad names the key" "r.yaml:[0-9]+: std.la2: a 1-sigma must be"
  holds "std $bad wrote nothing" empty "$tmp/mon"
done
finish
