#!/usr/bin/env bash
# Hostile outputs against the output policy (docs/CLI.md "Output files"): the
# measured-data guard (models/measured_data.cpp, app/cmd_run.cpp), every input
# against every output by file identity (models/output_file.cpp and the
# commands: app/cmd_simulate.cpp, cmd_run.cpp, cmd_monitor.cpp, cmd_zero.cpp,
# cmd_sample.cpp), samples written to a device or FIFO and duplicate sample ids
# (hw/procedures/sample_log.cpp), everything checked before the robot moves
# (run/monitor_run.cpp, app/cmd_zero.cpp), the drive emulator's flags
# (hw/backends/emulator_main.cpp, drive_emulator.cpp), a full disk under gpm
# monitor --hardware (app/cmd_monitor.cpp: checked before moving, the
# record kept when the report cannot be written).
# One table, one row per case: the command, its exit code, a fragment of its
# one stderr line, and a file that must be byte-identical afterwards (- none).
# No wall-clock sleeps: a running session is stood in for by flock(1) holding
# the folder's lock, FIFOs and files are waited on with read -t / tail -F.
set -u
GPM="$1"; EMU="$2"; SRC="$3"
source "$(dirname "$0")/cli_lib.sh"
exec 3>&-  # fd 3 is the FIFO's reader below

safety=$(sed -n '/^safety:/,$p' "$SRC/hw/examples/twin.yaml")
cat >"$tmp/twin.yaml" <<YAML
backend: twin
controller: $SRC/models/gpm2002.yaml
twin: {scenario: $SRC/tests/fixtures/twin_disc.yaml}
$safety
YAML
printf 'backend: nonsense\n' >"$tmp/bad.yaml"
printf 'poses: [[236.5, 260], [196.5, 240]]\n' >"$tmp/poses2.yaml"
# A short hardware run: 20 poses through the twin backend, no accuracy test.
cat >"$tmp/hwrun.yaml" <<YAML
name: hostile_hw
robot: $SRC/models/gpm2002.yaml
seed: 7
actual: {perturb: {base_mm: 0.3, link_mm: 0.3, offset_rad: 0.01, keep: [xa1, ya1, xa2, ya2]}}
encoder: {bits: 17, noise_rad: 0}
sampling: {pattern: disc, centre: [216.5, 250], radius: 80, count: 20, move_speed_mm_s: 150,
           settle: {velocity_rad_s: 0.002, hold_s: 0.02, timeout_s: 2}, average_s: 0.05}
calibration: {cost: ml, method: lm}
outputs: {compensation: false, report: false}
YAML
sed "s|^robot: .*|robot: $SRC/models/gpm2002.yaml|" "$SRC/tests/fixtures/twin_disc.yaml" >"$tmp/sim.yaml"
op() {  # a monitor scenario: robot file, circle radius (mm)
  cat <<YAML
name: op
robot: $1
encoder: {bits: 17}
operation:
  path: {shape: circle, centre: [216.5, 250], radius: $2, period_s: 2}
  duration_s: 1
YAML
}
op "$SRC/models/gpm2002.yaml" 40 >"$tmp/op.yaml"
# Joint 1 (the zero search's read-only joint) kept within 0.06 rad of home:
# the searches pass, the comparison's section-3 poses (all joints) do not.
sed -e 's/joint_min: \[0.3,/joint_min: [1.05,/' -e 's/joint_max: \[1.9,/joint_max: [1.17,/' "$tmp/twin.yaml" >"$tmp/narrow.yaml"
# Inside the reach of the GPM2002, outside the hardware file's 90 mm safety disc.
op "$SRC/models/gpm2002.yaml" 100 >"$tmp/opfar.yaml"

