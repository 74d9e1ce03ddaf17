#!/usr/bin/env bash
# Tests of app/cmd_study.cpp (gpm study crb): the bound is refused, like gpm
# calibrate refuses the data, when the samples cannot identify the free
# parameters (never -nan); a good set gives finite positive bounds. gpm study
# population: bad input is one line and exit 2, with nothing written.
set -u
GPM="$1"
source "$(dirname "$0")/cli_lib.sh"

check "study samples" 0 "$GPM" study samples --actual table5 --n 20 --radius 80 --seed 3 -o "$tmp/s20.csv"
check "crb" 0 "$GPM" study crb --data "$tmp/s20.csv" --sigma 1e-4
expect_out "crb finite" "^dth3 +[0-9.]+(e-?[0-9]+)?$"
if grep -qi nan "$tmp/out"; then echo "FAIL crb prints nan"; fail=$((fail+1)); else passed=$((passed+1)); fi

# Issue 14.10: 3 samples (fewer than the 11 free parameters), as gpm calibrate.
head -4 "$tmp/s20.csv" >"$tmp/s3.csv"
check "crb 3 samples" 2 "$GPM" study crb --data "$tmp/s3.csv" --sigma 1e-4
expect_err "crb 3 samples message" "3 samples for 11 free parameters; need at least 11"
check "calibrate 3 samples" 2 "$GPM" calibrate --data "$tmp/s3.csv" -o "$tmp/r.yaml"
expect_err "calibrate 3 samples message" "3 samples for 11 free parameters; need at least 11"

# 20 copies of one sample: enough rows, rank 1.
# Twenty samples of one pose (ids 0..19: a sample id may appear once).
{ head -1 "$tmp/s20.csv"; for k in $(seq 0 19); do sed -n 2p "$tmp/s20.csv" | sed "s/^[^,]*,/$k,/"; done; } >"$tmp/same.csv"
check "crb coincident" 2 "$GPM" study crb --data "$tmp/same.csv" --sigma 1e-4
expect_err "crb coincident message" "are not identifiable from encoder angles \(rank 1 of 11\)"
[[ ! -s "$tmp/out" ]] && passed=$((passed+1)) || { echo "FAIL crb coincident printed a table"; fail=$((fail+1)); }
check "calibrate coincident" 2 "$GPM" calibrate --data "$tmp/same.csv" -o "$tmp/r.yaml"
expect_err "calibrate coincident message" "are not identifiable from encoder angles \(rank 1 of 11\)"

# gpm study population: bad input before any run, nothing written.
SMALL="$(dirname "$0")/../fixtures/population_small.yaml"
check "population count 0" 2 "$GPM" study population "$SMALL" -o "$tmp/pop" --count 0
expect_err "population count 0 message" "--count"
check "population missing scenario" 2 "$GPM" study population "$tmp/none.yaml" -o "$tmp/pop"
expect_err "population missing scenario message" "none.yaml"
check "population repeated seed" 2 "$GPM" study population "$SMALL" -o "$tmp/pop" --seeds 5,5
expect_err "population repeated seed message" "--seeds"
check "population bad seed" 2 "$GPM" study population "$SMALL" -o "$tmp/pop" --seeds 5,x
expect_err "population bad seed message" "--seeds"
check "population threads 0" 2 "$GPM" study population "$SMALL" -o "$tmp/pop" --threads 0
: >"$tmp/file"
check "population output is a file" 2 "$GPM" study population "$SMALL" -o "$tmp/file"
expect_err "population output is a file message" "not a folder"
printf 'name: x\nseed: 1\nhardware: twin.yaml\n' >"$tmp/hw.yaml"
check "population hardware scenario" 2 "$GPM" study population "$tmp/hw.yaml" -o "$tmp/pop"
expect_err "population hardware scenario message" "runs twins"
[[ ! -e "$tmp/pop" ]] && passed=$((passed+1)) || { echo "FAIL population left $tmp/pop"; fail=$((fail+1)); }

finish
