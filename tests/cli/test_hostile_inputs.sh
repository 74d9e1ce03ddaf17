#!/usr/bin/env bash
# Hostile inputs (issue 36, items 1, 5, 8 and 12) against the command line:
# the documented bounds of models/bounds.hpp as checked by
# app/number_options.cpp and app/cmd_*.cpp (flags), run/run_spec.cpp and
# sim/scenario.cpp (scenario keys), models/samples.cpp (the CSV header),
# calib/sample_check.cpp (a joint that never moved), calib/robust_loss.cpp and
# calib/lm.cpp (loss scale, sigma), calib/result_yaml.cpp (the result is a
# robot file). One row per case: the command, its exit code, and a fragment of
# its single stderr line; nothing is left behind.
#   bash test_hostile_inputs.sh GPM SOURCE_DIR
set -u
GPM="$1"
SRC="$2"
source "$(dirname "$0")/cli_lib.sh"

# row NAME EXIT FRAGMENT CMD...: CMD exits EXIT (for 2 with one stderr line)
# and that line holds FRAGMENT (a fixed string).
row() {
  local name=$1 want=$2 fragment=$3; shift 3
  check "$name" "$want" "$@" || return 0
  [[ -z $fragment ]] && return 0
  if grep -qF -- "$fragment" "$tmp/err"; then passed=$((passed+1)); else
    echo "FAIL $name: no '$fragment' in:"; cat "$tmp/err"; fail=$((fail+1))
  fi
}

# Fixtures: 50 exact samples of the Table 5 robot; the same with theta_m1
# named twice; with theta_m1 constant; 11 samples (no residual left for a 1-sigma).
"$GPM" study samples --actual table5 --n 50 --radius 80 --seed 3 -o "$tmp/s.csv" >/dev/null
awk -F, 'BEGIN{OFS=","} {print $0, (NR == 1 ? "theta_m1" : $2)}' "$tmp/s.csv" >"$tmp/dup.csv"
awk -F, 'BEGIN{OFS=","} NR == 2 {v = $2} NR > 1 {$2 = v} {print}' "$tmp/s.csv" >"$tmp/const.csv"
"$GPM" study samples --actual table5 --n 11 --radius 80 --seed 3 -o "$tmp/s11.csv" >/dev/null
cal=("$GPM" calibrate --data "$tmp/s.csv" -o "$tmp/r.yaml")
mkfifo "$tmp/fifo"
truncate -s 65M "$tmp/big.csv"  # sparse

# A gpm run scenario with the calibration section $1; a monitor scenario with $1 events.
run_scenario() {
  printf 'robot: %s/models/gpm2002.yaml\nsampling: {pattern: disc, radius: 50, count: 12}\ncalibration: %s\n' \
    "$SRC" "$1" >"$tmp/sc.yaml"
}
monitor_scenario() {
  printf 'robot: %s/models/gpm2002.yaml\noperation:\n  path: {shape: circle, centre: [216.5, 250], radius: 60, period_s: 4}\n  duration_s: 60\nevents:\n' \
    "$SRC" >"$tmp/mon.yaml"
  for ((k = 0; k < $1; ++k)); do echo "  - {at_s: 30, change: {dth2: 1.0e-4}}"; done >>"$tmp/mon.yaml"
}

# --- 36.1: loss scale and sigma out of range (was SIGSEGV inside Ceres) ---
row "loss scale 1e-200" 2 "--loss: scale of 'cauchy:1e-200': must be a number from 1e-12 to 1e6" \
  "${cal[@]}" --loss cauchy:1e-200
row "loss scale 1e7" 2 "--loss: scale of 'huber:1e7': must be a number from 1e-12 to 1e6" "${cal[@]}" --loss huber:1e7
row "sigma 1e-300 with cauchy" 2 "--sigma: must be a number from 1e-12 to 1 rad, got '1e-300'" \
  "${cal[@]}" --sigma 1e-300 --loss cauchy
row "sigma 2 rad" 2 "--sigma: must be a number from 1e-12 to 1 rad, got '2'" "${cal[@]}" --sigma 2
run_scenario "{sigma: 1e-300, loss: cauchy}"
row "scenario sigma 1e-300" 2 "calibration.sigma: must be a number from 1e-12 to 1 rad, got 1e-300" \
  "$GPM" run "$tmp/sc.yaml" -o "$tmp/run"
run_scenario "{loss: 'cauchy:1e-200'}"
row "scenario loss scale 1e-200" 2 "calibration.loss: scale of 'cauchy:1e-200': must be a number from 1e-12 to 1e6" \
  "$GPM" run "$tmp/sc.yaml" -o "$tmp/run"
