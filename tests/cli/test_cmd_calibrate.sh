#!/usr/bin/env bash
# Tests of app/cmd_calibrate.cpp (and gpm study samples for the data): exit
# codes 0/1/2, one-line errors naming file, line or key, no result file left
# behind on failure, warnings on stderr, the rank-deficient gauge refused and
# solved on request, the reference-point start.
set -u
GPM="$1"
fail=0; passed=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

check() {  # name, expected exit, command...
  local name=$1 want=$2; shift 2
  rm -f "$tmp/r.yaml"
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [[ $got -ne $want ]]; then
    echo "FAIL $name: exit $got, want $want"; cat "$tmp/err"; fail=$((fail+1)); return 1
  fi
  if [[ $want -eq 2 && $(wc -l <"$tmp/err") -ne 1 ]]; then
    echo "FAIL $name: stderr is not one line:"; cat "$tmp/err"; fail=$((fail+1)); return 1
  fi
  if [[ $want -eq 2 && -e "$tmp/r.yaml" ]]; then
    echo "FAIL $name: result file left behind"; fail=$((fail+1)); return 1
  fi
  passed=$((passed+1))
}
expect() {  # name, file, pattern
  if grep -qE -- "$3" "$2"; then passed=$((passed+1)); else echo "FAIL $1: no '$3' in:"; cat "$2"; fail=$((fail+1)); fi
}
no_tmp_files() {
  if ls "$tmp" | grep -q '\.tmp'; then echo "FAIL $1: temporary file left"; fail=$((fail+1)); else passed=$((passed+1)); fi
}

# The robot of paper Table 5 with its true fixed coordinates (ya2 = 0.3) and
# nominal values for the rest: the start of the calibration.
cat >"$tmp/start.yaml" <<'YAML'
name: GPM2002
geometry: {xa1: 0, ya1: 250, xa2: 433, ya2: 0.3, xa3: 433, ya3: 500, la1: 244, la2: 244, la3: 244,
           lb1: 244, lb2: 244, lb3: 244, dth1: 0, dth2: 0, dth3: 0}
YAML
check "study samples" 0 "$GPM" study samples --actual table5 --n 50 --radius 80 --seed 3 -o "$tmp/s.csv"

check "calibrate ok" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o "$tmp/r.yaml"
for key in "^geometry:" "^  dth3: " "^std:" "^  xa3: " "^fixed: \[xa1, ya1, xa2, ya2\]" "^diagnostics:" \
           "^  cost: " "^  iterations: [0-9]+" "^  evaluations: [0-9]+" "^  rank: 11" "^  condition_number: " \
           "^  kmrmse_mm: [0-9.e-]+" "^  seconds: " "^  cost_function: ml" "^  converged: true"; do
  expect "result has $key" "$tmp/r.yaml" "$key"
done
expect "la3 recovered" "$tmp/r.yaml" "^  la3: 243\.(5000|4999)"
expect "kmrmse tiny" "$tmp/r.yaml" "^  kmrmse_mm: [0-9.]+e-(0[7-9]|1[0-9])"
no_tmp_files "calibrate ok"

for c in j1 j2 j3; do
  check "cost $c" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --cost $c -o "$tmp/r.yaml"
  expect "cost $c la3" "$tmp/r.yaml" "^  la3: 243\.(5000|4999)"
done

# Global methods (paper section 4): DE on J3 inside the Table 5 box, and DE then LM.
check "method de j3" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --method de --cost j3 \
  --budget 900000 --seed 4 -o "$tmp/r.yaml"
expect "de la3" "$tmp/r.yaml" "^  la3: 243\.(5000|4999)"
expect "de method" "$tmp/r.yaml" "^  method: \"?de\"?$"
check "method de+lm ml" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --method de+lm \
  --budget 30000 --seed 4 -o "$tmp/r.yaml"
expect "de+lm la3" "$tmp/r.yaml" "^  la3: 243\.(5000|4999)"
check "method pso j2" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --method pso --cost j2 \
  --budget 20000 --seed 4 -o "$tmp/r.yaml"
