# Benchmarks of calib/global: batch closure-cost throughput (J3 evaluations per
# second, 1 and 2 threads) and our DE against pagmo2's DE on the same objective
# and budget. Not part of ctest: run build/bench/bench_global by hand.
find_package(pagmo CONFIG QUIET)
add_executable(bench_global
  ${CMAKE_CURRENT_LIST_DIR}/global_cost.cpp
  ${CMAKE_CURRENT_LIST_DIR}/global_de_vs_pagmo.cpp
)
target_include_directories(bench_global PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(bench_global PRIVATE gpm_calib_global benchmark::benchmark_main)
if(pagmo_FOUND)
  target_link_libraries(bench_global PRIVATE Pagmo::pagmo)
  target_compile_definitions(bench_global PRIVATE GPM_HAVE_PAGMO=1)
else()
  message(STATUS "pagmo2 not found (apt-get install libpagmo-dev): bench_global runs without the pagmo comparison")
endif()