row "loss scale at its bound" 0 "" "$GPM" calibrate --data "$tmp/s.csv" -o "$tmp/ok.yaml" --loss cauchy:1e-12

# --- 36.5: samples that cannot determine the parameters; the result is a robot file ---
row "duplicate theta_m1 header" 2 "dup.csv:1: column 'theta_m1' appears twice in the header (fields 2 and 7)" \
  "$GPM" calibrate --data "$tmp/dup.csv" -o "$tmp/r.yaml"
row "constant theta_m1" 2 "in all 50 samples: joint 1 never moved" \
  "$GPM" calibrate --data "$tmp/const.csv" -o "$tmp/r.yaml"
row "no 1-sigma with 11 samples (json)" 0 "no 1-sigma" \
  "$GPM" calibrate --data "$tmp/s11.csv" --json -o "$tmp/r11.yaml"
holds "json result has no null std" bash -c "! grep -q null '$tmp/out'"
cp "$tmp/out" "$tmp/r11.json"
row "json result is a robot file" 0 "" "$GPM" kin home --model "$tmp/r11.json"
row "yaml result is a robot file" 0 "" "$GPM" kin home --model "$tmp/r11.yaml"

# --- 36.8: every count that sizes work or memory is bounded, before any work ---
row "compare budget 1e19" 2 "--budget: must be a whole number from 1 to 1e10 evaluations, got '1e19'" \
  "$GPM" compare -o "$tmp/cmp" --budget 1e19
row "compare samples 2e9" 2 "--samples: must be a whole number from 1 to 100000 samples, got '2000000000'" \
  "$GPM" compare -o "$tmp/cmp" --samples 2000000000
row "calibrate de budget 1e19" 2 "--budget: must be a whole number from 1 to 1e10 evaluations, got '1e19'" \
  "${cal[@]}" --method de --cost j3 --budget 1e19
row "calibrate lm budget 2e6" 2 "--budget: must be a whole number from 1 to 1e6 iterations, got '2000000'" \
  "${cal[@]}" --budget 2e6
run_scenario "{method: de, cost: j3, budget: 1e12}"
row "scenario budget 1e12" 2 "calibration.budget: must be a whole number from 1 to 1e10 evaluations, got 1e12" \
  "$GPM" run "$tmp/sc.yaml" -o "$tmp/run"
row "study samples n 1e9" 2 "--n: must be a whole number from 1 to 100000 samples, got '1e9'" \
  "$GPM" study samples --n 1e9 -o "$tmp/n.csv"
row "montecarlo trials 1e9" 2 "--trials: must be a whole number from 2 to 10000 trials, got '1e9'" \
  "$GPM" study montecarlo --trials 1e9
row "zero points 1e9" 2 "--points: must be a whole number from 6 to 3600 points, got '1e9'" \
  "$GPM" zero --hardware "$SRC/hw/examples/twin.yaml" --points 1e9
row "zero dwell 1e9" 2 "--dwell: must be a number from 0 to 60 s, got '1e9'" \
  "$GPM" zero --hardware "$SRC/hw/examples/twin.yaml" --dwell 1e9
row "effects count 1e6" 2 "--count: must be a whole number from 12 to 2000 poses" \
  "$GPM" study effects --count 1000000 -o "$tmp/eff"
monitor_scenario 1001
row "1001 events" 2 "events: 1001 events; at most 1000 in one scenario" "$GPM" monitor "$tmp/mon.yaml" -o "$tmp/mon"
row "model /dev/zero" 2 "/dev/zero: is a character device, not a regular file" "$GPM" kin home --model /dev/zero
row "data /dev/zero" 2 "/dev/zero: is a character device, not a regular file" \
  "$GPM" calibrate --data /dev/zero -o "$tmp/r.yaml"
row "data larger than 64 MiB" 2 "big.csv: larger than 64 MiB" "$GPM" calibrate --data "$tmp/big.csv" -o "$tmp/r.yaml"
# --- a FIFO as an input: refused at once (was: open(2) waited for a writer
# forever; timeout 60 stands in for forever, exit 124) ---
row "model is a FIFO" 2 "fifo: is a FIFO (named pipe), not a regular file" \
  timeout 60 "$GPM" kin home --model "$tmp/fifo"
