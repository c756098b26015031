# The accuracy-cost study (workflows/accuracy-cost): its quick form runs mppm-accuracy
# over small sweeps (about 10 s) and checks the trends: the error falls with the spacing at a
# fixed horizon factor at the expected rate, the cost grows like dx^-(d+1). It starts from
# scratch every time (`clean`). The verification problems it shares with the verification tests
# are the library mppm_verification_problems (tests/verification/problems).
if(NOT TARGET mppm_verification_problems)
  add_subdirectory(${PROJECT_SOURCE_DIR}/tests/verification/problems ${CMAKE_BINARY_DIR}/verification_problems)
endif()
if(MPPM_BUILD_BENCHMARKS)  # mppm-accuracy is built with the benchmarks
  add_test(NAME workflows.accuracy_cost_quick
    COMMAND make -C ${PROJECT_SOURCE_DIR}/workflows/accuracy-cost clean check QUICK=1
            MPPM_BIN=${CMAKE_BINARY_DIR}/bin OUT=${CMAKE_BINARY_DIR}/workflow-runs/accuracy-cost-quick)
  set_tests_properties(workflows.accuracy_cost_quick PROPERTIES LABELS "verification" TIMEOUT 120)
endif()
