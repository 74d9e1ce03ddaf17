#!/usr/bin/env bash
# Tests of app/cli_main.cpp (did you mean), app/cmd_help.cpp and app/data_files.cpp (gpm help, scenarios by
# library name), app/written_files.cpp (every file written is listed), app/progress_mode.cpp (--progress) and
# app/cli_text.cpp (µm on a UTF-8 terminal) through gpm (issue 35.5): a new user's first minutes.
#   bash test_cli_usability.sh GPM SOURCE_DIR
set -u
GPM="$1"
SRC="$2"
source "$(dirname "$0")/cli_lib.sh"

# --- did you mean: one line, exit 2, at every level ---
check "kin hom" 2 "$GPM" kin hom
expect_err "kin hom suggests home" "^gpm: error: unknown subcommand 'hom' of gpm kin; did you mean 'home'\? valid: home, ik, fk"
check "simulte" 2 "$GPM" simulte -o x
expect_err "simulte suggests simulate" "did you mean 'simulate'\?"
check "study sample" 2 "$GPM" study sample
expect_err "study sample suggests samples" "of gpm study; did you mean 'samples'\?"
check "xyzzy" 2 "$GPM" xyzzy
expect_err "xyzzy lists the subcommands" "unknown subcommand 'xyzzy' of gpm; valid: kin, simulate, calibrate, run"
check "kin alone" 2 "$GPM" kin
expect_err "kin alone names its subcommands" "^gpm: error: gpm kin: name a subcommand: home, ik, fk"
check "kin home still runs" 0 "$GPM" kin home

# --- gpm help: the installed documents (here the source tree's) ---
check "help" 0 "$GPM" help
expect_out "schema .*scenarios/SCHEMA.md\)$" "schema .*scenarios/SCHEMA.md\)$"
expect_out "formats .*docs/FORMATS.md\)$" "formats .*docs/FORMATS.md\)$"
check "help schema" 0 "$GPM" help schema
holds "help schema prints SCHEMA.md" cmp -s "$tmp/out" "$SRC/scenarios/SCHEMA.md"
check "help formats" 0 "$GPM" help formats
holds "help formats prints FORMATS.md" cmp -s "$tmp/out" "$SRC/docs/FORMATS.md"
check "help hardware" 0 "$GPM" help hardware
holds "help hardware prints hw/README.md" cmp -s "$tmp/out" "$SRC/hw/README.md"
check "help scenarios" 0 "$GPM" help scenarios
holds "help scenarios lists every library scenario" \
  test "$(grep -c '^  [a-z]' "$tmp/out")" -eq "$(ls "$SRC"/scenarios/*.yaml | wc -l)"
expect_out "^  main +" "^  main +"
check "help run" 0 "$GPM" help run
expect_out "writes DIR/summary.json" "writes DIR/summary.json"
check "help bogus" 2 "$GPM" help bogus
expect_err "help bogus lists topics" "gpm help: no topic 'bogus'; topics: scenarios, schema, formats"
GPM_DATA_DIR="$tmp/nowhere" check "help without the data" 2 "$GPM" help cli
expect_err "missing document named" "gpm help cli: .*nowhere/docs/CLI.md is missing"

# No help text points at the source tree, and the backends are twin, modbus, plugin.
helps=()
for c in "" kin "kin home" "kin ik" "kin fk" simulate calibrate run compare study "study samples" "study crb" \
  "study montecarlo" "study effects" "study population" design sample zero monitor paper help; do
  # shellcheck disable=SC2086
  "$GPM" $c --help >>"$tmp/helps" 2>&1
done
holds "help texts name no source-tree file" bash -c "! grep -nE 'scenarios/|[A-Z_]{3,}\.md|hw/examples|python/' '$tmp/helps'"
holds "help texts never say 'twin or modbus'" bash -c "! grep -n 'twin or modbus' '$tmp/helps'"
holds "four hardware flags name plugin" test "$(grep -c 'twin, modbus or plugin' "$tmp/helps")" -eq 4

