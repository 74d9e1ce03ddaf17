#!/usr/bin/env bash
# Tests of app/cmd_monitor.cpp with a calibration result as the model: gpm run
# writes the monitor's reading model into DIR/calibration.yaml (`monitor:`,
# run/run_spec.hpp monitor_reading_model_yaml), gpm monitor --model reads it
# (over the scenario's statement) and reports it in summary.json; the result
# stays a robot file; a bad value in it exits 2 with one line naming the file
# and key, and writes nothing.
set -u
GPM="$1"
SCEN="$(cd "$(dirname "$0")/../../scenarios" && pwd)"
source "$(dirname "$0")/cli_lib.sh"

# A short calibration on the ideal twin (stated reading model: ideal), and a
# short operation whose scenario states the data sheet's reading model.
cat >"$tmp/cal.yaml" <<YAML
name: cal
robot: $SCEN/../models/gpm2002.yaml
seed: 5
actual: {perturb: {base_mm: 0.3, link_mm: 0.3, offset_rad: 0.01, keep: [xa1, ya1, xa2, ya2]}}
encoder: {bits: 17, noise_rad: 0}
sampling: {pattern: disc, radius: 100, count: 20, move_speed_mm_s: 250}
calibration: {cost: ml, fix: [xa1, ya1, xa2, ya2]}
monitor: ideal
outputs: {compensation: false, report: false}
YAML
cat >"$tmp/op.yaml" <<YAML
name: op
robot: $SCEN/../models/gpm2002.yaml
encoder: {bits: 17}
monitor: data_sheet
operation:
  path: {shape: circle, centre: [216.5, 250], radius: 40, period_s: 2}
  duration_s: 1
YAML

check "run" 0 "$GPM" run "$tmp/cal.yaml" -o "$tmp/cal"
holds "result carries monitor:" grep -q '^monitor:' "$tmp/cal/calibration.yaml"
holds "ideal statement kept" grep -q '^  skew_s: \[0, 0, 0\]$' "$tmp/cal/calibration.yaml"
check "result is a robot file" 0 "$GPM" kin home --model "$tmp/cal/calibration.yaml"

# The result's reading model wins over the scenario's statement (data_sheet
# has skew 5e-05 s on encoder 2): an edited skew reaches the monitor.
sed 's/^  skew_s: .*/  skew_s: [0, 3.25e-05, -1.5e-05]/' "$tmp/cal/calibration.yaml" >"$tmp/result.yaml"
check "monitor --model" 0 "$GPM" monitor "$tmp/op.yaml" --model "$tmp/result.yaml" -o "$tmp/mon"
expect_out "names the result" "readings   noise model as the calibration estimated it \(monitor: in .*result.yaml\)"
flat() { tr -d ' \n' <"$1"; }
holds "summary has the result's skew" grep -q '"skew_s":\[0.0,3.25e-05,-1.5e-05\]' <(flat "$tmp/mon/summary.json")
check "monitor, robot file as model" 0 "$GPM" monitor "$tmp/op.yaml" --model "$SCEN/../models/gpm2002.yaml" -o "$tmp/mon2"
expect_out "names the scenario" "readings   noise model as stated under monitor: in .*op.yaml"
holds "summary has the statement's skew" grep -q '"skew_s":\[0.0,5e-05,0.0001\]' <(flat "$tmp/mon2/summary.json")

# A bad value in the result: exit 2, one line with the file and key, nothing written.
sed 's/^  skew_s: .*/  skew_s: [0, 0.5, 0]/' "$tmp/cal/calibration.yaml" >"$tmp/bad.yaml"
check "bad skew in result" 2 "$GPM" monitor "$tmp/op.yaml" --model "$tmp/bad.yaml" -o "$tmp/bad"
expect_err "file and key" "bad.yaml.*monitor.skew_s.*out of range"
holds "nothing written" test ! -e "$tmp/bad"
finish
