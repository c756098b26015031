# The stability suite (tests/stability/README.md). One executable; every test runs in
# its short form in the default suite (label `stability`), and the cases with a long form run
# again with MPPM_STABILITY_FORM=long under the labels `stability;slow` (10^5 steps). Each test
# writes its measured margin to ${CMAKE_BINARY_DIR}/stability/<form>/<case>.json, which
# `make -C workflows stability-report` renders into the README's table.
if(TARGET mppm_solver AND TARGET mppm_preprocess)
  set(MPPM_TEST_LIBS mppm_solver mppm_preprocess)
  mppm_add_gtest(test_stability stability
    stability/stability_support.cpp
    stability/test_stability_length_scale.cpp
    stability/test_stability_energy_balance.cpp
    stability/test_stability_near_incompressible.cpp
    stability/test_stability_softening.cpp
    stability/test_stability_hourglass.cpp
    stability/test_stability_guards.cpp
    stability/test_stability_refusals.cpp
    stability/test_stability_fragmentation.cpp
    stability/test_stability_damage_runs.cpp
  )
  # The exit-code cases run the stage executables of this build.
  add_dependencies(test_stability mppm-solve mppm-preprocess)

  # Long forms: the same checks over 10^5 steps.
  foreach(suite StabilityLengthScale StabilityEnergyBalance StabilityNearIncompressible StabilityHourglass
                StabilitySoftening StabilityFragmentation StabilityCrackBranchingRate StabilityNotchedImpact3d)
    add_test(NAME stability.long.${suite}
      COMMAND test_stability --gtest_filter=${suite}.*)
    set_tests_properties(stability.long.${suite} PROPERTIES
      LABELS "stability;slow" ENVIRONMENT "MPPM_STABILITY_FORM=long" TIMEOUT 3600)
  endforeach()
endif()
