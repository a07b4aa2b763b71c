# libccd (libccd-dev), GJK/EPA/MPR collision detection between convex shapes: defines mrqp_dep::ccd
# when found. Optional: control/collision (and with it the `collisions` constraint kind of the
# scene files) is built only when it exists. Debian ships no static archive, so a static runtime
# build (MRQP_STATIC_RUNTIME) goes without it.
include_guard(GLOBAL)
find_package(ccd QUIET CONFIG)
if(ccd_FOUND AND TARGET ccd AND NOT MRQP_STATIC_RUNTIME)
  add_library(mrqp_dep::ccd INTERFACE IMPORTED GLOBAL)
  target_link_libraries(mrqp_dep::ccd INTERFACE ccd)
else()
  message(STATUS "mrqp: libccd not found (or a static runtime build): no collision avoidance (control/collision)")
endif()
