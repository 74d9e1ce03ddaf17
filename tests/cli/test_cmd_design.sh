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

# Bad input: exit 2, one line naming the flag, no output file.
check "too few poses" 2 "$GPM" design --count 5 --grid-step 10 -o "$tmp/bad.yaml"
expect_err "too few message" "5 poses cannot identify 11 free parameters"
check "bad sigma" 2 "$GPM" design --sigma -1 -o "$tmp/bad.yaml"
expect_err "sigma message" "^gpm: error: --sigma: must be a positive"
check "bad criterion" 2 "$GPM" design --criterion a -o "$tmp/bad.yaml"
expect_err "criterion message" "--criterion: 'a' is not d or worst"
check "bad fix" 2 "$GPM" design --fix xa1,bogus -o "$tmp/bad.yaml"
expect_err "fix message" "--fix"
check "gauge not fixed" 2 "$GPM" design --fix xa1 --grid-step 10 -o "$tmp/bad.yaml"
expect_err "gauge message" "cannot be identified from any poses"
check "bad grid" 2 "$GPM" design --grid-step 0 -o "$tmp/bad.yaml"
expect_err "grid message" "--grid-step"
check "missing model" 2 "$GPM" design --model /nonexistent.yaml -o "$tmp/bad.yaml"
expect_err "model message" "/nonexistent.yaml: cannot open file"
check "unwritable output" 2 "$GPM" design --count 12 --grid-step 10 -o /nonexistent/dir/poses.yaml
expect "no partial output" "[[ ! -e '$tmp/bad.yaml' ]]"

finish
