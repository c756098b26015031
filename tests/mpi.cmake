# Tests of distributed runs (label mpi, in the default suite): each runs under mpirun with 1 to 4
# processes and 1 or 2 OpenMP threads each. As root (CI), OpenMPI asks for the two variables below;
# --oversubscribe lets 4 processes share 2 cores, and --bind-to none lets each one's threads use
# both. Oversubscribed, OpenMP threads that spin at a barrier take the cores from the processes they
# wait for (measured: a damage test 4x slower with 2 threads than with 1): the tests make them
# sleep instead (OMP_WAIT_POLICY=passive; no result depends on it).
set(MPPM_MPI_ENVIRONMENT OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive)

# mppm_add_mpi_test(NAME SOURCES...): one executable, run as mpi.NAME.npP.threadsT.
function(mppm_add_mpi_test name)
  add_executable(test_mpi_${name} ${ARGN} mpi/mpi_test_main.cpp)
  target_link_libraries(test_mpi_${name} PRIVATE GTest::gtest mppm_solver mppm_warnings MPI::MPI_C)
  foreach(processes 1 2 3 4)
    foreach(threads 1 2)
      set(test mpi.${name}.np${processes}.threads${threads})
      add_test(NAME ${test}
        COMMAND ${MPIEXEC_EXECUTABLE} --oversubscribe --bind-to none ${MPIEXEC_NUMPROC_FLAG} ${processes}
                $<TARGET_FILE:test_mpi_${name}>)
      set_tests_properties(${test} PROPERTIES LABELS mpi TIMEOUT 120
        ENVIRONMENT "${MPPM_MPI_ENVIRONMENT};OMP_NUM_THREADS=${threads}")
    endforeach()
  endforeach()
endfunction()

mppm_add_mpi_test(reductions mpi/test_mpi_reductions.cpp)
mppm_add_mpi_test(forces mpi/test_mpi_forces.cpp)
mppm_add_mpi_test(run mpi/test_mpi_run.cpp)

# mppm-solve under mpirun (tests/mpi/distributed_solve.sh, which says what each mode checks): the run
# directory of 1 to 4 processes x 1 and 2 threads the one-process run's byte for byte (a 2-D plate
# with a pre-crack and tractions, a 3-D notched bar, the viscoplastic shear-band specimen, the plate
# cracking with damage and viscoplasticity); checkpoints written on N processes continued
# on M; a NaN on the last of 3 processes; refusals and an interruption reaching every process with
# one message.
set(MPPM_DISTRIBUTED_SOLVE ${PROJECT_SOURCE_DIR}/tests/mpi/distributed_solve.sh)
set(MPPM_TEST_SCENES ${PROJECT_SOURCE_DIR}/tests/data/scenes)
function(mppm_add_distributed_solve_test name mode scene)
  add_test(NAME mpi.solve.${name}
    COMMAND sh ${MPPM_DISTRIBUTED_SOLVE} ${mode} ${MPIEXEC_EXECUTABLE} $<TARGET_FILE_DIR:mppm-solve>
            ${MPPM_TEST_SCENES}/${scene} ${CMAKE_CURRENT_BINARY_DIR}/mpi_solve_${name} ${ARGN})
  set_tests_properties(mpi.solve.${name} PROPERTIES LABELS mpi TIMEOUT 120 ENVIRONMENT "${MPPM_MPI_ENVIRONMENT}")
endfunction()
mppm_add_distributed_solve_test(plate_2d same mpi_plate.yaml 1 2 3 4)
mppm_add_distributed_solve_test(notched_bar_3d same mpi_notched_3d.yaml 2 3)
mppm_add_distributed_solve_test(shear_band_viscoplastic same mpi_shear_band.yaml 2 3 4)
mppm_add_distributed_solve_test(nan_on_last_process nan mpi_plate.yaml)
mppm_add_distributed_solve_test(plate_damage_viscoplastic same mpi_plate_damage.yaml 1 2 3 4)
mppm_add_distributed_solve_test(estimate_refused refused mpi_plate.yaml "run it on one process" --estimate)
# Each process checks its share against its machine's memory over the processes on it: with a
# budget of 10 MB for the machine (5 MB each) the plate's share does not fit.
mppm_add_distributed_solve_test(memory_refused refused mpi_plate.yaml
  "process 0 of 2, one of 2 sharing this machine's memory.*spread the processes over more machines")
set_property(TEST mpi.solve.memory_refused APPEND PROPERTY ENVIRONMENT MPPM_MEMORY_AVAILABLE=10000000)
# Checkpoints: the cracking plate (bonds broken and their work, detached points, the crack-arrival
# table, the plastic state) written on 4 processes, continued on 3 and 1; written on 1, continued
# on 2 (the loaded surfaces' rows of the integrator); with damping every point's (written on 3,
# continued on 2); the shear-band specimen's plastic state (written on 2, continued on 3).
mppm_add_distributed_solve_test(checkpoint_damage_4_to_3_and_1 checkpoint mpi_plate_damage.yaml 4 3 1)
mppm_add_distributed_solve_test(checkpoint_1_to_2 checkpoint mpi_plate.yaml 1 2)
mppm_add_distributed_solve_test(checkpoint_damped_3_to_2 checkpoint mpi_plate.yaml 3 2 -- --set numerics.damping=1000)
mppm_add_distributed_solve_test(checkpoint_viscoplastic_2_to_3 checkpoint mpi_shear_band.yaml 2 3 --
  --set output.checkpoint_interval=0.3ms)
mppm_add_distributed_solve_test(run_directory_taken taken mpi_plate.yaml)
mppm_add_distributed_solve_test(interrupted interrupt mpi_plate.yaml)
