# End to end: the quickstart case through the three executables of this build, then its
# physics check (energy conserved, plate pulled apart symmetrically). Output goes to the build
# tree so the source tree stays clean.
add_test(NAME workflows.quickstart_end_to_end
  COMMAND make -C ${PROJECT_SOURCE_DIR}/workflows/quickstart all check
          MPPM_BIN=${CMAKE_BINARY_DIR}/bin OUT=${CMAKE_BINARY_DIR}/workflow-runs/quickstart THREADS=2)
set_tests_properties(workflows.quickstart_end_to_end PROPERTIES LABELS "regression" TIMEOUT 600)

# The shear-band case (workflows/shear-band, workflows/shear-band/README.md) in its reduced form: the five runs
# of the friction and dilatancy sweeps on the case's lattice with the case's 9 mm platen
# travel at 4x the platen speed (0.2 m/s, 0.05 s), then check_case.py --quick: two conjugate
# bands in every run, band angle growing with the dilatancy angle, peak load growing with the
# friction angle, energy balance below 1 %, run status. The micro-rotation ratio and the ridge
# fit are printed but asserted only by the full `make check` (README of the case).
# 5 runs of 7143 steps on 3372 points, two at a time, from scratch: about 13 s of CPU per run
# (65 s in all); 111 s wall measured with the 2 cores shared (load average 5).
add_test(NAME workflows.shear_band_quick
  COMMAND sh -c "make -s -C '${PROJECT_SOURCE_DIR}/workflows/shear-band' clean OUT='${CMAKE_BINARY_DIR}/workflow-runs/shear-band-quick' && make -j2 -C '${PROJECT_SOURCE_DIR}/workflows/shear-band' quick MPPM_BIN='${CMAKE_BINARY_DIR}/bin' OUT='${CMAKE_BINARY_DIR}/workflow-runs/shear-band-quick'")
set_tests_properties(workflows.shear_band_quick PROPERTIES LABELS "regression" TIMEOUT 600)

# The saturated shear-band case (workflows/saturated-shear-band/README.md) in its reduced form:
# case 1's quick loading (the platens at 0.2 m/s for 0.045 s, 9 mm, hold to 0.05 s) at
# dilatancy 15 and 0 deg, undrained (k = 1e-16 m^2) and dry, then check_case.py --quick: run
# status, energy balance, fluid mass balance at round-off, bands in the dry runs, suction in the
# bands and a raised peak and a later band at psi 15, neither at psi 0. The drained end
# (k = 1e-10) is only in the full `make check`. 2 saturated runs of 14 430 steps and 2 dry runs
# of 7 143 steps on 3372 points, two at a time: 96 s wall measured with the 2 cores shared
# (load average about 4); not yet timed on an idle machine.
add_test(NAME workflows.saturated_shear_band_quick
  COMMAND sh -c "make -s -C '${PROJECT_SOURCE_DIR}/workflows/saturated-shear-band' clean OUT='${CMAKE_BINARY_DIR}/workflow-runs/saturated-shear-band-quick' && make -j2 -C '${PROJECT_SOURCE_DIR}/workflows/saturated-shear-band' quick MPPM_BIN='${CMAKE_BINARY_DIR}/bin' OUT='${CMAKE_BINARY_DIR}/workflow-runs/saturated-shear-band-quick'")
set_tests_properties(workflows.saturated_shear_band_quick PROPERTIES LABELS "regression" TIMEOUT 600)

# The crack-initiation case (workflows/crack-initiation/README.md) in its quick form: the coarse level
# (dx = 1 mm) with each calibration through mppm-crack-initiation, then check_case.py --quick: the
# wave's arrival, the first break at the tip within the horizon band of Freund's start time, the order
# of the calibrations, the energy balance. Three runs of about 140-160 steps: 17-35 s measured with the
# 2 cores shared (most of it the model build).
add_test(NAME workflows.crack_initiation_quick
  COMMAND sh -c "make -s -C '${PROJECT_SOURCE_DIR}/workflows/crack-initiation' clean OUT='${CMAKE_BINARY_DIR}/workflow-runs/crack-initiation-quick' && make -C '${PROJECT_SOURCE_DIR}/workflows/crack-initiation' quick MPPM_BIN='${CMAKE_BINARY_DIR}/bin' OUT='${CMAKE_BINARY_DIR}/workflow-runs/crack-initiation-quick' THREADS=2")
set_tests_properties(workflows.crack_initiation_quick PROPERTIES LABELS "regression" TIMEOUT 300)

# The Kalthoff-Winkler case (workflows/kalthoff-winkler/README.md) in its quick form: the micro-polar
# run at dx = 1 mm to 50 us (its cracks have crossed the angle ring by then), then check_case.py's
# checks of one run: a crack leaves each notch tip toward the unstruck side, the two cracks are
# mirror images within 5 degrees, tip speeds below the Rayleigh speed, energy balance. The
# comparisons across spacings and models are the full case's (`make check`, which fails today:
# README of the case). About 12 s of CPU.
add_test(NAME workflows.kalthoff_winkler_quick
  COMMAND sh -c "make -s -C '${PROJECT_SOURCE_DIR}/workflows/kalthoff-winkler' clean OUT='${CMAKE_BINARY_DIR}/workflow-runs/kalthoff-winkler-quick' && make -j2 -C '${PROJECT_SOURCE_DIR}/workflows/kalthoff-winkler' quick MPPM_BIN='${CMAKE_BINARY_DIR}/bin' OUT='${CMAKE_BINARY_DIR}/workflow-runs/kalthoff-winkler-quick'")
set_tests_properties(workflows.kalthoff_winkler_quick PROPERTIES LABELS "regression" TIMEOUT 600)

# The case-level convergence study (workflows/case-convergence/README.md) in its quick form: the
# coarsest spacing of the shear-band and crack-branching cases at both horizon factors, estimated,
# run, postprocessed, reported and checked (the driver end to end; the convergence itself needs
# the full study on an idle machine). 4 runs, one at a time: 72 s measured with the 2 cores shared.
add_test(NAME workflows.case_convergence_quick
  COMMAND sh -c "rm -rf '${CMAKE_BINARY_DIR}/workflow-runs/case-convergence-quick' && make -s -C '${PROJECT_SOURCE_DIR}/workflows/case-convergence' QUICK=1 all report check MPPM_BIN='${CMAKE_BINARY_DIR}/bin' OUT='${CMAKE_BINARY_DIR}/workflow-runs/case-convergence-quick'")
set_tests_properties(workflows.case_convergence_quick PROPERTIES LABELS "regression" TIMEOUT 600)
