#!/usr/bin/env bash
# Tests of app/cmd_kin.cpp and app/main.cpp: subcommands listed, kin works,
# bad input exits 2 with exactly one line on stderr.
set -u
GPM="$1"
source "$(dirname "$0")/cli_lib.sh"

check help 0 "$GPM" --help
for sub in kin simulate calibrate run render; do expect_out "help lists $sub" "^  $sub"; done

check home 0 "$GPM" kin home
expect_out "home angles" "theta_a \(rad\) +1\.11113[0-9]* +3\.11068[0-9]* +4\.82485[0-9]*"
expect_out "home position" "x = 216\.500000 mm, y = 250\.000000 mm"

check ik 0 "$GPM" kin ik 230 260
expect_out "ik workspace" "inside, with margins"

# fk of the home angles returns home
read -r t1 t2 t3 < <("$GPM" kin home | awk '/^theta_a/ {print $3, $4, $5}')
check fk 0 "$GPM" kin fk "$t1" "$t2" "$t3"
expect_out "fk home" "x = (216\.50000[0-9]|216\.49999[0-9]) mm, y = (250\.00000[0-9]|249\.99999[0-9]) mm"

check "ik out of reach" 2 "$GPM" kin ik 216.5 750
expect_err "reach message" "chain 1: target .* out of reach by [0-9.]+ mm"
check "no subcommand" 2 "$GPM"
check "unknown option" 2 "$GPM" kin ik 1 2 --bogus
check "missing model" 2 "$GPM" kin home --model /nonexistent.yaml
expect_err "missing model message" "/nonexistent.yaml: cannot open file"
printf 'name: x\ngeometry: {xa1: 0}\n' >"$tmp/bad.yaml"
check "bad model" 2 "$GPM" kin home --model "$tmp/bad.yaml"
expect_err "bad model key" "missing key 'ya1'"

# Issue 18.2: a calibration result file is a robot file (--model).
check "study samples" 0 "$GPM" study samples --actual table5 --n 30 --radius 80 --seed 3 -o "$tmp/s.csv"
check "calibrate" 0 "$GPM" calibrate --data "$tmp/s.csv" -o "$tmp/result.yaml"
check "kin home result model" 0 "$GPM" kin home --model "$tmp/result.yaml"
la1=$(awk '/^  la1:/ {print $2; exit}' "$tmp/result.yaml")
check "kin ik result model json" 0 "$GPM" kin ik 230 260 --model "$tmp/result.yaml" --json
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["workspace"]["inside"] is True' "$tmp/out" \
  && passed=$((passed+1)) || { echo "FAIL result model used"; fail=$((fail+1)); }
# the calibrated geometry is the one used: its home angles differ from the nominal ones
"$GPM" kin home --model "$tmp/result.yaml" | grep '^theta_a' >"$tmp/a1"
"$GPM" kin home | grep '^theta_a' >"$tmp/a0"
[[ -n "$la1" ]] && ! cmp -s "$tmp/a0" "$tmp/a1" && passed=$((passed+1)) || { echo "FAIL result geometry not used"; fail=$((fail+1)); }
sed 's/^  rank: .*/  rank: eleven/' "$tmp/result.yaml" >"$tmp/bad_result.yaml"
check "bad result diagnostics" 2 "$GPM" kin home --model "$tmp/bad_result.yaml"
expect_err "bad result message" "bad_result.yaml:[0-9]+: diagnostics.rank"

# Issue 14.14: non-finite numbers are refused (exit 2, one line naming the argument).
for v in nan inf NaN 1e999; do
  check "ik $v" 2 "$GPM" kin ik "$v" 250
  expect_err "ik $v message" "xy: must be a finite number, got '$v'"
done
check "fk nan" 2 "$GPM" kin fk 1 nan 2
expect_err "fk nan message" "angles: must be a finite number, got 'nan'"

# Issue 18.3: --json is one JSON document with the text output's numbers.
check "ik json" 0 "$GPM" kin ik 230 260 --json
cp "$tmp/out" "$tmp/ik.json"
check "ik text" 0 "$GPM" kin ik 230 260
python3 - "$tmp/ik.json" "$tmp/out" <<'PY' && passed=$((passed+1)) || { echo "FAIL ik json matches text"; fail=$((fail+1)); }
import json, re, sys
j = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
row = lambda name: [float(v) for v in re.search(name + r" +(\S+) +(\S+) +(\S+)", text).groups()]
assert j["robot"] == "GPM2002"
assert j["end_effector_mm"] == {"x": 230, "y": 260}
for key, name in (("theta_a_rad", r"theta_a \(rad\)"), ("theta_b_rad", r"theta_b \(rad\)"), ("theta_m_rad", r"theta_m \(rad\)")):
    assert all(abs(a - b) < 1e-9 for a, b in zip(j[key], row(name))), key
assert all(abs(a - b) < 1e-4 for a, b in zip(j["transmission"], row("transmission")))
assert abs(j["passive_spread"] - float(re.search(r"passive spread +(\S+)", text).group(1))) < 1e-4
assert 0.0 <= j["passive_spread"] <= 1.0
assert abs(j["jacobian_condition"] - float(re.search(r"cond\(J\) +(\S+)", text).group(1))) < 1e-4
assert j["workspace"] == {"inside": True, "reason": ""}
PY
check "fk json" 0 "$GPM" kin fk "$t1" "$t2" "$t3" --json
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert abs(j["end_effector_mm"]["x"]-216.5)<1e-6 and abs(j["closure_mm2"])<1e-4' "$tmp/out" \
  && passed=$((passed+1)) || { echo "FAIL fk json"; fail=$((fail+1)); }
check "ik json outside margins" 0 "$GPM" kin ik 487 250 --json
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["workspace"]["inside"] is False and j["workspace"]["reason"]' "$tmp/out" \
  && passed=$((passed+1)) || { echo "FAIL json outside"; fail=$((fail+1)); }

finish
