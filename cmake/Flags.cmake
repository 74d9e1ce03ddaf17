# The project's compile and link flags, set PRIVATE on each of its own targets
# (never global, never on imported targets, never passed on to consumers).

# Flags of one target: the warning set, and the GPM_WERROR, GPM_NATIVE and
# GPM_SANITIZE options.
function(gpm_target_flags target)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  # GCC 12's libstdc++ trips -Wrestrict in std::string assignments at -O3 (GCC PR 105329, fixed in 13).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(GPM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(GPM_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
    # GCC 12's avx512fintrin.h trips -Wmaybe-uninitialized inside Eigen (GCC PR 105593, fixed in 13).
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
    # Our Eigen instantiations must not interpose those of the shared libceres (calib/CMakeLists.txt).
    set_target_properties(${target} PROPERTIES CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  endif()
  if(GPM_SANITIZE)
    set(_san -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    target_compile_options(${target} PRIVATE ${_san})
    target_link_options(${target} PRIVATE ${_san})
  endif()
endfunction()

# gpm_target_flags on every library and executable defined under DIR and its subfolders.
function(gpm_flags_for_directory dir)
  get_property(_targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(_t IN LISTS _targets)
    get_target_property(_type ${_t} TYPE)
    if(_type MATCHES "^(STATIC_LIBRARY|SHARED_LIBRARY|MODULE_LIBRARY|OBJECT_LIBRARY|EXECUTABLE)$")
      gpm_target_flags(${_t})
    endif()
  endforeach()
  get_property(_subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(_d IN LISTS _subdirs)
    gpm_flags_for_directory(${_d})
  endforeach()
endfunction()
