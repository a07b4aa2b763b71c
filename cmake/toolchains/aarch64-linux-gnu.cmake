# Cross build for an aarch64 (arm64) Linux robot computer with Debian's cross compiler
# g++-aarch64-linux-gnu (docs/cross-compiling.md). Install what it needs with
#   tools/setup-deps.sh --target aarch64
# and configure with
#   cmake --preset aarch64          (CMakePresets.json), or
#   cmake -S . -B build/aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake
#
# Libraries of the target come from Debian's arm64 packages through multiarch (no sysroot): they
# install into /usr/lib/aarch64-linux-gnu, which both CMake (CMAKE_LIBRARY_ARCHITECTURE, detected
# from the compiler) and the cross linker search. Header-only, architecture-independent packages
# (Eigen, Catch2) are used from the host's /usr/include as they are: the cross compiler searches
# /usr/include after its own /usr/aarch64-linux-gnu/include, so the host's C library headers never
# shadow the target's.
#
# Test programs and every add_test() of an executable target run under qemu-aarch64 user-mode
# emulation (CMAKE_CROSSCOMPILING_EMULATOR), catch_discover_tests() included.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(MRQP_CROSS_TRIPLET aarch64-linux-gnu)
set(CMAKE_C_COMPILER ${MRQP_CROSS_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${MRQP_CROSS_TRIPLET}-g++)

# Programs found with find_program() are host programs; libraries, headers and packages are
# searched in the usual places (multiarch keeps the host's and the target's libraries apart).
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)

# pkg-config for the target: Debian's triplet wrapper if present, else the host's pkg-config
# restricted to the target's .pc files.
find_program(MRQP_CROSS_PKG_CONFIG ${MRQP_CROSS_TRIPLET}-pkg-config)
if(MRQP_CROSS_PKG_CONFIG)
  set(PKG_CONFIG_EXECUTABLE ${MRQP_CROSS_PKG_CONFIG} CACHE FILEPATH "pkg-config for the target")
else()
  set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/${MRQP_CROSS_TRIPLET}/pkgconfig:/usr/share/pkgconfig")
endif()

# qemu-aarch64 through a wrapper that points it at the cross C library (QEMU_LD_PREFIX): one
# program, no arguments, because catch_discover_tests() passes the emulator through a
# command line where a list would be split. Override with -DCMAKE_CROSSCOMPILING_EMULATOR=...
if(NOT DEFINED CMAKE_CROSSCOMPILING_EMULATOR)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${CMAKE_CURRENT_LIST_DIR}/qemu-aarch64.sh")
endif()
