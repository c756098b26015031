# Reliability (issue 10): the fuzz corpus and crash reproducers replayed through the fuzzers'
# entry points in the normal build, and the stages' exit code 2 on malformed input files.
set(MPPM_TEST_LIBS mppm_common)
mppm_add_gtest(test_reliability_corpus unit
  unit/test_reliability_corpus.cpp
  fuzz/fuzz_entry_points.cpp
)

# Each malformed scene of the corpus, run through the real executable: exit code 2, a message
# naming the file (or the --set option) and no output file.
if(TARGET mppm-preprocess)
  add_test(NAME reliability.preprocess_rejects_malformed_scenes
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:mppm-preprocess> -DMODE=scene
            -DINPUTS=${PROJECT_SOURCE_DIR}/tests/fuzz/corpus/scene
            -DWORK=${CMAKE_CURRENT_BINARY_DIR}/reliability_preprocess
            -P ${PROJECT_SOURCE_DIR}/tests/fuzz/expect_bad_input_exit.cmake)
  set_tests_properties(reliability.preprocess_rejects_malformed_scenes PROPERTIES LABELS unit TIMEOUT 300)
endif()
# Each malformed points file, given to the solver with a valid scene: exit code 2.
if(TARGET mppm-solve)
  add_test(NAME reliability.solve_rejects_malformed_points
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:mppm-solve> -DMODE=points
            -DINPUTS=${PROJECT_SOURCE_DIR}/tests/fuzz/corpus/point_cloud
            -DSCENE=${PROJECT_SOURCE_DIR}/tests/fuzz/corpus/scene/valid_crack_branching.yaml
            -DWORK=${CMAKE_CURRENT_BINARY_DIR}/reliability_solve
            -P ${PROJECT_SOURCE_DIR}/tests/fuzz/expect_bad_input_exit.cmake)
  set_tests_properties(reliability.solve_rejects_malformed_points PROPERTIES LABELS unit TIMEOUT 300)
endif()
