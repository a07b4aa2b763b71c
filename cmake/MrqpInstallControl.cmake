# Installation of the controller (control/), like the drivers: the libraries as mrqp:: targets of
# the export set mrqpTargets, their headers under include/mrqp/control/<folder>/ (a user writes the
# same #include "problem/multi_robot_problem.hpp" as the tree does), the built-in models' generated
# headers under include/mrqp/models/. find_package(mrqp) then gives a user's project the whole
# controller: model traits, QP solver, problem, scenes (with the built-in panda, jvrc1 and door
# models), the controller loop, plus mrqp_generate_model() for the user's own robots.
#
# Included by the top-level CMakeLists.txt after control/. The control libraries name their include
# folder as a plain source path (${CMAKE_CURRENT_SOURCE_DIR}/..); for the export it is split here
# into the build folder and the installed one.
include_guard(GLOBAL)

function(mrqp_install_control)
  set(control_dir "${PROJECT_SOURCE_DIR}/control")
  set(installed_include "${CMAKE_INSTALL_INCLUDEDIR}/mrqp/control")
  set(libs)
  set(folders)
  # library  header folder of control/ (- for none)
  foreach(pair mrqp_model:model mrqp_qp:qp mrqp_problem:problem mrqp_collision:collision mrqp_yaml:- mrqp_scene:scene
               mrqp_estimation:estimation mrqp_builtin_models:- mrqp_loop_devices:- mrqp_loop:loop)
    string(REPLACE ":" ";" pair "${pair}")
    list(GET pair 0 lib)
    list(GET pair 1 folder)
    if(NOT TARGET ${lib})
      continue()
    endif()
    get_target_property(incs ${lib} INTERFACE_INCLUDE_DIRECTORIES)
    if(incs)
      set(fixed)
      foreach(dir IN LISTS incs)
        if(dir MATCHES "^\\$<")  # already a generator expression
          list(APPEND fixed "${dir}")
        else()
          get_filename_component(dir "${dir}" ABSOLUTE)
          list(APPEND fixed "$<BUILD_INTERFACE:${dir}>")
          if(dir STREQUAL control_dir)
            list(APPEND fixed "$<INSTALL_INTERFACE:${installed_include}>")
          endif()
        endif()
      endforeach()
      list(REMOVE_DUPLICATES fixed)
      set_target_properties(${lib} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${fixed}")
    endif()
    list(APPEND libs ${lib})
    if(NOT folder STREQUAL "-")
      list(APPEND folders ${folder})
    endif()
  endforeach()

  # The built-in models: generated libraries and headers.
  foreach(model panda_model jvrc1_model door_model shadow_hand_model pen_model)
    if(TARGET ${model})
      get_target_property(dir ${model} MRQP_GENERATED_DIR)
      target_include_directories(${model} PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/mrqp/models>)
      install(FILES "${dir}/${model}.hpp" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/mrqp/models)
      list(APPEND libs ${model})
    endif()
  endforeach()

  # mrqp_warnings is linked PRIVATE by the libraries: exported too (it carries compile options
  # only, which a private link does not pass on to a user).
  install(TARGETS mrqp_warnings ${libs} EXPORT mrqpTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  foreach(lib IN LISTS libs)
    if(NOT TARGET mrqp::${lib})
      add_library(mrqp::${lib} ALIAS ${lib})
    endif()
  endforeach()
  foreach(folder IN LISTS folders)
    install(DIRECTORY ${control_dir}/${folder}/ DESTINATION ${installed_include}/${folder}
      FILES_MATCHING PATTERN "*.hpp" PATTERN "urdf" EXCLUDE)
  endforeach()
endfunction()
