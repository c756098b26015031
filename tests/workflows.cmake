# End to end: the quickstart case through the three executables of this build, then its
# physics check (energy conserved, plate pulled apart symmetrically). Output goes to the build
# tree so the source tree stays clean.
add_test(NAME workflows.quickstart_end_to_end
  COMMAND make -C ${PROJECT_SOURCE_DIR}/workflows/quickstart all check
          MPPM_BIN=${CMAKE_BINARY_DIR}/bin OUT=${CMAKE_BINARY_DIR}/workflow-runs/quickstart THREADS=2)
set_tests_properties(workflows.quickstart_end_to_end PROPERTIES LABELS "regression" TIMEOUT 600)