expect "pso evaluations within budget" "$tmp/r.yaml" "^  evaluations: (1?[0-9]{1,4}|20000)$"

# Reference-point start (section 3.2 step 3): readings at home of the actual robot.
check "reference start" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" \
  --reference-reading 1.10,3.12,4.81 -o "$tmp/r.yaml"
expect "reference start dth1" "$tmp/r.yaml" "^  dth1: 0\.0(0999|1000)"
check "bad reference reading" 2 "$GPM" calibrate --data "$tmp/s.csv" --reference-reading 1.1,x,3 -o "$tmp/r.yaml"
expect "bad reference message" "$tmp/err" "--reference-reading: 'x' is not a finite number"

# Rank-deficient gauge (paper section 3: xa1, ya1, ya2 fixed).
check "rank deficient refused" 2 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --fix xa1,ya1,ya2 -o "$tmp/r.yaml"
expect "rank message" "$tmp/err" "rank 11 of 12.*scale and rotation about A1: all lengths grow together, all offsets shift together.*fix xa2"
check "rank deficient allowed" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --fix xa1,ya1,ya2 \
  --allow-rank-deficient -o "$tmp/r.yaml"
expect "allowed says so" "$tmp/r.yaml" "^  rank_deficient: true"
expect "allowed note" "$tmp/r.yaml" "minimum-norm"
expect "allowed warns" "$tmp/err" "^gpm: warning: rank-deficient"

# Poorly exciting samples: all on a line -> a warning with the number, exit 0.
{ echo "sample,theta_m1,theta_m2,theta_m3"; } >"$tmp/line.csv"
for j in $(seq 0 29); do
  x=$(awk -v j=$j 'BEGIN{printf "%.3f", 160 + 4*j}')
  "$GPM" kin ik "$x" 250 --model "$tmp/start.yaml" | awk -v j=$j '/^theta_m/ {print j "," $3 "," $4 "," $5}' >>"$tmp/line.csv"
done
check "line samples" 0 "$GPM" calibrate --data "$tmp/line.csv" --model "$tmp/start.yaml" --cost ml -o "$tmp/r.yaml"
expect "line warning" "$tmp/err" "^gpm: warning: poorly exciting samples: condition number [0-9.e+]+"

# Not converged within the budget -> exit 1 (the result says so).
check "budget 1" 1 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --budget 1 -o "$tmp/r.yaml"
expect "not converged" "$tmp/r.yaml" "^  converged: false"

# Issue 18.3: --json prints the result file's content as one JSON document and
# nothing else; every value equals the file's (read here by a small reader of
# the result layout, independent of yaml-cpp), numbers exactly.
check "calibrate json" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --json -o "$tmp/r.yaml"
cp "$tmp/out" "$tmp/r.json"; cp "$tmp/r.yaml" "$tmp/r_json_run.yaml"
python3 - "$tmp/r.json" "$tmp/r_json_run.yaml" <<'PY' && passed=$((passed+1)) || { echo "FAIL calibrate json is the result file"; fail=$((fail+1)); }
import json, sys
j = json.load(open(sys.argv[1]))  # fails on any text around the document
def value(t):
    t = t.split(" #")[0].strip()
    if t.startswith('"'): return json.loads(t)
    if t in ("true", "false"): return t == "true"
    if t == "[]": return []
    if t.startswith("["): return [v.strip() for v in t[1:-1].split(",")]
    for kind in (int, float):
        try: return kind(t)
        except ValueError: pass
    return t
y, section = {}, None
for line in open(sys.argv[2]):
    if not line.strip() or line.startswith("#"): continue
    key, _, rest = line.strip().partition(":")
    if line.startswith("    - "): y[section]["notes"].append(json.loads(line.strip()[2:])); continue
    if not line.startswith(" "):
        section = key
        y[key] = {} if rest.split(" #")[0].strip() == "" else value(rest)
        if rest.strip() == "{}": y[key] = {}
    else:
        y[section][key] = [] if rest.strip() == "" else value(rest)
