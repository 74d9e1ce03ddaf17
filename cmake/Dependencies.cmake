# Every dependency comes from Debian 12 packages (scripts/setup.sh installs them)
# and is found through its CMake package.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(Ceres REQUIRED)
find_package(fmt REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)
find_package(mujoco REQUIRED)
find_package(Boost 1.74 REQUIRED)  # header-only: Boost.Math special functions
find_package(nlohmann_json 3 REQUIRED)

include(${CMAKE_CURRENT_LIST_DIR}/MujocoIncludes.cmake)

if(GPM_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(GPM_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
