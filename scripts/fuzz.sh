#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs each for SECONDS (default 600) on the
# corpus in tests/fuzz/corpus/<target>, one after another. New crashing inputs
# are written to build-fuzz/artifacts/; after fixing the bug, copy them into
# the corpus so the default test run replays them. Not part of the default
# test run.
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]
# Environment: FUZZ_TIMEOUT (s per input before libFuzzer calls it a hang;
# default 60: a niced process on a loaded machine misses 10 s), FUZZ_NICE
# (niceness of the fuzzers, default 10), FUZZ_BUILD=0 (run targets already
# built in build-fuzz/, e.g. while another target still builds).
# Each target's result is one line on stdout and one row of
# out/fuzz/summary.tsv (appended; the log of each run in out/fuzz/TARGET.log):
#   target commit seconds executions edges crashes exit
# where seconds is the wall time the fuzzer ran, executions and edges are
# libFuzzer's final stats (stat::number_of_executed_units, the last cov:),
# crashes the crash/leak/timeout/oom inputs it wrote to build-fuzz/artifacts/.
# The script exits 1 when any target found one.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
SUDO=""; [[ $(id -u) -eq 0 ]] || SUDO="sudo"
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "$p"
done
seconds=${1:-600}; shift || true
targets=("$@"); ((${#targets[@]})) || targets=(robot_yaml samples_csv scenario_yaml cli modbus_server calibrate_options)
timeout_s=${FUZZ_TIMEOUT:-60}
niceness=${FUZZ_NICE:-10}
san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"
[[ ${FUZZ_BUILD:-1} == 0 ]] || CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGPM_FUZZ=ON -DGPM_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="$san" -DCMAKE_EXE_LINKER_FLAGS="$san" >/dev/null
for t in "${targets[@]}"; do
  [[ -d tests/fuzz/corpus/$t ]] || { echo "fuzz: unknown target $t" >&2; exit 2; }
done
[[ ${FUZZ_BUILD:-1} == 0 ]] || cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"
mkdir -p build-fuzz/artifacts out/fuzz
summary=out/fuzz/summary.tsv
[[ -s $summary ]] || printf 'target\tcommit\tseconds\texecutions\tedges\tcrashes\texit\n' >"$summary"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
[[ -z $(git status --porcelain --untracked-files=no 2>/dev/null) ]] || commit="$commit+"
found=0
for t in "${targets[@]}"; do
  work=build-fuzz/corpus/$t; mkdir -p "$work"
  log=out/fuzz/$t.log
  before=$(ls build-fuzz/artifacts | grep -c "^$t-" || true)
  echo "fuzz: $t for ${seconds}s"
  start=$(date +%s)
  rc=0
  nice -n "$niceness" ./build-fuzz/tests/fuzz/fuzz_$t "$work" "tests/fuzz/corpus/$t" -max_total_time="$seconds" \
    -timeout="$timeout_s" -rss_limit_mb=4096 -max_len=4096 -artifact_prefix=build-fuzz/artifacts/$t- \
    -print_final_stats=1 >"$log" 2>&1 || rc=$?
  ran=$(( $(date +%s) - start ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  edges=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1 | cut -d' ' -f2)
  crashes=$(( $(ls build-fuzz/artifacts | grep -c "^$t-" || true) - before ))
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$commit" "$ran" "${execs:-?}" "${edges:-?}" "$crashes" "$rc" >>"$summary"
  echo "fuzz: $t: ${execs:-?} executions in ${ran} s, ${edges:-?} edges, $crashes crashes (exit $rc; log $log)"
  ((crashes == 0 && rc == 0)) || { found=1; grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error)' "$log" | head -n 5 || true; }
done
echo "fuzz: summary in $summary"
exit "$found"
