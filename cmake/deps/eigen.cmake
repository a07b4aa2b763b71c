# Eigen 3 (libeigen3-dev): defines mrqp_dep::eigen. Required by every part of the tree.
# The other modules of this folder follow the same pattern: cmake/deps/README.md.
include_guard(GLOBAL)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
add_library(mrqp_dep::eigen INTERFACE IMPORTED GLOBAL)
target_link_libraries(mrqp_dep::eigen INTERFACE Eigen3::Eigen)
