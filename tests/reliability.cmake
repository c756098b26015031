# Reliability: the fuzz corpus and crash reproducers replayed through the fuzzers'
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
  # The points files that crashed VTK 9.1's XML reader (segfault, abort, huge allocation) before
  # the points file got its own strict reader: now exit code 2 with a message, like the rest.
  add_test(NAME reliability.solve_rejects_fuzz_crash_points
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:mppm-solve> -DMODE=points
            -DINPUTS=${PROJECT_SOURCE_DIR}/tests/fuzz/crashes/point_cloud
            -DSCENE=${PROJECT_SOURCE_DIR}/tests/fuzz/corpus/scene/valid_crack_branching.yaml
            -DWORK=${CMAKE_CURRENT_BINARY_DIR}/reliability_solve_crashes
            -P ${PROJECT_SOURCE_DIR}/tests/fuzz/expect_bad_input_exit.cmake)
  set_tests_properties(reliability.solve_rejects_fuzz_crash_points PROPERTIES LABELS unit TIMEOUT 300)
endif()

# Write-failure safety of atomic_file: a failed write (RLIMIT_FSIZE, EFBIG as on a full disk)
# throws, names the file and keeps the previous file; no temporary is left.
mppm_add_gtest(test_atomic_file unit unit/test_atomic_file.cpp)
# The memory estimate: bond count, refusal with the advice, MemAvailable, and against the peak
# resident memory of a real mppm-solve run (runs mppm-preprocess and mppm-solve from bin/).
mppm_add_gtest(test_memory_estimate unit unit/test_memory_estimate.cpp)
# Refusal and --force replacement of an output directory, and the same through the real stages
# (mppm-solve, mppm-postprocess) with write failures of mppm-preprocess and mppm-solve.
mppm_add_gtest(test_output_directory unit unit/test_output_directory.cpp)
mppm_add_gtest(test_output_safety unit unit/test_output_safety.cpp)
# The points file's own reader on every encoding VTK writes (VTK's writer makes the variants).
set(MPPM_TEST_LIBS mppm_common VTK::IOXML VTK::CommonDataModel VTK::CommonCore)
mppm_add_gtest(test_vtk_xml_reader unit unit/test_vtk_xml_reader.cpp)
set(MPPM_TEST_LIBS mppm_common)
# Checkpoint and restart: a stopped run continued with restart() / mppm-solve --restart
# gives the bytes of the uninterrupted run (elastic, damage, viscoplastic; after SIGTERM and
# kill -9 of the real executable), a failed checkpoint write keeps the previous checkpoint, and a
# corrupted checkpoint, a changed scene, points or tables are refused.
set(MPPM_TEST_LIBS mppm_solver)
mppm_add_gtest(test_checkpoint_restart unit unit/test_checkpoint_restart.cpp)
set(MPPM_TEST_LIBS mppm_common)
mppm_add_gtest(test_restart_process unit unit/test_restart_process.cpp)