row "data is a FIFO" 2 "fifo: is a FIFO (named pipe)" timeout 60 "$GPM" calibrate --data "$tmp/fifo" -o "$tmp/r.yaml"
row "scenario is a FIFO" 2 "fifo: is a FIFO (named pipe)" timeout 60 "$GPM" simulate "$tmp/fifo" -o "$tmp/simf"
row "hardware file is a FIFO" 2 "fifo: is a FIFO (named pipe)" \
  timeout 60 "$GPM" sample --hardware "$tmp/fifo" --poses "$tmp/fifo" -o "$tmp/sf.csv"
row "model is a folder" 2 "$tmp: is a folder, not a file" "$GPM" kin home --model "$tmp"

# --- 36.12: empty numbers, negative seeds, repeated list items ---
row "fk empty angle" 2 "angles: an empty argument is not a number" "$GPM" kin fk "" 3.11 4.82
row "ik empty coordinate" 2 "xy: an empty argument is not a number" "$GPM" kin ik 216.5 ""
row "calibrate empty sigma" 2 "--sigma: an empty argument is not a number" "${cal[@]}" --sigma ""
row "paper seed -1" 2 "--seed: must be a whole number from 0 to 9007199254740992, got '-1'" \
  "$GPM" paper -o "$tmp/paper" --seed -1
row "calibrate seed -1" 2 "--seed: must be a whole number from 0 to 9007199254740992, got '-1'" \
  "${cal[@]}" --method de --cost j3 --seed -1
row "design seed -1" 2 "--seed: must be a whole number from 0 to 9007199254740992, got '-1'" \
  "$GPM" design --compare --seed -1 -o "$tmp/design"
row "compare seeds repeated" 2 "--seeds: '1' is given twice (items 1 and 3); give each once" \
  "$GPM" compare -o "$tmp/cmp" --seeds 1,2,1
row "fix repeated" 2 "--fix[4]: 'xa1' is given twice; give each parameter once" \
  "${cal[@]}" --fix xa1,ya1,xa2,ya2,xa1
row "effects repeated" 2 "--effects: 'ideal' is given twice (items 1 and 2); give each once" \
  "$GPM" study effects --effects ideal,ideal -o "$tmp/eff"
row "montecarlo costs repeated" 2 "--costs: 'ml' is given twice (items 1 and 2); give each once" \
  "$GPM" study montecarlo --costs ml,ml
run_scenario "{fix: [xa1, ya1, xa2, ya2, ya2]}"
row "scenario fix repeated" 2 "calibration.fix[4]: 'ya2' is listed twice" "$GPM" run "$tmp/sc.yaml" -o "$tmp/run"
run_scenario "{estimate: [skew, skew]}"
row "scenario estimate repeated" 2 "calibration.estimate[1]: 'skew' is listed twice" \
  "$GPM" run "$tmp/sc.yaml" -o "$tmp/run"

# --- numbers are decimal; a long argument is not echoed whole (cut to 40 characters and "…") ---
row "fk hex angle" 2 "angles: must be a decimal number (digits, optional fraction and exponent: 12, -0.5, 1e6), got '0x1'" \
  "$GPM" kin fk 0x1 3.11 4.82
row "ik hex float" 2 "xy: must be a decimal number" "$GPM" kin ik 0x1p3 250
row "radius with digit separator" 2 "--radius: must be a decimal number" "$GPM" study samples --radius 1_0 -o "$tmp/n.csv"
row "budget hex" 2 "--budget: must be a whole number from 1 to 1e10 evaluations, got '0x10'" \
  "$GPM" paper -o "$tmp/paper" --budget 0x10
long=$(printf '9%.0s' {1..300})
row "300 digits, bounded flag" 2 "--n: must be a whole number from 1 to 100000 samples, got '$(printf '9%.0s' {1..40})…'" \
  "$GPM" study samples --n "$long" -o "$tmp/n.csv"
row "300 digits, plain int flag" 2 "--count = $(printf '9%.0s' {1..40})… (see gpm --help)" \
  "$GPM" design --count "$long" -o "$tmp/design"
row "300 letters as a number" 2 "got '$(printf 'x%.0s' {1..40})…'" "$GPM" kin fk "$(printf 'x%.0s' {1..300})" 0 0
row "300-character subcommand" 2 "unknown subcommand '$(printf 'k%.0s' {1..40})…' of gpm" "$GPM" "$(printf 'k%.0s' {1..300})"
holds "no error line echoes 300 characters" test "$(wc -c <"$tmp/err")" -lt 300

# Nothing a refused command could have made is left.
for f in r.yaml run cmp n.csv eff mon paper design; do
  holds "nothing left: $f" test ! -e "$tmp/$f"
done
finish
