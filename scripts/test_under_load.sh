#!/usr/bin/env bash
# Runs the default test suite RUNS times (default 3) in one build while two busy processes
# compete for the cores (`yes > /dev/null`), to show that no test depends on
# the wall clock: exits non-zero if any run fails.
#
#   RUNS=3 bash scripts/test_under_load.sh [BUILD_DIR] [ctest args...]
#
# BUILD_DIR defaults to build/ (built already: run scripts/build.sh first).
# The busy processes are this script's own children, ended by their process
# ids when it exits (also on failure or Ctrl-C). Each run's summary and load
# average are printed; the full logs go to BUILD_DIR/test_under_load.N.log.
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
[[ -f "$build/CTestTestfile.cmake" ]] || { echo "test_under_load: $build is not a configured build (run scripts/build.sh)" >&2; exit 2; }

burners=()
stop_burners() {
  for pid in "${burners[@]}"; do kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; done
  burners=()
}
trap stop_burners EXIT
trap 'exit 130' INT TERM
for _ in 1 2; do
  yes >/dev/null &
  burners+=($!)
done

status=0
for run in $(seq "${RUNS:-3}"); do
  log="$build/test_under_load.$run.log"
  start=$(date +%s)
  ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -LE 'long|montecarlo' "$@" >"$log" 2>&1
  rc=$?
  echo "run $run: exit $rc in $(( $(date +%s) - start )) s, load average $(cut -d' ' -f1-3 /proc/loadavg)," \
       "$(grep -E 'tests passed|tests failed' "$log" | tail -1)"
  if [[ $rc -ne 0 ]]; then
    status=1
    sed -n '/The following tests FAILED/,$p' "$log"
  fi
done
exit $status
