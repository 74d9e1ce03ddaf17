# Benchmark of calib/monitor: per-cycle cost of monitor_step() (goal < 20 us
# at a 1 kHz servo rate). Run by hand: build/bench/bench_monitor.
add_executable(bench_monitor ${CMAKE_CURRENT_LIST_DIR}/monitor_bench.cpp)
target_link_libraries(bench_monitor PRIVATE gpm_calib_monitor benchmark::benchmark_main)
