#!/usr/bin/env bash
# The main job's procedure (scenarios/main.yaml: the excitation path sampled
# on the fly) through Modbus TCP and gpm-drive-emulator (loopback, ephemeral
# port) in lock step: the emulator --stepped advances its plant one command
# period per client cycle and the hardware file's modbus.timing: stepped makes
# the client's time its count of cycles (checked against the drives' latch
# time every cycle), so neither the samples nor the robot time depend on how
# loaded the machine is. The run passes, records the torques and read times
# of every sample, takes at most 15 s of robot time, and its calibrated
# parameters agree with the twin backend's on the same robot and plan within
# 5 of their combined stated 1-sigma (the twin backend is gpm run's in-process loop; the
# drives report torque in 0.01 N m steps and are polled one after another).
# Everything in a fresh temporary folder that is removed.
# Usage: test_hardware_main.sh GPM EMULATOR SOURCE_DIR [COUNTS_PER_REV [TIMING]]
# (the drives' position unit, default 1048576 = 2^20, the test's; TIMING
# stepped, the test's, or real_time: the client paces its cycles on the wall
# clock against the same stepped emulator, with watchdogs of 1 s and 4 s, for
# the comparison in docs/PROCEDURES.md).
set -u
GPM="$1"; EMU="$2"; SRC="$3"; COUNTS="${4:-1048576}"; TIMING="${5:-stepped}"
tmp=$(mktemp -d); emu_pid=""
cleanup() { [[ -n "$emu_pid" ]] && kill "$emu_pid" 2>/dev/null && wait "$emu_pid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
fail=0; passed=0
ok() { passed=$((passed+1)); }
bad() { echo "FAIL $1"; fail=$((fail+1)); }

# A run through hardware fails the main job's floor_ratio (the actual
# parameters are not known through hardware): it is judged by what it wrote.
"$GPM" run "$SRC/scenarios/main.yaml" --hardware "$SRC/hw/examples/twin_main.yaml" -o "$tmp/twin" --quiet \
  >"$tmp/twin.out" 2>&1
[[ -f "$tmp/twin/summary.json" ]] && ok || { bad "twin backend run"; cat "$tmp/twin.out"; }

# Positions in 2^20 counts per revolution: the drive turns the steps between
# its setpoints into velocity feed-forward, and 17-bit setpoints (the example
# map's) make that feed-forward jump by a count per cycle (3.3x the twin
# backend's error, docs/PROCEDURES.md); the readings stay the twin's 17 bits.
sed -e "s/counts_per_rev: 131072/counts_per_rev: $COUNTS/" "$SRC/hw/examples/register_map_emulator.yaml" \
  >"$tmp/map20.yaml"
mkfifo "$tmp/emu.fifo"
"$EMU" --map "$tmp/map20.yaml" --scenario "$SRC/scenarios/main.yaml" \
  --port 0 --stepped --command-period 0.00025 --comms-watchdog 5 >"$tmp/emu.fifo" 2>"$tmp/emu.err" &
emu_pid=$!
line=""; read -r -t 60 line <"$tmp/emu.fifo" || { bad "emulator did not start"; cat "$tmp/emu.err"; }
port=${line##*:}
sed -e "s/port: 1502/port: $port/" -e "s/response_timeout: [0-9.]*/response_timeout: 1/" \
  "$tmp/map20.yaml" >"$tmp/map.yaml"
# The main job's hardware file with the emulator's drives, stepped; its
# limits as they are (the command watchdog runs on the cycles' time), but for
# comms_timeout, which must cover the map's response_timeout (wall clock: the
# emulator's replies on a loaded host).
watchdogs=()
[[ "$TIMING" == real_time ]] && watchdogs=(-e "s|^  watchdog_hold: [0-9.]*|  watchdog_hold: 1|"
                                           -e "s|^  watchdog_disable: [0-9.]*|  watchdog_disable: 4|")
sed -e "s|^backend: twin|backend: modbus|" -e "s|^controller: .*|controller: $SRC/models/gpm2002.yaml|" \
    -e "s|^twin:|modbus:|" -e "s|^  scenario: .*|  register_map: $tmp/map.yaml\\n  timing: $TIMING|" \
    -e "s|^  comms_timeout: [0-9.]*|  comms_timeout: 2|" "${watchdogs[@]}" "$SRC/hw/examples/twin_main.yaml" \
    >"$tmp/modbus.yaml"
"$GPM" run "$SRC/scenarios/main.yaml" --hardware "$tmp/modbus.yaml" -o "$tmp/modbus" --quiet \
  >"$tmp/modbus.out" 2>&1
[[ -f "$tmp/modbus/summary.json" ]] && ok || { bad "modbus run"; cat "$tmp/modbus.out"; }
grep -q "through modbus backend" "$tmp/modbus.out" && ok || bad "modbus run says how it sampled"

python3 - "$tmp/twin/summary.json" "$tmp/modbus/summary.json" "$tmp/modbus/samples.csv" "$TIMING" <<'PY' && ok || bad "modbus accuracy"
import csv, json, sys
twin, modbus = (json.load(open(p)) for p in sys.argv[1:3])
rows = list(csv.DictReader(open(sys.argv[3])))
assert len(rows) > 5000 and all(k in rows[0] for k in ("t", "tau_last1", "tau_between3", "t_read2")), len(rows)
def after(s):
    return s["accuracy"]["calibrated"]["static_rms_um"]
ratio = after(modbus) / after(twin)
print(f"static RMS calibrated: twin backend {after(twin):.2f} um, modbus {after(modbus):.2f} um "
      f"(x{ratio:.2f}); robot time {twin['robot_time_s']:.2f} s, {modbus['robot_time_s']:.2f} s")
ok = True
# The two backends' calibrations agree within their stated 1-sigma (each
# parameter's difference within 5 of the two 1-sigma combined), and each is
# within 6 of its own 1-sigma of the actual parameters: this is the main
# job's robot, the worst of its 30 preset robots, outside its 1-sigma since
# that carries the encoders' own error once per joint revolution instead of
# the reducer's (in process up to 5.55 Cramer-Rao sigmas, scenarios/main.yaml
# states 6; measured here 3.8 apart, dth1, and modbus's ya3 4.1 of its
# 1-sigma; 3 and 3 when the 1-sigma carried the reducer's). The static RMS at 12
# poses is held only to the main job's 200x improvement over the nominal
# model: on one robot it moves by 2x either way with data that differ by the
# drives' torque noise (modbus 0.8x the twin backend with the force signs'
# threshold at 1.5 N, 2.1x with the force balance's; docs/PROCEDURES.md).
for name, p in twin["parameters"].items():
    q = modbus["parameters"][name]
    if not p.get("std"):
        continue
    apart = abs(q["estimated"] - p["estimated"]) / (p["std"] ** 2 + q["std"] ** 2) ** 0.5
    if apart > 5.0:
        print(f"FAIL {name}: the backends' estimates {apart:.1f} combined 1-sigma apart (at most 5)"); ok = False
    for backend, e in (("twin backend", p), ("modbus", q)):
        if abs(e["estimated"] - e["actual"]) > 6.0 * e["std"]:
            print(f"FAIL {name}: {backend}'s error {abs(e['estimated'] - e['actual']) / e['std']:.1f} of its 1-sigma (at most 6)")
            ok = False
improvement = modbus["accuracy"]["nominal"]["static_rms_um"] / after(modbus)
if improvement < 200.0:
    print(f"FAIL modbus static RMS only {improvement:.0f}x better than the nominal model's (at least 200x)"); ok = False
if modbus["robot_time_s"] > 15.0:
    print(f"FAIL modbus robot time {modbus['robot_time_s']:.2f} s (at most 15 s)"); ok = False
# Lock step: the samples' times are the cycles' (one sample every 4 cycles of
# 0.25 ms), each joint read at the latch of its sample's cycle.
t = [float(r["t"]) for r in rows]
if sys.argv[4] == "stepped":
    steps = [b - a for a, b in zip(t, t[1:])]
    late = max(abs(float(r[f"t_read{i}"]) - float(r["t"])) for r in rows for i in (1, 2, 3))
    if max(abs(d - 0.001) for d in steps) > 1e-9 or late > 1e-9:
        print(f"FAIL samples' times: steps {min(steps)}..{max(steps)} s, reads up to {late} s from t"); ok = False
sys.exit(0 if ok else 1)
PY

echo "$passed passed, $fail failed"
[[ $fail -eq 0 ]]
