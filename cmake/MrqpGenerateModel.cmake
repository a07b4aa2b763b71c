# mrqp_generate_model(<name> URDF <file> [FLOATING_BASE] [PROBE] [OUTPUT_DIR <dir>]
#                     [GENERATOR_ARGS <args>...])
#
# Runs the mrqp model generator at build time on <file> and defines a static library
# target <name> holding the generated, allocation-free model code (namespace <name>,
# header "<name>.hpp"; target property MRQP_GENERATED_DIR: the output folder). The code is
# regenerated whenever the URDF or the generator changes.
# PROBE also builds <name>_probe, the standalone JSON probe program. GENERATOR_ARGS are passed
# to mrqp-gen as they are (e.g. --allow-nonphysical-inertia, --package-path DIR).
include_guard(GLOBAL)

function(mrqp_generate_model name)
  cmake_parse_arguments(ARG "FLOATING_BASE;PROBE" "URDF;OUTPUT_DIR" "GENERATOR_ARGS" ${ARGN})
  if(NOT ARG_URDF)
    message(FATAL_ERROR "mrqp_generate_model(${name}): URDF <file> is required")
  endif()
  if(NOT name MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
    message(FATAL_ERROR "mrqp_generate_model(${name}): the name must be a C++ identifier")
  endif()
  if(NOT TARGET mrqp::mrqp-gen)
    message(FATAL_ERROR "mrqp_generate_model(${name}): the generator mrqp::mrqp-gen is not available "
                        "(configure with MRQP_BUILD_MODEL_GEN=ON, give a host one with MRQP_HOST_GENERATOR, "
                        "or find_package(mrqp) on a host install)")
  endif()
  get_filename_component(urdf "${ARG_URDF}" ABSOLUTE)
  if(ARG_OUTPUT_DIR)
    set(out "${ARG_OUTPUT_DIR}")
  else()
    set(out "${CMAKE_CURRENT_BINARY_DIR}/mrqp_models")
  endif()
  set(flags ${ARG_GENERATOR_ARGS})
  set(outputs "${out}/${name}.hpp" "${out}/${name}.cpp")
  if(ARG_FLOATING_BASE)
    list(APPEND flags --floating-base)
  endif()
  if(ARG_PROBE)
    list(APPEND flags --probe)
    list(APPEND outputs "${out}/${name}_probe.cpp")
  endif()
  add_custom_command(
    OUTPUT ${outputs}
    COMMAND mrqp::mrqp-gen "${urdf}" --name ${name} --out "${out}" --quiet ${flags}
    DEPENDS "${urdf}" $<TARGET_FILE:mrqp::mrqp-gen>
    COMMENT "mrqp-gen: generating model ${name} from ${ARG_URDF}"
    VERBATIM)
  add_library(${name} STATIC "${out}/${name}.cpp" "${out}/${name}.hpp")
  # The folder of the generated files, for a test that compiles them on their own.
  set_target_properties(${name} PROPERTIES MRQP_GENERATED_DIR "${out}")
  target_include_directories(${name} PUBLIC "$<BUILD_INTERFACE:${out}>")
  target_link_libraries(${name} PUBLIC mrqp_dep::eigen)
  target_compile_features(${name} PUBLIC cxx_std_17)
  if(TARGET mrqp_host_gen)  # cross/static build: the nested host generator is rebuilt first
    add_dependencies(${name} mrqp_host_gen)
  endif()
  if(ARG_PROBE)
    add_executable(${name}_probe "${out}/${name}_probe.cpp")
    target_link_libraries(${name}_probe PRIVATE ${name})
  endif()
endfunction()