# --- scenarios by name, from a working folder that has none ---
mkdir -p "$tmp/wd" && cd "$tmp/wd" || exit 1
check "simulate by name" 0 "$GPM" simulate simulate_disc -o sim --progress=none
expect_out "^scenario +simulate_disc$" "^scenario +simulate_disc$"
expect_out "^samples +30 \(each taken at rest\)$" "^samples +30 \(each taken at rest\)$"
holds "by name: no stderr" test ! -s "$tmp/err"
# Every file written is listed, and only those: the wrote lines are the folder.
holds "wrote lists the folder" diff <(sed -n 's/^wrote *//p' "$tmp/out" | sort) <(find sim -type f | sort)
touch -d '1 hour ago' sim/old.txt
check "simulate.yaml by name" 0 "$GPM" simulate simulate_disc.yaml -o sim --progress=none
holds "an older file is not listed" bash -c "! grep -q old.txt '$tmp/out'"
holds "the four outputs are listed again" test "$(grep -c '^wrote' "$tmp/out")" -eq 4
# A file of the working folder wins over the library.
sed "s|^name: .*|name: local_copy|; s|^robot: .*|robot: $SRC/models/gpm2002.yaml|" "$SRC/scenarios/simulate_disc.yaml" \
  >simulate_disc.yaml
check "local file first" 0 "$GPM" simulate simulate_disc.yaml -o sim2 --progress=none
expect_out "^scenario +local_copy$" "^scenario +local_copy$"
check "unknown name" 2 "$GPM" simulate simulat_disk -o sim3
expect_err "unknown name: did you mean" "scenario 'simulat_disk': no such file here nor in the scenario library .*; did you mean 'simulate_disc'\?"
expect_err "unknown name lists the library" "library names: .*, main, "
holds "unknown name wrote nothing" test ! -e sim3
# gpm run and gpm monitor resolve the name too (refused after the scenario is read: nothing runs).
check "run main.yaml by name" 2 "$GPM" run main.yaml -o run --resume
expect_err "run read the library's main.yaml" "give --hardware HW.yaml \(or hardware: in .*scenarios/main.yaml\)"
check "monitor by name" 2 "$GPM" monitor monitor_offset_jump -o mon --model "$tmp/none.yaml"
expect_err "monitor read the library's scenario, then the model" "none.yaml"
check "render by name" 2 "$GPM" render simulate_disc --frame-png 0:frame.jpg
expect_err "render read the library's scenario, then the suffix" "frame.jpg.*\.png"
check "a path is not looked up" 2 "$GPM" simulate ./main.yaml -o sim3
expect_err "a path names the file" "main.yaml: cannot open file"

# --- progress on stderr ---
check "progress none" 0 "$GPM" simulate simulate_disc -o sim4 --progress=none
holds "progress none: stderr empty" test ! -s "$tmp/err"
check "progress bad" 2 "$GPM" simulate simulate_disc -o sim4 --progress=sometimes
expect_err "progress bad names the choices" "--progress: sometimes not in \{none,line,bar\}"
# Not a terminal, no choice: the line mode, whose lines have no carriage return
# (its timing is tested with a fake clock: tests/cli/test_progress_mode.cpp).
check "progress default off a terminal" 0 "$GPM" simulate simulate_disc -o sim5
holds "line mode writes plain lines" bash -c "! grep -q $'\r' '$tmp/err'"

# --- wording: on the fly is not 'did not settle'; µm on a UTF-8 terminal only ---
sed "s|^robot: .*|robot: $SRC/models/gpm2002.yaml|; s/count: 30, /count: 12, /" "$SRC/scenarios/procedure_trajectory.yaml" \
  >traj.yaml
check "on the fly" 0 "$GPM" simulate traj.yaml -o traj --progress=none
expect_out "^samples +[0-9]+ \(taken on the fly along the excitation path\)$" "^samples +[0-9]+ \(taken on the fly along the excitation path\)$"
holds "no 'did not settle'" bash -c "! grep -q 'settle' '$tmp/out'"
expect_out "max gap [0-9.e+-]+ um$" "max gap [0-9.e+-]+ um$"  # a pipe: ASCII even with LANG=...UTF-8
if command -v script >/dev/null; then
  LC_ALL= LC_CTYPE= LANG=C.UTF-8 script -qec "'$GPM' simulate simulate_disc -o sim6 --progress=none" /dev/null >"$tmp/out"
  expect_out "max gap [0-9.e+-]+ µm" "max gap [0-9.e+-]+ µm"
  LC_ALL=C script -qec "'$GPM' simulate simulate_disc -o sim7 --progress=none" /dev/null >"$tmp/out"
  expect_out "max gap [0-9.e+-]+ um" "max gap [0-9.e+-]+ um"
fi
cd / && finish