# D: a hardware run's folder (measured samples, marker).
D="$tmp/D"
check "hardware run" 0 "$GPM" run "$tmp/hwrun.yaml" -o "$D" --hardware "$tmp/twin.yaml" --quiet
holds "the marker is written" test -f "$D/.gpm-measured"
# No truth through hardware: the position line and summary.json state the
# 1-sigma the calibration gives over the disc, and no error.
expect_out "hardware position line" "^position   calibrated model over the 80 mm disc: stated 1-sigma [0-9.]+ um per axis.*known in simulation only"
holds "hardware summary: stated 1-sigma, no error" python3 -c "
import json, sys
p = json.load(open(sys.argv[1]))['positioning_um']
sys.exit(0 if p['rms'] is None and p['bound_rms'] is None and p['stated_sigma_rms'] > 0 and p['points'] > 150 else 1)" "$D/summary.json"
holds "no positioning.csv without the truth" test ! -e "$D/positioning.csv"
holds "20 measured samples" test "$(tail -n +2 "$D/samples.csv" | wc -l)" -eq 20
cp "$D/samples.csv" "$tmp/measured.csv"
# E: a samples.csv no hardware session recorded there. D2: measured, one id twice.
mkdir "$tmp/E" && cp "$tmp/measured.csv" "$tmp/E/samples.csv"
cp -a "$D" "$tmp/D2" && tail -n 1 "$tmp/measured.csv" >>"$tmp/D2/samples.csv"
head -n 3 "$tmp/measured.csv" >"$tmp/dup.csv" && sed -n 3p "$tmp/measured.csv" >>"$tmp/dup.csv"
# F: an output folder whose files are also inputs.
F="$tmp/F"; mkdir "$F"
"$GPM" study samples --n 12 -o "$F/samples.csv" >/dev/null  # a simulation's samples, not measured
cp "$tmp/sim.yaml" "$F/actual.yaml"
for f in estimates.csv report.md offsets.yaml calibration.yaml summary.json; do cp "$SRC/models/gpm2002.yaml" "$F/$f"; done
sed "s|^robot: .*|robot: $F/calibration.yaml|" "$tmp/hwrun.yaml" >"$tmp/robotF.yaml"
op "$F/summary.json" 40 >"$tmp/opF.yaml"
mkfifo "$tmp/fifo"
EMU_FLAGS="--map $SRC/hw/examples/register_map_emulator.yaml --scenario $SRC/tests/fixtures/twin_disc.yaml --port 0"

# S: a gpm sample log in a folder of its own (measured, no marker: known by its header).
mkdir "$tmp/S"
check "gpm sample log" 0 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/S/samples.csv"
printf 'notes without a newline' >"$tmp/notes.txt"
printf 'a,b\nc' >"$tmp/ab.csv"

