# Warnings as errors for every target of the project, and the sanitizer build.
add_library(mrqp_warnings INTERFACE)
target_compile_options(mrqp_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Werror>
  $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic -Werror>)

if(MRQP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
  add_compile_definitions(MRQP_SANITIZED=1)
endif()

# Instruction set of the machine the programs run on, e.g. -DMRQP_ARCH=x86-64-v3 (AVX2 + FMA) or
# armv8.2-a: the dense linear algebra of the QP then uses the wide vector units (docs/BENCHMARKS.md
# gives figures with and without). Empty: the compiler's portable default.
set(MRQP_ARCH "" CACHE STRING "Target instruction set for -march= (empty: compiler default)")
if(MRQP_ARCH)
  add_compile_options(-march=${MRQP_ARCH})
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC 12 reports array-bounds / maybe-uninitialized / stringop-overflow warnings inside its own
    # AVX intrinsic headers when Eigen vectorises small fixed-size objects (false positives that
    # -Werror would turn into build failures); every other warning stays an error.
    add_compile_options(-Wno-array-bounds -Wno-maybe-uninitialized -Wno-stringop-overflow)
  endif()
endif()
