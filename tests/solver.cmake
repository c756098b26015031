# Tests of the solver: unit tests of the model and driver, verification against
# analytic solutions.
set(MPPM_TEST_LIBS mppm_solver)
mppm_add_gtest(test_solver_unit unit
  unit/test_solver_kinematics.cpp
  unit/test_solver_energy_gradient.cpp
  unit/test_solver_momentum.cpp
  unit/test_solver_time_step.cpp
  unit/test_solver_run.cpp
  unit/test_solver_families.cpp
  unit/test_solver_command.cpp
  unit/test_solver_boundary_conditions.cpp
  unit/test_solver_damage.cpp
)
set(MPPM_TEST_LIBS mppm_solver mppm_verification_problems)  # tests/verification/problems
mppm_add_gtest(test_solver_verification verification
  verification/test_solver_waves.cpp
  verification/test_solver_layer_shear.cpp
  verification/test_solver_energy_balance.cpp
  verification/test_solver_crack_energy.cpp
)
