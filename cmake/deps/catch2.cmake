# Catch2 v2 (catch2): defines mrqp_dep::catch2 and, through the package's Catch module,
# catch_discover_tests(). Required when the tests are built (MRQP_BUILD_TESTS).
include_guard(GLOBAL)
find_package(Catch2 2 REQUIRED)
include(Catch)
add_library(mrqp_dep::catch2 INTERFACE IMPORTED GLOBAL)
target_link_libraries(mrqp_dep::catch2 INTERFACE Catch2::Catch2)
