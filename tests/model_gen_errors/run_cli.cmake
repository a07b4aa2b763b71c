# Runs mrqp-gen and checks its exit code and stderr. Used by the mrqp-gen.* CLI tests.
#   cmake -DEXE=<mrqp-gen> -DARGS=<a|b|c> -DEXPECT_RC=<code or NONZERO> -DEXPECT_STDERR=<regex>
#         [-DOUT_DIR=<dir, emptied first; must stay without generated files>] -P run_cli.cmake
foreach(var EXE EXPECT_RC EXPECT_STDERR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_cli.cmake: ${var} not set")
  endif()
endforeach()
string(REPLACE "|" ";" args "${ARGS}")
if(DEFINED OUT_DIR)
  file(REMOVE_RECURSE "${OUT_DIR}")
endif()

execute_process(COMMAND "${EXE}" ${args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "exit code: ${rc}\nstdout:\n${out}\nstderr:\n${err}")

if(EXPECT_RC STREQUAL "NONZERO")
  if(rc EQUAL 0 OR NOT rc MATCHES "^[0-9]+$")
    message(FATAL_ERROR "expected a non-zero exit code, got '${rc}'")
  endif()
elseif(NOT rc STREQUAL EXPECT_RC)
  message(FATAL_ERROR "expected exit code ${EXPECT_RC}, got '${rc}'")
endif()
if(NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_STDERR}'")
endif()
if(DEFINED OUT_DIR)
  file(GLOB generated "${OUT_DIR}/*")
  if(generated)
    message(FATAL_ERROR "files written despite the error: ${generated}")
  endif()
endif()
