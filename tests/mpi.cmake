# Tests of distributed runs (label mpi, in the default suite): each runs under mpirun with 1 to 4
# processes and 1 or 2 OpenMP threads each. As root (CI), OpenMPI asks for the two variables below;
# --oversubscribe lets 4 processes share 2 cores, and --bind-to none lets each one's threads use
# both.
set(MPPM_MPI_ENVIRONMENT OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)

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

# mppm-solve does not run across processes yet: under mpirun it refuses (exit 2, one message from the
# first process) before it reads or writes anything, instead of running N copies into one directory.
add_test(NAME mpi.solve_refuses_several_processes
  COMMAND sh -c "rm -rf mpi_refused_run; ${MPIEXEC_EXECUTABLE} --oversubscribe -np 2 $<TARGET_FILE:mppm-solve> \
${PROJECT_SOURCE_DIR}/tests/data/scenes/solver_case1_block.yaml --points absent.vtp -o mpi_refused_run 2> refused.txt; \
code=$?; cat refused.txt; test $code -ne 0 && test ! -e mpi_refused_run && \
test $(grep -c 'a run across processes is not built yet' refused.txt) -eq 1 && \
test $(grep -c 'Exit code:    2' refused.txt) -eq 1"
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(mpi.solve_refuses_several_processes PROPERTIES LABELS mpi TIMEOUT 60
  ENVIRONMENT "${MPPM_MPI_ENVIRONMENT}")
