# Google Benchmark (libbenchmark-dev): defines mrqp_dep::benchmark. Host tools only (bench_model,
# bench_codec); a target build (cross or static) does not include it.
include_guard(GLOBAL)
find_package(benchmark REQUIRED)
add_library(mrqp_dep::benchmark INTERFACE IMPORTED GLOBAL)
target_link_libraries(mrqp_dep::benchmark INTERFACE benchmark::benchmark)
