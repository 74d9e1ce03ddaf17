#!/usr/bin/env bash
# Tests of app/cmd_calibrate.cpp on gpm run's own samples (one calibration
# for every entry point, run/calibration_procedure.hpp): gpm calibrate on the
# samples.csv of a short on-the-fly run gives gpm run's geometry to the last
# digit and its model test, on a geared robot too (the offsets stated at
# home); a file without the time and torque columns gets
# the static fit and a model test; a bad value in the new columns: one line, exit 2.
set -u
GPM="$1"; SRC="$2"
source "$(dirname "$0")/cli_lib.sh"

check "gpm run" 0 "$GPM" run "$SRC/tests/fixtures/on_the_fly_small.yaml" -o "$tmp/run"
S="$tmp/run/samples.csv"
# gpm run's model test line says what summary.json's figures mean, as the
# report does (report::model_test_verdict): passed; or the scatter
# sqrt(chi2/dof), and whether the stated 1-sigma accounts for it
# (positioning normalised RMS at most 1.5).
cp "$tmp/out" "$tmp/run_out.txt"
holds "gpm run's model test line" python3 - "$tmp/run/summary.json" "$tmp/run_out.txt" <<'PY'
import json, math, re, sys
s = json.load(open(sys.argv[1]))
t, p = s["model_test"], s["positioning_um"]["normalised_rms"]
line = next(l for l in open(sys.argv[2]) if l.startswith("model test "))
def sig(v):
    whole = math.floor(math.log10(abs(v))) + 1
    return f"{v:.{max(0, 2 - whole)}f}"
if t["passed"]:
    want = "the residuals are as small as the encoders explain"
elif p <= 1.5:
    want = (f"the readings scatter {sig(math.sqrt(t['chi2'] / t['dof']))}x the encoders' 1-sigma; the stated 1-sigma "
            f"accounts for it (positioning error {sig(p)}x the stated 1-sigma)")
else:
    want = f"the stated 1-sigma understates the error (positioning error {sig(p)}x it"
ok = want in line and "fails" not in line
print("" if ok else f"line {line!r}, want {want!r}")
sys.exit(0 if ok else 1)
PY
holds "samples.csv has t" grep -qE '^sample,.*,tau_between3,t$' "$S"

check "calibrate on the run's samples" 0 "$GPM" calibrate --data "$S" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml"
expect_out "the motion model" "the motion model"
expect_out "model test line" "^model test (passes|fails) \(chi2/dof"
# The positioning 1-sigma and its carried share, as gpm run states them (its
# own sensitivities at the calibrated model instead of the actual robot's:
# equal to the printed digits on this robot).
holds "positioning 1-sigma as gpm run's" python3 - "$tmp/run/summary.json" "$tmp/out" <<'PY'
import json, re, sys
p = json.load(open(sys.argv[1]))["positioning_um"]
line = next(l for l in open(sys.argv[2]) if l.startswith("positioning over the 80 mm disc"))
# The main job's encoders turn with the joints: their error once per joint
# revolution is estimated, nothing carried, and the line names no share.
m = re.search(r"stated 1-sigma ([0-9.]+) um per axis(, ([0-9.]+) um of it the error once per joint revolution)?", line)
carried = m and (m.group(3) or "0.00")
ok = m and m.group(1) == f"{p['stated_sigma_rms']:.2f}" and carried == f"{p['carried_sigma_rms']:.2f}"
print("" if ok else f"line {line!r}, gpm run's {p}")
sys.exit(0 if ok else 1)
PY
# On a UTF-8 terminal (a pty) the line and the notes say χ²; in the C locale chi2.
if command -v script >/dev/null; then
  LC_ALL= LC_CTYPE= LANG=C.UTF-8 script -qec "'$GPM' calibrate --data '$S' --model '$SRC/models/gpm2002.yaml' -o '$tmp/r.yaml'" /dev/null >"$tmp/out"
  expect_out "model test line in UTF-8" "^model test (passes|fails) \(χ²/dof"
  holds "no chi2 on a UTF-8 terminal" bash -c "! grep -q 'chi2' '$tmp/out'"
  LC_ALL=C script -qec "'$GPM' calibrate --data '$S' --model '$SRC/models/gpm2002.yaml' -o '$tmp/r.yaml'" /dev/null >"$tmp/out"
  expect_out "model test line in the C locale" "^model test (passes|fails) \(chi2/dof"
