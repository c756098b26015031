# Tests of the solver: unit tests of the model and driver, verification against
# analytic solutions.
set(MPPM_TEST_LIBS mppm_solver)
mppm_add_gtest(test_solver_unit unit
  unit/test_exact_sum.cpp
  unit/test_distributed_partition.cpp
  unit/test_solver_kinematics.cpp
  unit/test_solver_energy_gradient.cpp
  unit/test_solver_momentum.cpp
  unit/test_solver_time_step.cpp
  unit/test_solver_parallel_policy.cpp
  unit/test_solver_model_patch.cpp
  unit/test_solver_bond_sums.cpp
  unit/test_solver_bond_products.cpp
  unit/test_solver_run.cpp
  unit/test_solver_families.cpp
  unit/test_solver_command.cpp
  unit/test_solver_start_up.cpp
  unit/test_solver_boundary_conditions.cpp
  unit/test_solver_damage.cpp
  unit/test_solver_crack_area.cpp
  unit/test_solver_cosserat_law.cpp
  unit/test_solver_pore_fluid.cpp
  unit/test_run_estimate.cpp
  unit/test_solver_fluid_boundaries.cpp
  unit/test_solver_retention_curve.cpp
  unit/test_solver_unsaturated.cpp
  unit/test_huge_page_allocation.cpp
  ${PROJECT_SOURCE_DIR}/solver/huge_page_allocation.cpp
)
set(MPPM_TEST_LIBS mppm_solver mppm_verification_problems)  # tests/verification/problems
mppm_add_gtest(test_solver_verification verification
  verification/test_solver_waves.cpp
  verification/test_solver_layer_shear.cpp
  verification/test_solver_energy_balance.cpp
  verification/test_solver_crack_energy.cpp
  verification/test_solver_crack_initiation.cpp
  verification/test_solver_pore_fluid_flow.cpp
  verification/test_solver_flow_super_step.cpp
  verification/test_solver_pore_fluid_boundaries.cpp
  verification/test_solver_pore_fluid_mandel.cpp
  verification/test_richards_reference.cpp
  verification/test_solver_unsaturated_infiltration.cpp
)
# The energies are computed by their own file's code, not the force kernel's (compiled with other
# options), only if the two files share no out-of-line inline function
# (cmake/check_kernel_objects.cmake says why).
add_test(NAME SolverBuild.EnergiesShareNoArithmeticWithTheForceKernel
  COMMAND ${CMAKE_COMMAND} -DNM=${CMAKE_NM} "-DOBJECTS=$<JOIN:$<TARGET_OBJECTS:mppm_solver>,|>"
          -P ${PROJECT_SOURCE_DIR}/cmake/check_kernel_objects.cmake)
set_tests_properties(SolverBuild.EnergiesShareNoArithmeticWithTheForceKernel PROPERTIES LABELS unit)
