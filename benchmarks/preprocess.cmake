# mppm-bench-preprocess: a 3-D CAD part to ~1e6 points; time per phase and peak memory.
add_executable(mppm-bench-preprocess ${CMAKE_CURRENT_LIST_DIR}/bench_preprocess.cpp)
target_link_libraries(mppm-bench-preprocess PRIVATE mppm_preprocess mppm_common mppm_warnings OpenMP::OpenMP_CXX)
target_compile_definitions(mppm-bench-preprocess PRIVATE MPPM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
