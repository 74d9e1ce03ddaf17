#!/usr/bin/env bash
# Tests of app/cmd_design.cpp (gpm design, issue 10): the pose list is a
# scenario the twin accepts, every pose is reachable with the margins (checked
# with gpm kin ik), the comparison files, one-line errors, no partial output.
set -u
GPM="$1"
source "$(dirname "$0")/cli_lib.sh"
expect() {  # name, condition (shell test)
  if eval "$2"; then passed=$((passed+1)); else echo "FAIL $1: $2"; fail=$((fail+1)); fi
}

check help 0 "$GPM" --help
expect "help lists design" "grep -qE '^  design' '$tmp/out'"

# A small design: 12 poses on a 10 mm grid.
check design 0 "$GPM" design --count 12 --sigma 1e-4 --grid-step 10 -o "$tmp/poses.yaml"
expect "summary" "grep -qE '^optimised +worst [0-9.e+-]+ mm' '$tmp/out'"
expect "header comment" "head -1 '$tmp/poses.yaml' | grep -q '^# gpm design: 12 poses, criterion worst'"
expect "sampling block" "grep -qx 'sampling:' '$tmp/poses.yaml' && grep -qx '  pattern: list' '$tmp/poses.yaml'"
expect "12 poses" "[[ \$(grep -cE '^    - \[[0-9.e+-]+, [0-9.e+-]+\]$' '$tmp/poses.yaml') -eq 12 ]]"
# Every pose reachable with the margins, by the independent gpm kin ik.
while read -r x y; do
  check "kin ik $x $y" 0 "$GPM" kin ik "$x" "$y"
  expect "pose $x $y inside" "grep -q 'inside, with margins' '$tmp/out'"
done < <(sed -nE 's/^    - \[([^,]+), ([^]]+)\]$/\1 \2/p' "$tmp/poses.yaml")
# The file is a scenario: the twin samples exactly these poses.
check "simulate the poses" 0 "$GPM" simulate "$tmp/poses.yaml" -o "$tmp/sim"
expect "12 samples" "[[ \$(( \$(wc -l <'$tmp/sim/samples.csv') - 1 )) -eq 12 ]]"

check "d criterion" 0 "$GPM" design --count 12 --criterion d --grid-step 10 -o "$tmp/poses_d.yaml"
expect "d header" "head -1 '$tmp/poses_d.yaml' | grep -q 'criterion d'"

# Comparison folder.
check compare 0 "$GPM" design --compare --count 20 --grid-step 10 -o "$tmp/cmp"
for f in design_comparison.md design_comparison.csv design_comparison.svg design_layouts.svg optimised_poses.yaml; do
  expect "compare wrote $f" "[[ -s '$tmp/cmp/$f' ]]"
done
expect "csv rows" "[[ \$(wc -l <'$tmp/cmp/design_comparison.csv') -eq 6 ]]"
expect "csv header" "head -1 '$tmp/cmp/design_comparison.csv' | grep -q '^layout,poses,worst_mm,worst_param,mean_mm,log_det,xa3_mm'"
expect "md table" "grep -q '^| optimised |' '$tmp/cmp/design_comparison.md'"
expect "no temporary left" "[[ -z \$(ls -A '$tmp/cmp' | grep -E 'tmp') ]]"