# name | exit | fragment of the stderr line | byte-identical file | command
while IFS='|' read -r name want frag guard cmd; do
  name=$(echo $name); want=$(echo $want); frag=$(echo "$frag" | sed 's/^ *//; s/ *$//'); guard=$(echo $guard)
  [[ -z "$name" || "$name" == \#* ]] && continue
  [[ "$guard" != - ]] && cp "$guard" "$tmp/guard.before"
  if check "$name" "$want" eval "$cmd"; then
    [[ -n "$frag" ]] && expect_err "$name: says why" "$frag"
  fi
  [[ "$guard" != - ]] && holds "$name: $guard unchanged" cmp -s "$guard" "$tmp/guard.before"
done <<TABLE
# 2: a folder holding measured samples is written by its hardware session only
simulate into a measured folder        |2| holds the measured samples of a gpm run --hardware session | $D/samples.csv | "$GPM" simulate "$tmp/sim.yaml" -o "$D"
run without hardware into it           |2| holds the measured samples                  | $D/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$D"
run --resume without hardware          |2| --resume continues the measured samples     | $D/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$D" --resume
monitor into a measured folder         |2| holds the measured samples                  | $D/samples.csv | "$GPM" monitor "$tmp/op.yaml" -o "$D"
zero into a measured folder            |2| holds the measured samples                  | $D/samples.csv | "$GPM" zero --hardware "$tmp/twin.yaml" -o "$D"
sample --resume onto a run's samples   |2| is the measured samples file                | $D/samples.csv | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$D/samples.csv" --resume
calibrate over measured samples        |2| is the measured samples file                | $D/samples.csv | "$GPM" calibrate --data "$tmp/measured.csv" -o "$D/samples.csv"
simulate while a session records       |2| is recording into this folder now           | $D/samples.csv | flock "$D/.gpm-measured" "$GPM" simulate "$tmp/sim.yaml" -o "$D"
a second hardware session at once      |2| another hardware session is recording       | $D/samples.csv | flock "$D/.gpm-measured" "$GPM" run "$tmp/hwrun.yaml" -o "$D" --hardware "$tmp/twin.yaml" --resume
resume samples no session recorded     |2| no hardware session recorded it             | $tmp/E/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$tmp/E" --hardware "$tmp/twin.yaml" --resume
the hardware run itself resumes        |0|                                             | $D/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$D" --hardware "$tmp/twin.yaml" --resume --quiet
# 12: duplicate sample ids, a bad hardware file leaves no folder
resume a file with an id twice         |2| sample 19 appears twice                     | $tmp/D2/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$tmp/D2" --hardware "$tmp/twin.yaml" --resume
sample --resume with an id twice       |2| sample 1 appears twice                      | $tmp/dup.csv | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/dup.csv" --resume
bad hardware file                      |2| 'nonsense' is not a backend                 | - | "$GPM" run "$tmp/hwrun.yaml" -o "$tmp/NEW" --hardware "$tmp/bad.yaml"
# 2b: a gpm sample log is measured data wherever it lies: never replaced, only resumed
simulate over a gpm sample log         |2| a hardware sampling log: first line      | $tmp/S/samples.csv | "$GPM" simulate "$tmp/sim.yaml" -o "$tmp/S"
run over a gpm sample log              |2| a hardware sampling log: first line      | $tmp/S/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$tmp/S"
study samples over a gpm sample log    |2| a hardware sampling log: first line      | $tmp/S/samples.csv | "$GPM" study samples --n 12 -o "$tmp/S/samples.csv"
calibrate over a gpm sample log        |2| a hardware sampling log: first line      | $tmp/S/samples.csv | "$GPM" calibrate --data "$tmp/measured.csv" -o "$tmp/S/samples.csv"
hardware run over a gpm sample log     |2| no hardware session recorded it             | $tmp/S/samples.csv | "$GPM" run "$tmp/hwrun.yaml" -o "$tmp/S" --hardware "$tmp/twin.yaml"
a second gpm sample without --resume   |2| pass --resume to continue it                | $tmp/S/samples.csv | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/S/samples.csv"
sample into a file that is no log      |2| is not a samples log                        | $tmp/notes.txt | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/notes.txt"
sample --resume a file that is no log  |2| is not a samples log                        | $tmp/ab.csv | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/ab.csv" --resume
sample into a missing folder           |2| nodir/x.csv: cannot create                  | - | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/nodir/x.csv"
the log's session resumes it           |0|                                             | - | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/S/samples.csv" --resume
# 3: an input that is also an output, found by file identity before any work
simulate D/samples.csv -o D            |2| samples.csv: is also an input               | $F/samples.csv | "$GPM" simulate "$F/samples.csv" -o "$F"
simulate D/actual.yaml -o D            |2| actual.yaml: is also an input               | $F/actual.yaml | "$GPM" simulate "$F/actual.yaml" -o "$F"
monitor --model D/estimates.csv -o D   |2| estimates.csv: is also an input             | $F/estimates.csv | "$GPM" monitor "$tmp/op.yaml" --model "$F/estimates.csv" -o "$F"
zero --hardware D/report.md -o D       |2| report.md: is also an input                 | $F/report.md | "$GPM" zero --hardware "$F/report.md" -o "$F"
zero --model D/offsets.yaml -o D       |2| offsets.yaml: is also an input              | $F/offsets.yaml | "$GPM" zero --hardware "$tmp/twin.yaml" --model "$F/offsets.yaml" -o "$F"
run, robot: D/calibration.yaml, -o D   |2| calibration.yaml: is also an input          | $F/calibration.yaml | "$GPM" run "$tmp/robotF.yaml" -o "$F"
monitor, robot: D/summary.json, -o D   |2| summary.json: is also an input              | $F/summary.json | "$GPM" monitor "$tmp/opF.yaml" -o "$F"
# 4: samples to a device or FIFO: in place, or refused before anything moves
sample to /dev/null                    |0|                                             | - | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o /dev/null
sample to /dev/full                    |2| /dev/full: write failed: No space left      | - | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o /dev/full
sample --resume to a device            |2| is a device or FIFO                         | - | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o /dev/null --resume
sample to a FIFO nobody reads          |2| no process reads this FIFO                  | - | "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/fifo"
# 7: everything a command will command is checked before the first motion
monitor --hardware, path outside       |2| operation.path is outside the safety limits | - | "$GPM" monitor "$tmp/opfar.yaml" --hardware "$tmp/twin.yaml" -o "$tmp/M"
zero, a --start outside the limits     |2| is outside the safety limits                | - | "$GPM" zero --hardware "$tmp/twin.yaml" --start 219.5,252.5 --start 330,250 -o "$tmp/Z"
zero --compare, section-3 poses outside|2| is outside the safety limits                | - | "$GPM" zero --hardware "$tmp/narrow.yaml" --compare -o "$tmp/Z3"
# 9: every emulator flag is bounded (NaN too)
emulator --command-period nan          |2| --command-period: nan s is outside          | - | timeout 60 "$EMU" $EMU_FLAGS --command-period nan
emulator --command-period 0            |2| --command-period: 0 s is outside            | - | timeout 60 "$EMU" $EMU_FLAGS --command-period 0
TABLE

holds "a bad hardware file makes no folder" test ! -e "$tmp/NEW"
holds "a monitor refused makes no folder" test ! -e "$tmp/M"
holds "a zero refused makes no folder" test ! -e "$tmp/Z"
holds "section 3 refused before the searches moved" test ! -e "$tmp/Z3"
holds "F keeps its files only" test "$(ls -A "$F" | wc -l)" -eq 7

# 4: a FIFO with a reader gets the header and every sample, in place.
exec 3<>"$tmp/fifo"
check "sample to a FIFO" 0 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/fifo"
lines=0
while read -r -t 10 -u 3 line; do lines=$((lines+1)); [[ $lines -eq 3 ]] && break; done
exec 3>&-
holds "the FIFO got the header and 2 samples" test "$lines" -eq 3
holds "the FIFO stays a FIFO" test -p "$tmp/fifo"

# A full disk under gpm monitor --hardware (app/cmd_monitor.cpp): files are
# limited in size (ulimit -f, SIGXFSZ ignored: a write past the limit fails
# as on a full disk), the command's own stdout and stderr go through pipes.
fsize_limited() {  # KIB CMD...
  local -; set -o pipefail
  local kib=$1; shift
  { ( trap '' XFSZ; ulimit -f "$kib"; exec "$@" ) 2>&1 1>&3 3>&- | cat >&2; } 3>&1 | cat
}
# No room at all: refused before the robot moves, no folder left.
check "monitor --hardware, no room" 2 fsize_limited 0 "$GPM" monitor "$tmp/op.yaml" --hardware "$tmp/twin.yaml" -o "$tmp/MF0" &&
  expect_err "monitor, no room: before moving" "MF0/alarms.csv: write failed: .*\(nothing moved\)"
holds "monitor, no room: no folder" test ! -e "$tmp/MF0"
# Room for the record, not the report: the alarms and estimates recorded as
# the robot moved are kept (the same bytes as a run with room), a previous
# run's summary and report removed, one line, exit 1.
check "monitor --hardware with room" 0 "$GPM" monitor "$tmp/op.yaml" --hardware "$tmp/twin.yaml" -o "$tmp/MF"
cp "$tmp/MF/estimates.csv" "$tmp/MF.estimates" && cp "$tmp/MF/alarms.csv" "$tmp/MF.alarms"
rows=$(($(wc -l <"$tmp/MF.estimates") - 1))
check "monitor --hardware, no room for the report" 1 fsize_limited 8 "$GPM" monitor "$tmp/op.yaml" --hardware "$tmp/twin.yaml" -o "$tmp/MF" &&
  expect_err "monitor, no room for the report: says what is kept" \
    "report.html: write failed .*; $rows estimates and 0 alarms kept in .*MF/estimates.csv and alarms.csv"
holds "monitor, no room for the report: one line" test "$(wc -l <"$tmp/err")" -eq 1
holds "monitor, no room for the report: estimates kept whole" cmp -s "$tmp/MF/estimates.csv" "$tmp/MF.estimates"
holds "monitor, no room for the report: alarms kept whole" cmp -s "$tmp/MF/alarms.csv" "$tmp/MF.alarms"
holds "monitor, no room for the report: no stale report" test ! -e "$tmp/MF/summary.json" -a ! -e "$tmp/MF/report.md"
holds "monitor, no room for the report: no temporary left" test "$(ls -A "$tmp/MF" | wc -l)" -eq 2

# 7: without -o, section 3's samples stay in memory: no temporary that an
# interruption could leave behind (a TMPDIR that does not exist is never used).
check "zero --compare without -o" 0 env TMPDIR="$tmp/none" "$GPM" zero --hardware "$tmp/twin.yaml" --compare
expect_out "section 3 ran" "^\| section 3 \| lm ml"
holds "no temporary folder made" test ! -e "$tmp/none"

finish
