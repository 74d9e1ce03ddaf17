#!/usr/bin/env bash
# Scaling of calib/global with threads, 1 and 2 measured in the same run
# (build/bench/bench_global, repetitions interleaved at random so that a
# change of machine load hits both alike): the batch J3 kernel (evaluations
# per second, 50 samples, 11 parameters) and our DE (paper settings, J3,
# budget 1.5e6 evaluations). Prints the medians, the ratio 2 threads / 1
# thread (goal >= 1.8x for the kernel on an idle machine), the cores each
# run used (process CPU time / wall time) and the load average before and
# after: on a shared machine a ratio below the goal with fewer than 2 cores
# used means the second core was busy, not that the code does not scale.
#   bash bench/global_threads.sh [BUILD_DIR] [REPETITIONS]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
reps=${2:-5}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) cores)"
"$build/bench/bench_global" --benchmark_filter='BM_PopulationCost/j3/|BM_OurDe/' \
  --benchmark_repetitions="$reps" --benchmark_enable_random_interleaving=true \
  --benchmark_format=json --benchmark_out_format=json --benchmark_out="$tmp/out.json" >/dev/null 2>"$tmp/err" ||
  { cat "$tmp/err" >&2; exit 1; }
/usr/bin/python3 - "$tmp/out.json" <<'EOF'
import json, statistics, sys
runs = [b for b in json.load(open(sys.argv[1]))["benchmarks"] if b.get("run_type") == "iteration"]
def med(prefix, key):
    return statistics.median(b[key] for b in runs if b["run_name"] == prefix)
def cores(prefix):
    return statistics.median(b["cpu_time"] / b["real_time"] for b in runs if b["run_name"] == prefix)
print(f"{'what':34} {'1 thread':>12} {'2 threads':>12} {'ratio':>7} {'cores used 1t/2t':>17}")
k1 = med("BM_PopulationCost/j3/1/process_time/real_time", "evals_per_s")
k2 = med("BM_PopulationCost/j3/2/process_time/real_time", "evals_per_s")
print(f"{'batch J3 kernel, evaluations/s':34} {k1 / 1e6:10.1f} M {k2 / 1e6:10.1f} M {k2 / k1:6.2f}x "
      f"{cores('BM_PopulationCost/j3/1/process_time/real_time'):8.2f} /{cores('BM_PopulationCost/j3/2/process_time/real_time'):5.2f}")
d1 = med("BM_OurDe/1/iterations:3/process_time/real_time", "real_time")
d2 = med("BM_OurDe/2/iterations:3/process_time/real_time", "real_time")
print(f"{'DE, 1.5e6 evaluations, wall ms':34} {d1:12.0f} {d2:12.0f} {d1 / d2:6.2f}x "
      f"{cores('BM_OurDe/1/iterations:3/process_time/real_time'):8.2f} /{cores('BM_OurDe/2/iterations:3/process_time/real_time'):5.2f}")
EOF
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
