# Tests of the viscoplastic solver: the return map wired into mppm-solve.
set(MPPM_TEST_LIBS mppm_solver)
mppm_add_gtest(test_solver_viscoplastic_verification verification
  verification/test_solver_viscoplastic_compression.cpp
)
mppm_add_gtest(test_solver_viscoplastic_unit unit
  unit/test_solver_viscoplastic_run.cpp
)
