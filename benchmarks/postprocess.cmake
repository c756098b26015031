# mppm-bench-postprocess: postprocessing a million-point snapshot series (time, peak memory).
# It generates its series with the postprocessor tests' run-directory generator.
add_executable(mppm-bench-postprocess
  ${CMAKE_CURRENT_SOURCE_DIR}/postprocess_benchmark.cpp
  ${PROJECT_SOURCE_DIR}/tests/unit/test_post_run_fixture.cpp)
target_include_directories(mppm-bench-postprocess PRIVATE ${PROJECT_SOURCE_DIR}/tests/unit)
target_link_libraries(mppm-bench-postprocess PRIVATE mppm_postprocess mppm_warnings)
