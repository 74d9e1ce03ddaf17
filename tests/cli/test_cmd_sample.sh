#!/usr/bin/env bash
# Tests of app/cmd_sample.cpp: gpm sample on the twin (poses given, and the
# main job's designed path on the fly, in two passes where it ends early) and, through
# gpm-drive-emulator on a loopback ephemeral port, on the modbus backend;
# refusals exit 2 with one line; a failed session exits 1 and leaves no empty file;
# SIGINT/SIGTERM/SIGHUP disable the drives, keep the samples, exit 130.
# No wall-clock sleeps: the script waits on FIFOs and on tail -F.
set -u
GPM="$1"; EMU="$2"; SRC="$3"
fail=0; passed=0
tmp=$(mktemp -d); emu_pid=""
cleanup() { [[ -n "$emu_pid" ]] && kill "$emu_pid" 2>/dev/null && wait "$emu_pid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT

check() {  # name, expected exit, command...
  local name=$1 want=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [[ $got -ne $want ]]; then
    echo "FAIL $name: exit $got, want $want"; cat "$tmp/err"; fail=$((fail+1)); return 1
  fi
  if [[ $want -ne 0 && $(wc -l <"$tmp/err") -ne 1 ]]; then
    echo "FAIL $name: stderr is not one line:"; cat "$tmp/err"; fail=$((fail+1)); return 1
  fi
  passed=$((passed+1))
}
expect() {  # name, file, pattern
  if grep -qE -- "$3" "$2"; then passed=$((passed+1)); else echo "FAIL $1: no '$3' in:"; cat "$2"; fail=$((fail+1)); fi
}
rows() { tail -n +2 "$1" | wc -l; }

safety=$(sed -n '/^safety:/,$p' "$SRC/hw/examples/twin.yaml")
cat >"$tmp/twin.yaml" <<YAML
backend: twin
controller: $SRC/models/gpm2002.yaml
twin: {scenario: $SRC/tests/fixtures/twin_disc.yaml}
$safety
YAML
printf 'poses: [[236.5, 260], [196.5, 240]]\n' >"$tmp/poses2.yaml"
printf 'poses: [[236.5, 260], [196.5, 240], [230, 225]]\n' >"$tmp/poses3.yaml"

check help 0 "$GPM" --help
expect "help lists sample" "$tmp/out" "^  sample"

check "twin session" 0 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/s.csv"
[[ $(rows "$tmp/s.csv") -eq 2 ]] && passed=$((passed+1)) || { echo "FAIL twin rows"; fail=$((fail+1)); }
cp "$tmp/s.csv" "$tmp/before.csv"
check "existing file refused" 2 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses3.yaml" -o "$tmp/s.csv"
expect "refusal says --resume" "$tmp/err" "pass --resume"
cmp -s "$tmp/s.csv" "$tmp/before.csv" && passed=$((passed+1)) || { echo "FAIL file changed"; fail=$((fail+1)); }
check "resume" 0 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses3.yaml" -o "$tmp/s.csv" --resume
expect "resume counts" "$tmp/out" "1 samples taken, 2 already"

grep -v '^  watchdog_disable' "$tmp/twin.yaml" >"$tmp/nosafety.yaml"
check "missing safety limit" 2 "$GPM" sample --hardware "$tmp/nosafety.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/n.csv"
expect "names the key" "$tmp/err" "missing key 'watchdog_disable'"
[[ ! -e "$tmp/n.csv" ]] && passed=$((passed+1)) || { echo "FAIL output left behind"; fail=$((fail+1)); }
printf 'poses: [[336.5, 250]]\n' >"$tmp/far.yaml"
check "pose outside limits" 2 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/far.yaml" -o "$tmp/f.csv"
[[ ! -e "$tmp/f.csv" ]] && passed=$((passed+1)) || { echo "FAIL output left behind (far)"; fail=$((fail+1)); }
check "both pose sources" 2 "$GPM" sample --hardware "$tmp/twin.yaml" --poses "$tmp/poses2.yaml" --scenario x.yaml -o "$tmp/b.csv"

# A scenario whose poses are designed: the main job's procedure (the path on
# the fly, designed for this hardware's limits) without its calibration, into
# one samples file with the torque and read-time columns.
check "main job on the fly" 0 "$GPM" sample --hardware "$SRC/hw/examples/twin_main.yaml" --scenario main -o "$tmp/main.csv"
expect "says its robot time" "$tmp/out" "twin backend from .*: [0-9]{4,} samples in .*main.csv \([0-9.]+ s of robot time\)"
head -1 "$tmp/main.csv" >"$tmp/main_header"
expect "on-the-fly columns" "$tmp/main_header" "^sample,.*,tau1,.*,t_read1,"
[[ $(rows "$tmp/main.csv") -gt 5000 ]] && passed=$((passed+1)) || { echo "FAIL main job rows"; fail=$((fail+1)); }
check "main job file kept" 2 "$GPM" sample --hardware "$SRC/hw/examples/twin_main.yaml" --scenario main -o "$tmp/main.csv"
# The robot of seed 7011 leaves its first pass's plan (its offsets beyond the
# data sheet's) designed with a deviation margin at the watch's 20 mm: the
# first pass's samples stay beside the file, the second pass, planned from
# their offsets, fills it (as gpm run --hardware).
sed -e "s#seed: 2026#seed: 7011#" -e "s#robot: \.\./models/#robot: $SRC/models/#" \
    -e "s#deviation_mm: 10#deviation_mm: 20#" "$SRC/scenarios/main.yaml" >"$tmp/r7011.yaml"
sed -e "s#scenario: \.\./\.\./scenarios/main.yaml#scenario: $tmp/r7011.yaml#" \
    -e "s#controller: \.\./\.\./models/#controller: $SRC/models/#" "$SRC/hw/examples/twin_main.yaml" >"$tmp/twin7011.yaml"
check "a path that ended early" 0 "$GPM" sample --hardware "$tmp/twin7011.yaml" --scenario "$tmp/r7011.yaml" -o "$tmp/r.csv"
expect "names the first pass" "$tmp/out" "first pass ended early \(tracking: .*\); its [0-9]+ samples in .*r_first_pass.csv planned the second pass"
[[ $(rows "$tmp/r_first_pass.csv") -ge 12 && $(rows "$tmp/r.csv") -gt 5000 ]] && passed=$((passed+1)) ||
  { echo "FAIL first and second pass rows"; fail=$((fail+1)); }

# modbus through the emulator on an ephemeral loopback port; its drive-side
# comms watchdog is long, so only the client can switch the drives off here.
# Two processes on the wall clock, so every time limit is generous (response
# 2 s, comms 5 s, command watchdog 2 s / 5 s): this tests the command's
# contract, not real-time timing, and must hold on a loaded machine (the
# timeouts themselves are tested on an injected clock: tests/hw).
mkfifo "$tmp/emu.fifo"
"$EMU" --map "$SRC/hw/examples/register_map_emulator.yaml" --scenario "$SRC/tests/fixtures/twin_disc.yaml" \
  --port 0 --comms-watchdog 30 >"$tmp/emu.fifo" 2>"$tmp/emu.err" &
emu_pid=$!
read -r -t 60 line <"$tmp/emu.fifo" || { echo "FAIL emulator did not start"; cat "$tmp/emu.err"; exit 1; }
port=${line##*:}
sed -e "s/port: 1502/port: $port/" -e "s/response_timeout: [0-9.]*/response_timeout: 2/" \
  "$SRC/hw/examples/register_map_emulator.yaml" >"$tmp/map.yaml"
cat >"$tmp/modbus.yaml" <<YAML
backend: modbus
controller: $SRC/models/gpm2002.yaml
modbus: {register_map: $tmp/map.yaml}
$(printf '%s\n' "$safety" | sed -e 's/^\(  watchdog_hold:\) *[0-9.]*/\1 2/' -e 's/^\(  watchdog_disable:\) *[0-9.]*/\1 5/' \
  -e 's/^\(  comms_timeout:\) *[0-9.]*/\1 5/')
YAML
check "modbus session" 0 "$GPM" sample --hardware "$tmp/modbus.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/m.csv"
expect "modbus describes itself" "$tmp/out" "modbus-tcp 127.0.0.1:$port"
[[ $(rows "$tmp/m.csv") -eq 2 ]] && passed=$((passed+1)) || { echo "FAIL modbus rows"; fail=$((fail+1)); }

# Power stages on (1) or off (0) of the three drives, read from the emulator
# over Modbus (status word, register 10, bit 0).
drives() {
  python3 "$SRC/tests/hw/emulator_drives.py" "$port"
}
# One signal policy: each of SIGINT, SIGTERM, SIGHUP once the first sample is on disk.
printf 'poses: [%s]\n' "$(for k in $(seq 0 19); do printf '[%s, 250],' $((206 + k % 2 * 20)); done | sed 's/,$//')" >"$tmp/poses20.yaml"
for sig in INT TERM HUP; do
  out="$tmp/sig_$sig.csv"
  "$GPM" sample --hardware "$tmp/modbus.yaml" --poses "$tmp/poses20.yaml" -o "$out" >"$tmp/sig.out" 2>"$tmp/sig.err" &
  pid=$!
  # Returns as soon as the first sample row is on disk (tail follows the file's creation).
  read -r -t 120 first < <(tail -n +2 -F --pid=$pid "$out" 2>/dev/null) || true
  kill -s "$sig" "$pid"; wait "$pid"; rc=$?
  [[ $rc -eq 130 ]] && passed=$((passed+1)) || { echo "FAIL SIG$sig: exit $rc, want 130"; cat "$tmp/sig.err"; fail=$((fail+1)); }
  [[ $(wc -l <"$tmp/sig.err") -eq 1 ]] && passed=$((passed+1)) || { echo "FAIL SIG$sig: stderr not one line"; cat "$tmp/sig.err"; fail=$((fail+1)); }
  expect "SIG$sig says so" "$tmp/sig.err" "interrupted by SIG$sig: drives disabled; [0-9]+ samples kept in $out"
  n=$(rows "$out")
  [[ $n -ge 1 && $n -lt 20 ]] && passed=$((passed+1)) || { echo "FAIL SIG$sig: $n samples kept"; fail=$((fail+1)); }
  expect "SIG$sig samples are readable" <(python3 -c "import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); print(len(r), 'rows', all(len(x) == 6 for x in r))" "$out") "^$n rows True$"
  [[ "$(drives)" == "0 0 0" ]] && passed=$((passed+1)) || { echo "FAIL SIG$sig: drives still on: $(drives)"; fail=$((fail+1)); }
done
check "resume after a signal" 0 "$GPM" sample --hardware "$tmp/modbus.yaml" --poses "$tmp/poses20.yaml" -o "$tmp/sig_INT.csv" --resume
[[ $(rows "$tmp/sig_INT.csv") -eq 20 ]] && passed=$((passed+1)) || { echo "FAIL resume after signal rows"; fail=$((fail+1)); }

kill "$emu_pid"; wait "$emu_pid" 2>/dev/null; emu_pid=""
check "drives unreachable" 1 "$GPM" sample --hardware "$tmp/modbus.yaml" --poses "$tmp/poses2.yaml" -o "$tmp/u.csv"
expect "connect error" "$tmp/err" "127.0.0.1:$port: cannot connect"
[[ ! -e "$tmp/u.csv" ]] && passed=$((passed+1)) || { echo "FAIL empty output left behind"; fail=$((fail+1)); }

echo "$passed passed, $fail failed"
[[ $fail -eq 0 ]]
