#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs each for SECONDS (default 600) on the
# corpus in tests/fuzz/corpus/<target>. New crashing inputs are written to
# build-fuzz/artifacts/; after fixing the bug, copy them into the corpus so the
# default test run replays them. Not part of the default test run.
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]
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
san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGPM_FUZZ=ON -DGPM_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="$san" -DCMAKE_EXE_LINKER_FLAGS="$san" >/dev/null
mkdir -p build-fuzz/artifacts
for t in "${targets[@]}"; do
  [[ -d tests/fuzz/corpus/$t ]] || { echo "fuzz: unknown target $t" >&2; exit 2; }
  cmake --build build-fuzz --target "fuzz_$t"
  work=build-fuzz/corpus/$t; mkdir -p "$work"
  echo "fuzz: $t for ${seconds}s"
  ./build-fuzz/tests/fuzz/fuzz_$t "$work" "tests/fuzz/corpus/$t" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=4096 -max_len=4096 -artifact_prefix=build-fuzz/artifacts/$t- \
    -print_final_stats=1 2>&1 | tail -n 25
done