fi
geometry() { awk '/^geometry:/{on=1; next} /^[^ ]/{on=0} on' "$1"; }
holds "geometry bit for bit" cmp <(geometry "$tmp/run/calibration.yaml") <(geometry "$tmp/r.yaml")
holds "model test as gpm run's" python3 - "$tmp/run/summary.json" "$tmp/r.yaml" <<'PY'
import json, re, sys
run = json.load(open(sys.argv[1]))["model_test"]
text = open(sys.argv[2]).read()
chi2 = float(re.search(r"^  model_test_chi2: (\S+)$", text, re.M).group(1))
dof = float(re.search(r"^  model_test_dof: (\S+)$", text, re.M).group(1))
passed = re.search(r"^  model_test_passed: (\S+)$", text, re.M).group(1) == "true"
sys.exit(0 if (chi2, dof, passed) == (run["chi2"], run["dof"], run["passed"]) else 1)
PY
check "calibrate --json" 0 "$GPM" calibrate --data "$S" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml" --json
holds "json has the model test" python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if "model_test_chi2_per_dof" in d["diagnostics"] else 1)' "$tmp/out"
check "result as --model (still a robot file)" 0 "$GPM" kin home --model "$tmp/r.yaml"

# Without the time and torque columns (an old file): the static model, and its model test.
cut -d, -f1-6 "$S" >"$tmp/old.csv"
check "old file" 0 "$GPM" calibrate --data "$tmp/old.csv" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml"
expect_out "static model" "the static model"
expect_out "static model test fails and says so" "^model test fails \(chi2/dof [0-9.e+]+, p [0-9.e+-]+\): the readings scatter"
check "--static" 0 "$GPM" calibrate --data "$S" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml" --static --sigma 1e-5
expect_out "--static: static model" "the static model"
expect_out "stated sigma understated" "^model test fails .*: the stated 1-sigma understates the error"

# A geared robot whose reducers err twice per motor revolution: both state
# the encoder offsets at home (calib/home_reference.hpp), to the last digit.
check "gpm run, geared" 0 "$GPM" run "$SRC/tests/fixtures/on_the_fly_geared_small.yaml" -o "$tmp/geared"
check "calibrate on the geared run's samples" 0 "$GPM" calibrate --data "$tmp/geared/samples.csv" \
  --model "$SRC/models/gpm2002.yaml" -o "$tmp/g.yaml"
for f in "$tmp/geared/calibration.yaml" "$tmp/g.yaml"; do
  holds "offsets at home in $(basename "$f")" grep -q "encoder offsets stated at home" "$f"
done
holds "geared geometry bit for bit" cmp <(geometry "$tmp/geared/calibration.yaml") <(geometry "$tmp/g.yaml")
# A bad value in the new columns: one line naming file, line and column, exit 2, nothing written.
awk -F, 'BEGIN{OFS=","} NR==5{$NF="0.x"} {print}' "$S" >"$tmp/bad_t.csv"
rm -f "$tmp/r.yaml"
check "bad t" 2 "$GPM" calibrate --data "$tmp/bad_t.csv" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml"
expect_err "bad t message" "bad_t.csv:5: column 't': '0.x' is not a number"
holds "nothing written" test ! -e "$tmp/r.yaml"
awk -F, 'BEGIN{OFS=","} NR==1{for(i=1;i<=NF;i++) if($i=="tau_last2") c=i} NR==7{$c="nan"} {print}' "$S" >"$tmp/bad_tau.csv"
check "bad tau_last" 2 "$GPM" calibrate --data "$tmp/bad_tau.csv" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml"
expect_err "bad tau_last message" "bad_tau.csv:7: column 'tau_last2': value must be finite"
awk -F, 'BEGIN{OFS=","} NR==9{$NF="0"} {print}' "$S" >"$tmp/back_t.csv"
check "t going back" 2 "$GPM" calibrate --data "$tmp/back_t.csv" --model "$SRC/models/gpm2002.yaml" -o "$tmp/r.yaml"
expect_err "t going back message" "back_t.csv:9: column 't': 0 s does not follow"
check "bad --encoder-bits" 2 "$GPM" calibrate --data "$S" --encoder-bits 41 -o "$tmp/r.yaml"

finish
