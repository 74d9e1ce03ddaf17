# Benchmarks of calib: one whole LM calibration (bench_calib_lm) timed against
# scipy.optimize.least_squares on the same CSV by bench/calib_vs_scipy.sh.
# Not part of ctest: run `bench/calib_vs_scipy.sh build` by hand.
add_executable(bench_calib_lm ${CMAKE_CURRENT_LIST_DIR}/calib_lm_timing.cpp)
target_include_directories(bench_calib_lm PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(bench_calib_lm PRIVATE gpm_calib)
