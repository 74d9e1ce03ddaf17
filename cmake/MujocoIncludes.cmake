# Debian's mujoco::mujoco lists /usr/include/libqhull_r among its include
# directories; that folder exists only with libqhull-dev. Drop it if absent so
# the target works either way. Included after find_package(mujoco) by the
# build (cmake/Dependencies.cmake) and by the installed package (gpmConfig.cmake).
get_target_property(_gpm_mj_inc mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
if(_gpm_mj_inc)
  set(_gpm_mj_inc_ok "")
  foreach(_gpm_d IN LISTS _gpm_mj_inc)
    if(EXISTS "${_gpm_d}" OR _gpm_d MATCHES "\\$<")
      list(APPEND _gpm_mj_inc_ok "${_gpm_d}")
    endif()
  endforeach()
  set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_gpm_mj_inc_ok}")
endif()
