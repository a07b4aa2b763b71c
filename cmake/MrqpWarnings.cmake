# The one warning set of the whole tree, as errors, and the sanitizer build.
#
# MRQP_WARNINGS applies to every target of the project (add_compile_options at the top directory):
# the runtime, the drivers, the generated model code, the tools and the tests alike. Folders may
# add warnings of their own (firmware_if adds C-only firmware checks) but none is switched off,
# whatever MRQP_ARCH or the build type. Third-party headers (Eigen, yaml-cpp, urdfdom, Catch2) come
# in through imported targets, hence as system headers, and do not warn.
include_guard(GLOBAL)
# Errors everywhere but in the fuzz preset (tests/fuzz), which compiles the tree with clang: there
# the same warnings are reported, but a warning only clang gives (an unused inline function of the
# generated code) does not stop the fuzzing; the GCC builds keep them errors.
option(MRQP_WARNINGS_AS_ERRORS "Compile with -Werror (every preset does; OFF to see all warnings of a new compiler at once)" ON)
set(MRQP_WARNINGS
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
  $<$<COMPILE_LANGUAGE:CXX>:-Wnon-virtual-dtor>
  $<$<BOOL:${MRQP_WARNINGS_AS_ERRORS}>:-Werror>)
add_compile_options(${MRQP_WARNINGS})

# The same set as a target, for the targets that name it (and for a folder built on its own).
add_library(mrqp_warnings INTERFACE)
target_compile_options(mrqp_warnings INTERFACE ${MRQP_WARNINGS})

if(MRQP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
  add_compile_definitions(MRQP_SANITIZED=1)
  # GCC 12's flow analysis reports false "may be used uninitialized" inside libstdc++ (std::function
  # in <regex>, instantiated by Catch2) once the sanitizers instrument the code at -O1. The
  # release build keeps the warning as an error; the sanitizer build checks memory at run time.
  add_compile_options(-Wno-maybe-uninitialized)
endif()

# Instruction set of the machine the programs run on, e.g. -DMRQP_ARCH=x86-64-v3 (AVX2 + FMA) or
# armv8.2-a: the dense linear algebra of the QP then uses the wide vector units (docs/BENCHMARKS.md
# gives figures with and without). Empty: the compiler's portable default. It changes code
# generation only; the warning set above stays as it is (but for the one GCC false positive below).
set(MRQP_ARCH "" CACHE STRING "Target instruction set for -march= (empty: compiler default)")
if(MRQP_ARCH)
  add_compile_options(-march=${MRQP_ARCH})
  # GCC 12 with AVX reports "array subscript __m256d_u[0] is partly outside array bounds" for
  # Eigen's fixed-size 2-vectors (a 4-wide packet load on a branch that size 2 never takes, e.g.
  # the door model's configuration in ModelEntity): a false positive of its flow analysis. It stays
  # a warning there; the portable builds keep it an error.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-Wno-error=array-bounds>)
  endif()
endif()
