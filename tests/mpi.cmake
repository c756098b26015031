# Tests of distributed runs (label mpi, in the default suite): each runs under mpirun with 1 to 4
# processes and 1 or 2 OpenMP threads each. As root (CI), OpenMPI asks for the two variables below;
# --oversubscribe lets 4 processes share 2 cores, and --bind-to none lets each one's threads use
# both.
add_executable(test_mpi_reductions mpi/test_mpi_reductions.cpp)
target_link_libraries(test_mpi_reductions PRIVATE GTest::gtest mppm_solver mppm_warnings MPI::MPI_C)
set(MPPM_MPI_ENVIRONMENT OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
foreach(processes 1 2 3 4)
  foreach(threads 1 2)
    set(name mpi.reductions.np${processes}.threads${threads})
    add_test(NAME ${name}
      COMMAND ${MPIEXEC_EXECUTABLE} --oversubscribe --bind-to none ${MPIEXEC_NUMPROC_FLAG} ${processes}
              $<TARGET_FILE:test_mpi_reductions>)
    set_tests_properties(${name} PROPERTIES LABELS mpi TIMEOUT 120
      ENVIRONMENT "${MPPM_MPI_ENVIRONMENT};OMP_NUM_THREADS=${threads}")
  endforeach()
endforeach()