assert list(j) == ["name", "geometry", "std", "fixed", "diagnostics"], list(j)
assert len(j["geometry"]) == 15 and len(j["std"]) == 11
assert j == y, (j, y)
assert j["diagnostics"]["converged"] is True and j["diagnostics"]["rank"] == 11
PY
# The document reads back as a robot file (JSON is YAML): same home as the result file.
check "json as robot file" 0 "$GPM" kin home --model "$tmp/r.json"
cp "$tmp/out" "$tmp/home_json.txt"
check "yaml as robot file" 0 "$GPM" kin home --model "$tmp/r_json_run.yaml"
if cmp -s "$tmp/out" "$tmp/home_json.txt"; then passed=$((passed+1)); else echo "FAIL json result differs as a robot file"; fail=$((fail+1)); fi
# Issue 18.2: the result file is a robot file wherever one is read. As
# --model: calibrating again from it keeps its estimate. As a scenario's
# robot: and actual: the twin samples it (ideal encoders), and calibrating
# those samples from the start robot recovers the result's geometry.
check "result as --model" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/r_json_run.yaml" -o "$tmp/r.yaml"
cp "$tmp/r.yaml" "$tmp/r_again.yaml"
cat >"$tmp/sc.yaml" <<YAML
robot: r_json_run.yaml
actual: r_json_run.yaml
encoder: {bits: 0}   # ideal readings: the estimate is exact
sampling: {pattern: disc, centre: [216.5, 250], radius: 80, count: 30}
YAML
check "result as scenario robot" 0 "$GPM" simulate "$tmp/sc.yaml" -o "$tmp/sc_out"
check "calibrate scenario samples" 0 "$GPM" calibrate --data "$tmp/sc_out/samples.csv" --model "$tmp/start.yaml" --json -o "$tmp/r.yaml"
cp "$tmp/out" "$tmp/sc.json"
python3 - "$tmp/r.json" "$tmp/r_again.yaml" "$tmp/sc.json" <<'PY' && passed=$((passed+1)) || { echo "FAIL result file as robot file"; fail=$((fail+1)); }
import json, sys
first = json.load(open(sys.argv[1]))["geometry"]
text = open(sys.argv[2]).read()
block = text[text.index("\ngeometry:"):text.index("\nstd:")].splitlines()[2:]  # the geometry: map
again = {l.split(":")[0].strip(): float(l.split(":")[1]) for l in block}
twin = json.load(open(sys.argv[3]))["geometry"]
for k, v in first.items():
    tol = 1e-9 if k.startswith("dth") else 1e-7
    assert abs(again[k] - v) < tol, (k, again[k], v)
    assert abs(twin[k] - v) < 10 * tol, (k, twin[k], v)
PY

# Not converged: still one document (converged false), exit 1.
check "json budget 1" 1 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" --budget 1 --json -o "$tmp/r.yaml"
python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["diagnostics"]["converged"] is False' "$tmp/out" \
  && passed=$((passed+1)) || { echo "FAIL json not converged"; fail=$((fail+1)); }
# Bad input with --json: exit 2, one line on stderr, nothing on stdout.
check "json bad input" 2 "$GPM" calibrate --data "$tmp/none.csv" --json -o "$tmp/r.yaml"
if [[ ! -s "$tmp/out" ]]; then passed=$((passed+1)); else echo "FAIL json bad input wrote stdout"; fail=$((fail+1)); fi

