# `cmake --install build --prefix P` (issue 18.4): the programs (gpm,
# gpm-render, gpm-drive-emulator), the libraries and their public headers, a
# CMake package (find_package(gpm CONFIG) -> gpm::models, gpm::calib, ...), the
# data folder P/share/gpm/{models,scenarios,hw/examples,docs} that the installed
# programs find by their own location (models/data_dir.hpp), and the Python
# module into P/lib/python3/dist-packages. Included last by the top-level
# CMakeLists.txt, so that every target exists.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(GPM_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/gpm)  # holds models/, calib/, ...
set(GPM_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/gpm)         # holds models/, scenarios/
set(GPM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/gpm)
set(GPM_INSTALL_PYTHONDIR ${CMAKE_INSTALL_LIBDIR}/python3/dist-packages)

# The libraries of the package: gpm_<name> is exported as gpm::<name>.
# gpm_ceres is how gpm_calib links Ceres (calib/CMakeLists.txt).
set(GPM_EXPORTED_LIBRARIES
  gpm_models gpm_calib gpm_ceres gpm_calib_global gpm_calibrate gpm_calib_excitation gpm_calib_monitor
  gpm_sim gpm_hw gpm_hw_zero gpm_report gpm_run)

foreach(_t IN LISTS GPM_EXPORTED_LIBRARIES)
  string(REGEX REPLACE "^gpm_" "" _name ${_t})
  set_target_properties(${_t} PROPERTIES EXPORT_NAME ${_name})
  # The libraries name the source tree as their include folder; installed,
  # the headers are under P/include/gpm.
  get_target_property(_inc ${_t} INTERFACE_INCLUDE_DIRECTORIES)
  if(_inc)
    list(TRANSFORM _inc REPLACE "^(${PROJECT_SOURCE_DIR})$" "$<BUILD_INTERFACE:\\1>")
    list(APPEND _inc "$<INSTALL_INTERFACE:${GPM_INSTALL_INCLUDEDIR}>")
    list(REMOVE_DUPLICATES _inc)
    set_target_properties(${_t} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_inc}")
  endif()
endforeach()
# -march=native is never exported: a GPM_NATIVE build's package refuses
# consumers instead (gpmConfig.cmake.in; its Eigen layout differs from theirs).

install(TARGETS ${GPM_EXPORTED_LIBRARIES} EXPORT gpmTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS gpm gpm-drive-emulator RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS gpm-render RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} OPTIONAL)

# Public headers, in the layout the sources include them by (models/robot.hpp);
# the C header of backend plugins too (hw/plugin/gpm_backend_plugin.h: a
# plugin built elsewhere needs that file alone).
foreach(_dir models calib sim hw report run)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_dir}/ DESTINATION ${GPM_INSTALL_INCLUDEDIR}/${_dir}
    FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
endforeach()

# Data: the nominal robot, the scenario library and the hardware examples the
# scenarios name (relative paths between them are kept).
install(FILES ${PROJECT_SOURCE_DIR}/models/gpm2002.yaml ${PROJECT_SOURCE_DIR}/models/gpm2002.xml
  DESTINATION ${GPM_INSTALL_DATADIR}/models)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/ DESTINATION ${GPM_INSTALL_DATADIR}/scenarios
  FILES_MATCHING PATTERN "*.yaml" PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/hw/examples/ DESTINATION ${GPM_INSTALL_DATADIR}/hw/examples
  FILES_MATCHING PATTERN "*.yaml")
# The documents `gpm help TOPIC` prints (app/data_files.cpp; the scenario
# schema is installed with the scenarios above).
install(FILES ${PROJECT_SOURCE_DIR}/docs/CLI.md ${PROJECT_SOURCE_DIR}/docs/FORMATS.md
  ${PROJECT_SOURCE_DIR}/docs/PROCEDURES.md ${PROJECT_SOURCE_DIR}/docs/MONITORING.md
  ${PROJECT_SOURCE_DIR}/docs/OWN_ROBOT.md DESTINATION ${GPM_INSTALL_DATADIR}/docs)
install(FILES ${PROJECT_SOURCE_DIR}/hw/README.md DESTINATION ${GPM_INSTALL_DATADIR}/hw)

# The CMake package.
install(EXPORT gpmTargets NAMESPACE gpm:: DESTINATION ${GPM_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gpmConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/gpmConfig.cmake
  INSTALL_DESTINATION ${GPM_INSTALL_CMAKEDIR}
  PATH_VARS GPM_INSTALL_DATADIR GPM_INSTALL_INCLUDEDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/gpmConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/gpmConfig.cmake ${PROJECT_BINARY_DIR}/cmake/gpmConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/MujocoIncludes.cmake
  DESTINATION ${GPM_INSTALL_CMAKEDIR})

# The Python module (import gpm with PYTHONPATH=P/lib/python3/dist-packages).
if(TARGET gpm_python)
  install(TARGETS gpm_python LIBRARY DESTINATION ${GPM_INSTALL_PYTHONDIR} OPTIONAL)
endif()