# Issue 18.3: --json is one document: the pose list file's content (exact
# numbers) and the design's bounds; --compare --json is the comparison CSV.
check "design json" 0 "$GPM" design --count 12 --sigma 1e-4 --grid-step 10 --json -o "$tmp/poses_j.yaml"
python3 - "$tmp/out" "$tmp/poses_j.yaml" "$tmp/poses.yaml" <<'PY' && passed=$((passed+1)) || { echo "FAIL design json"; fail=$((fail+1)); }
import json, re, sys
j = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
poses = [[float(a), float(b)] for a, b in re.findall(r"^    - \[([^,]+), ([^]]+)\]$", text, re.M)]
assert j["sampling"]["pattern"] == "list" and j["sampling"]["poses"] == poses and len(poses) == 12
assert open(sys.argv[3]).read() == text  # --json changes the output, not the design
d = j["design"]
assert d["poses"] == 12 and d["criterion"] == "worst" and d["sigma_rad"] == 1e-4
assert d["free"] == ["xa3", "ya3", "la1", "la2", "la3", "lb1", "lb2", "lb3", "dth1", "dth2", "dth3"]
b = d["bounds"]
assert len(b["parameters_mm"]) == 11 and b["worst_mm"] == max(b["parameters_mm"].values())
assert b["parameters_mm"][b["worst_param"]] == b["worst_mm"]
assert abs(b["mean_mm"] - sum(b["parameters_mm"].values()) / 11) < 1e-12 * b["worst_mm"] * 11
m = re.search(r"worst ([0-9.e+-]+) mm \((\w+)\)", text.splitlines()[3])  # the file's comment
assert m and abs(float(m.group(1)) - b["worst_mm"]) < 1e-3 * b["worst_mm"] and m.group(2) == b["worst_param"]
assert d["start_bounds"]["worst_mm"] >= b["worst_mm"]
PY
check "compare json" 0 "$GPM" design --compare --count 20 --grid-step 10 --json -o "$tmp/cmp_j"
python3 - "$tmp/out" "$tmp/cmp_j/design_comparison.csv" "$tmp/cmp_j/optimised_poses.yaml" <<'PY' && passed=$((passed+1)) || { echo "FAIL compare json"; fail=$((fail+1)); }
import csv, json, math, re, sys
same = lambda v, t: v == float(t) if v is not None else not math.isfinite(float(t))  # null: inf or nan
j = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[2])))
assert [l["layout"] for l in j["layouts"]] == [r["layout"] for r in rows]
for l, r in zip(j["layouts"], rows):
    assert len(l["poses"]) == int(r["poses"])
    for key in ("worst_mm", "mean_mm", "log_det"):
        assert same(l[key], r[key]), (key, l[key], r[key])
    assert l["worst_param"] == r["worst_param"]
    for name, v in l["parameters_mm"].items():
        assert same(v, r[name + "_mm"]), name
opt = [[float(a), float(b)] for a, b in re.findall(r"^    - \[([^,]+), ([^]]+)\]$", open(sys.argv[3]).read(), re.M)]
assert j["layouts"][-1]["layout"] == "optimised" and j["layouts"][-1]["poses"] == opt
others = min(math.inf if l["worst_mm"] is None else l["worst_mm"] for l in j["layouts"][:-1])
assert abs(j["improvement_over_best_other"] - others / j["layouts"][-1]["worst_mm"]) < 1e-9 * j["improvement_over_best_other"]
PY

# Bad input: exit 2, one line naming the flag, no output file.
check "too few poses" 2 "$GPM" design --count 5 --grid-step 10 -o "$tmp/bad.yaml"
expect_err "too few message" "5 poses cannot identify 11 free parameters"
check "bad sigma" 2 "$GPM" design --sigma -1 -o "$tmp/bad.yaml"
expect_err "sigma message" "^gpm: error: --sigma: must be a number from 1e-12 to 1 rad, got"
check "bad criterion" 2 "$GPM" design --criterion a -o "$tmp/bad.yaml"
expect_err "criterion message" "--criterion: 'a' is not d, worst or positioning"
check "bad fix" 2 "$GPM" design --fix xa1,bogus -o "$tmp/bad.yaml"
expect_err "fix message" "--fix"
check "gauge not fixed" 2 "$GPM" design --fix xa1 --grid-step 10 -o "$tmp/bad.yaml"
expect_err "gauge message" "cannot be identified from any poses"
check "bad grid" 2 "$GPM" design --grid-step 0 -o "$tmp/bad.yaml"
expect_err "grid message" "--grid-step"
# Work and memory bounded before any work (issue 36.8): a grid of 1e-9 mm
# would hold about 1e23 candidates, a count of 1e9 as many poses.
check "tiny grid" 2 "$GPM" design --grid-step 1e-9 -o "$tmp/bad.yaml"
expect_err "tiny grid message" "--grid-step: must be a number from 1 to 100 mm, got"
check "huge count" 2 "$GPM" design --count 1000000000 -o "$tmp/bad.yaml"
expect_err "huge count message" "--count: must be a whole number from 1 to"
check "nan guard" 2 "$GPM" design --guard nan -o "$tmp/bad.yaml"
check "missing model" 2 "$GPM" design --model /nonexistent.yaml -o "$tmp/bad.yaml"
expect_err "model message" "/nonexistent.yaml: cannot open file"
check "unwritable output" 2 "$GPM" design --count 12 --grid-step 10 -o /nonexistent/dir/poses.yaml
expect "no partial output" "[[ ! -e '$tmp/bad.yaml' ]]"

finish
