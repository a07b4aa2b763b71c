# yaml-cpp (libyaml-cpp-dev): defines mrqp_dep::yaml_cpp when found. Optional: without it the scene
# files (control/scene) and mrqp-drive-emu are not built (they test if(TARGET mrqp_dep::yaml_cpp)).
#
# The static archive is linked when there is one: a static runtime build (MRQP_STATIC_RUNTIME)
# links every program with -static, and the HIL companions (tools/drive_emu) are static in any
# build. Debian 12's package exports the target `yaml-cpp`, newer ones `yaml-cpp::yaml-cpp`.
include_guard(GLOBAL)
find_package(yaml-cpp QUIET)
if(yaml-cpp_FOUND)
  if(TARGET yaml-cpp::yaml-cpp)
    set(_mrqp_yaml_target yaml-cpp::yaml-cpp)
  else()
    set(_mrqp_yaml_target yaml-cpp)
  endif()
  find_library(MRQP_YAML_CPP_ARCHIVE NAMES libyaml-cpp.a)
  add_library(mrqp_dep::yaml_cpp INTERFACE IMPORTED GLOBAL)
  if(MRQP_YAML_CPP_ARCHIVE)
    # Linking the archive by path brings no include directories: take the package target's.
    get_target_property(_mrqp_yaml_includes ${_mrqp_yaml_target} INTERFACE_INCLUDE_DIRECTORIES)
    target_link_libraries(mrqp_dep::yaml_cpp INTERFACE "${MRQP_YAML_CPP_ARCHIVE}")
    if(_mrqp_yaml_includes)
      target_include_directories(mrqp_dep::yaml_cpp INTERFACE ${_mrqp_yaml_includes})
    endif()
  else()
    target_link_libraries(mrqp_dep::yaml_cpp INTERFACE ${_mrqp_yaml_target})
  endif()
  unset(_mrqp_yaml_target)
  unset(_mrqp_yaml_includes)
else()
  message(STATUS "mrqp: yaml-cpp not found: scene files (control/scene) and mrqp-drive-emu are not built")
endif()
