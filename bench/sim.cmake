# Benchmarks of sim: twin steps per second vs bare mj_step and vs
# mujoco-testspeed on the same model.xml (bench/sim_vs_testspeed.sh).
add_executable(bench_sim ${CMAKE_CURRENT_LIST_DIR}/sim_bench.cpp)
target_link_libraries(bench_sim PRIVATE gpm_sim)