# Bad input: exit 2, one line, no result file.
check "method de with ml" 2 "$GPM" calibrate --data "$tmp/s.csv" --method de -o "$tmp/r.yaml"
expect "method message" "$tmp/err" "--cost ml works with lm or de\+lm only"
check "method bogus" 2 "$GPM" calibrate --data "$tmp/s.csv" --method simplex -o "$tmp/r.yaml"
check "cost bogus" 2 "$GPM" calibrate --data "$tmp/s.csv" --cost j4 -o "$tmp/r.yaml"
expect "cost message" "$tmp/err" "--cost: 'j4' is not one of j1, j2, j3, ml"
check "unknown fix" 2 "$GPM" calibrate --data "$tmp/s.csv" --fix xa1,ya1,xb2 -o "$tmp/r.yaml"
expect "fix message" "$tmp/err" "--fix\[2\]: unknown parameter 'xb2'"
check "missing data" 2 "$GPM" calibrate --data "$tmp/none.csv" -o "$tmp/r.yaml"
check "missing -o" 2 "$GPM" calibrate --data "$tmp/s.csv"
head -8 "$tmp/s.csv" >"$tmp/few.csv"
check "too few samples" 2 "$GPM" calibrate --data "$tmp/few.csv" -o "$tmp/r.yaml"
expect "too few message" "$tmp/err" "7 samples for 11 free parameters"
sed 's/^3,\([^,]*\),/3,\1x,/' "$tmp/s.csv" >"$tmp/nan.csv"
check "non-numeric" 2 "$GPM" calibrate --data "$tmp/nan.csv" -o "$tmp/r.yaml"
expect "non-numeric message" "$tmp/err" "nan.csv:5: column 'theta_m1'"
sed 's/^3,\([^,]*\),[^,]*,/3,\1,inf,/' "$tmp/s.csv" >"$tmp/inf.csv"
check "non-finite" 2 "$GPM" calibrate --data "$tmp/inf.csv" -o "$tmp/r.yaml"
cut -d, -f1,2,3 "$tmp/s.csv" >"$tmp/cols.csv"
check "missing column" 2 "$GPM" calibrate --data "$tmp/cols.csv" -o "$tmp/r.yaml"
expect "missing column message" "$tmp/err" "missing column 'theta_m3'"
awk -F, 'BEGIN{OFS=","} NR==6 {$3 = $3 + 2.0} {print}' "$tmp/s.csv" >"$tmp/wild.csv"
check "circles do not meet" 2 "$GPM" calibrate --data "$tmp/wild.csv" --model "$tmp/start.yaml" -o "$tmp/r.yaml"
expect "circles message names the line" "$tmp/err" "wild.csv:6 \(sample 4\): the passive circles"
check "sigma negative" 2 "$GPM" calibrate --data "$tmp/s.csv" --sigma -1 -o "$tmp/r.yaml"
check "unwritable output" 2 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o "$tmp/nodir/r.yaml"
expect "unwritable message" "$tmp/err" "nodir/r.yaml: cannot write"

# Output policy (models/output_file.hpp): an input is never overwritten, a
# device is written in place (never replaced by a regular file), a symlink is
# followed.
cp "$tmp/s.csv" "$tmp/s_before.csv"
check "output is the data" 2 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o "$tmp/s.csv"
expect "input message" "$tmp/err" "s.csv: is also an input of this command"
if cmp -s "$tmp/s.csv" "$tmp/s_before.csv"; then passed=$((passed+1)); else echo "FAIL data overwritten"; fail=$((fail+1)); fi
check "output is the model" 2 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o "$tmp/start.yaml"
check "output to /dev/null" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o /dev/null
if [[ -c /dev/null ]]; then passed=$((passed+1)); else echo "FAIL /dev/null is no longer a device"; fail=$((fail+1)); fi
if [[ -c /dev/full ]]; then  # a full disk: the reason, never "Success"
  check "output to a full device" 2 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o /dev/full
  expect "full device message" "$tmp/err" "/dev/full: write failed \(disk full\?\)"
  if grep -q Success "$tmp/err"; then echo "FAIL 'Success' in an error"; fail=$((fail+1)); else passed=$((passed+1)); fi
fi
mkdir -p "$tmp/real"
ln -s real/r_target.yaml "$tmp/link.yaml"
check "output through a symlink" 0 "$GPM" calibrate --data "$tmp/s.csv" --model "$tmp/start.yaml" -o "$tmp/link.yaml"
if [[ -L "$tmp/link.yaml" && -s "$tmp/real/r_target.yaml" ]]; then passed=$((passed+1)); else echo "FAIL symlink not followed"; fail=$((fail+1)); fi
no_tmp_files "failures"

echo "$passed passed, $fail failed"
[[ $fail -eq 0 ]]
