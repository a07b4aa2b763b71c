# urdfdom (liburdfdom-dev), the URDF parser: defines mrqp_dep::urdfdom. Host only (model_gen, the
# tests' reference model, bench_model); a target build (cross or static) does not include it.
include_guard(GLOBAL)
find_package(urdfdom REQUIRED)
add_library(mrqp_dep::urdfdom INTERFACE IMPORTED GLOBAL)
target_link_libraries(mrqp_dep::urdfdom INTERFACE urdfdom::urdfdom_model)
