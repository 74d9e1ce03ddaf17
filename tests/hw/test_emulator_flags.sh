#!/usr/bin/env bash
# Tests of hw/backends/emulator_main.cpp (gpm-drive-emulator flags): bad flags
# exit 2 with one line on stderr; --bind localhost listens on 127.0.0.1;
# non-loopback addresses need --allow-non-loopback. No wall-clock sleeps: the
# script waits for the "listening" line on a FIFO.
set -u
EMU="$1"; SRC="$2"
tmp=$(mktemp -d); emu_pid=""
cleanup() { [[ -n "$emu_pid" ]] && kill "$emu_pid" 2>/dev/null && wait "$emu_pid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
fail=0; passed=0
ok() { passed=$((passed+1)); }
bad() { echo "FAIL $1"; fail=$((fail+1)); }
MAP="$SRC/hw/examples/register_map_emulator.yaml"; SC="$SRC/tests/fixtures/twin_disc.yaml"

refused() {  # name, expected words, flags...
  local name="$1" words="$2"; shift 2
  "$EMU" --map "$MAP" --scenario "$SC" "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  [[ $rc -eq 2 ]] && ok || bad "$name: exit $rc, expected 2"
  [[ $(wc -l <"$tmp/err") -eq 1 ]] && ok || { bad "$name: not one line on stderr"; cat "$tmp/err"; }
  grep -q -- "$words" "$tmp/err" && ok || { bad "$name: message lacks '$words'"; cat "$tmp/err"; }
  ! grep -q listening "$tmp/out" && ok || bad "$name: listened"
}
refused "port -1" "--port" --port -1
refused "port 70000" "65535" --port 70000
refused "comms watchdog 0" "--comms-watchdog" --comms-watchdog 0
refused "bind 0.0.0.0" "--allow-non-loopback" --bind 0.0.0.0 --port 0
refused "bind unresolvable" "--bind" --bind "no such host.invalid" --port 0
refused "unknown flag" "--frobnicate" --frobnicate 1
refused "port not a number" "--port" --port abc
refused "stall -1" "--stall" --stall -1 --stall-after-writes 3
refused "stall after -2 writes" "--stall-after-writes" --stall-after-writes -2

mkfifo "$tmp/fifo"
"$EMU" --map "$MAP" --scenario "$SC" --bind localhost --port 0 >"$tmp/fifo" 2>"$tmp/err" &
emu_pid=$!
if read -r -t 30 line <"$tmp/fifo"; then
  [[ "$line" =~ ^gpm-drive-emulator:\ listening\ on\ 127\.0\.0\.1:[0-9]+$ ]] && ok || bad "localhost: '$line'"
  port=${line##*:}
  grep -q "127.0.0.1:$port" <(ss -ltn 2>/dev/null || true) && ok || { command -v ss >/dev/null && bad "not listening on 127.0.0.1:$port" || ok; }
else
  bad "localhost: no listening line"; cat "$tmp/err"
fi
kill "$emu_pid"; wait "$emu_pid"; rc=$?; emu_pid=""
[[ $rc -eq 0 ]] && ok || bad "SIGTERM: exit $rc, expected 0"

echo "$passed passed, $fail failed"
[[ $fail -eq 0 ]]
