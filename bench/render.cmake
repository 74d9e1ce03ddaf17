# Benchmark of render: frames per second of off-screen rendering and of
# rendering plus H.264 encoding (goal: at least 60 at 640x480, quality fast).
add_executable(bench_render ${CMAKE_CURRENT_LIST_DIR}/render_fps.cpp)
target_link_libraries(bench_render PRIVATE gpm_render)
target_compile_definitions(bench_render PRIVATE GPM_SCENARIOS_DIR="${PROJECT_SOURCE_DIR}/scenarios")
