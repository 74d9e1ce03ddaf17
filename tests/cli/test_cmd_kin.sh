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

finish
