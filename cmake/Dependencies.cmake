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

# Debian's mujoco::mujoco lists /usr/include/libqhull_r among its include
# directories; that folder exists only with libqhull-dev. Drop it if absent so
# the target works either way.
get_target_property(_mj_inc mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
if(_mj_inc)
  set(_mj_inc_ok "")
  foreach(_d IN LISTS _mj_inc)
    if(EXISTS "${_d}" OR _d MATCHES "\\$<")
      list(APPEND _mj_inc_ok "${_d}")
    endif()
  endforeach()
  set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_mj_inc_ok}")
endif()

if(GPM_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(GPM_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
