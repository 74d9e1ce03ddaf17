#!/usr/bin/env bash
# gpm run with --hardware: the hardware_twin scenario sampled through Modbus
# TCP and gpm-drive-emulator (loopback, ephemeral port) gives the same
# verdict as on the in-process twin backend, and samples within two encoder
# counts of it (17-bit).
set -u
GPM="$1"; EMU="$2"; SRC="$3"
tmp=$(mktemp -d); emu_pid=""
cleanup() { [[ -n "$emu_pid" ]] && kill "$emu_pid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
fail=0; passed=0
ok() { passed=$((passed+1)); }
bad() { echo "FAIL $1"; fail=$((fail+1)); }

"$GPM" run "$SRC/scenarios/hardware_twin.yaml" -o "$tmp/twin" --quiet >"$tmp/twin.out" 2>&1 && ok || { bad "twin run"; cat "$tmp/twin.out"; }

"$EMU" --map "$SRC/hw/examples/register_map_emulator.yaml" --scenario "$SRC/scenarios/simulate_disc.yaml" \
  --port 0 >"$tmp/emu.out" 2>&1 &
emu_pid=$!
for _ in $(seq 100); do grep -q listening "$tmp/emu.out" && break; sleep 0.05; done
port=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$tmp/emu.out")
sed "s/port: 1502/port: $port/" "$SRC/hw/examples/register_map_emulator.yaml" >"$tmp/map.yaml"
sed -e "s|^controller: .*|controller: $SRC/models/gpm2002.yaml|" \
    -e "s|^  register_map: .*|  register_map: $tmp/map.yaml|" "$SRC/hw/examples/modbus_emulator.yaml" >"$tmp/modbus.yaml"

"$GPM" run "$SRC/scenarios/hardware_twin.yaml" --hardware "$tmp/modbus.yaml" -o "$tmp/modbus" --quiet \
  >"$tmp/modbus.out" 2>&1 && ok || { bad "modbus run"; cat "$tmp/modbus.out"; }
grep -q "through modbus backend" "$tmp/modbus.out" && ok || bad "modbus run says how it sampled"
grep -q "verdict    PASSED" "$tmp/modbus.out" && ok || bad "modbus verdict"
[[ -f "$tmp/modbus/report.html" && -f "$tmp/modbus/calibration.yaml" ]] && ok || bad "modbus outputs"

# Same poses, same twin behind both: readings agree within two counts.
count=$(python3 - "$tmp/twin/samples.csv" "$tmp/modbus/samples.csv" <<'PY'
import csv, math, sys
a = list(csv.DictReader(open(sys.argv[1]))); b = list(csv.DictReader(open(sys.argv[2])))
assert len(a) == len(b) == 50, (len(a), len(b))
step = 2 * math.pi / 2**17
worst = 0.0
for ra, rb in zip(a, b):
    for k in ("theta_m1", "theta_m2", "theta_m3"):
        d = abs(float(ra[k]) - float(rb[k]))
        worst = max(worst, min(d, 2 * math.pi - d) / step)
print(f"{worst:.3f}")
PY
)
echo "largest twin/modbus difference: $count counts"
awk -v c="$count" 'BEGIN { exit !(c != "" && c <= 2.0) }' && ok || bad "samples differ by $count counts"

echo "$passed passed, $fail failed"
[[ $fail -eq 0 ]]
