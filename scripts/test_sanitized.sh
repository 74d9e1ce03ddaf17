#!/usr/bin/env bash
# Builds the unit tests of models/, calib/ (with global/, excitation/, monitor/)
# and hw/ (with the drive emulator, the section-2 search and the fuzz corpus
# replays of the readers and the Modbus server) with AddressSanitizer and
# UndefinedBehaviorSanitizer (GPM_SANITIZE) into build-asan/, and runs them.
# Any finding fails the run (UBSan does not recover). CI runs it after
# scripts/test.sh. The MuJoCo-heavy tests (sim/, run/, scenarios) stay out:
# their time is in MuJoCo, which is not instrumented.
#   bash scripts/test_sanitized.sh [BUILD_DIR]   (default build-asan)
# FOLDERS="models calib" narrows it to those test folders' unit tests (no
# replays, no emulator; CI's selection, which fits its time).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan}
bash scripts/setup.sh
# -O1 -g: the sanitizers' usual level, readable reports, and a shorter build than -O3.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" \
  -DGPM_SANITIZE=ON -DGPM_BUILD_BENCH=OFF >/dev/null

# Every test executable of those folders but the two long studies (label long).
folders=${FOLDERS:-models calib global excitation monitor hw}
pattern=$(echo "$folders" | sed 's/ \+/\\|/g')
mapfile -t tests < <(cmake --build "$build" --target help |
  sed -n "s/^\(test_\($pattern\)_[a-z0-9_]*\):.*/\1/p" |
  grep -v -x -E 'test_excitation_montecarlo|test_monitor_long' | sort -u)
replays=(robot_yaml samples_csv modbus_server)
extra=("${replays[@]/#/replay_}" gpm-drive-emulator)
[[ -n ${FOLDERS:-} ]] && replays=() && extra=()
cmake --build "$build" --parallel "$(nproc)" --target "${tests[@]}" "${extra[@]}"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1
logs=$build/sanitized_logs
rm -rf "$logs" && mkdir -p "$logs"
# One line per run: log name, working folder, command.
runs=()
for t in "${tests[@]}"; do
  exe=$(find "$build/tests" -type f -name "$t" -perm -u+x | head -n 1)
  runs+=("$t $(dirname "$exe") $PWD/$exe")
done
for r in "${replays[@]}"; do
  runs+=("replay_$r $build/tests/fuzz $PWD/$build/tests/fuzz/replay_$r $PWD/tests/fuzz/corpus/$r")
done
[[ -z ${FOLDERS:-} ]] &&
  runs+=("emulator_flags $build bash $PWD/tests/hw/test_emulator_flags.sh $PWD/$build/hw/gpm-drive-emulator $PWD")

run_one() {  # name dir command...
  local name=$1 dir=$2; shift 2
  if (cd "$dir" && "$@") >"$logs/$name.log" 2>&1; then echo "ok   $name"; else echo "FAIL $name"; fi
}
export -f run_one; export logs
printf '%s\n' "${runs[@]}" | xargs -P "$(nproc)" -I{} bash -c 'run_one {}' | tee "$logs/summary.txt"
failed=$(grep -c '^FAIL' "$logs/summary.txt" || true)
for f in $(sed -n 's/^FAIL //p' "$logs/summary.txt"); do
  echo "=== $f"; tail -n 60 "$logs/$f.log"
done
echo "sanitized: ${#runs[@]} runs, $failed failed (logs in $logs)"
[[ $failed -eq 0 ]]
