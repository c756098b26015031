# mppm-bench-solver: bond updates per second of the solver kernel and whole steps.
add_executable(mppm-bench-solver bench_solver.cpp)
target_link_libraries(mppm-bench-solver PRIVATE mppm_solver mppm_warnings)
# mppm-damage-calibration: the released fraction of the `dissipation` calibration of the damage
# effect (the table in solver/damage_calibration.cpp). Uses the verification problems' crack strip.
if(NOT TARGET mppm_verification_problems)
  add_subdirectory(${PROJECT_SOURCE_DIR}/tests/verification/problems ${CMAKE_BINARY_DIR}/verification_problems)
endif()
add_executable(mppm-damage-calibration ${CMAKE_CURRENT_LIST_DIR}/damage_calibration.cpp)
target_link_libraries(mppm-damage-calibration PRIVATE mppm_verification_problems mppm_solver mppm_warnings)
# mppm-bench-checkpoint: bytes and seconds of one checkpoint of a 1-million-point 3-D model.
add_executable(mppm-bench-checkpoint ${CMAKE_CURRENT_LIST_DIR}/bench_checkpoint.cpp)
target_link_libraries(mppm-bench-checkpoint PRIVATE mppm_solver mppm_warnings)
# mppm-crack-initiation: crack start under a stress wave against Freund's prediction, per horizon and
# calibration (workflows/crack-initiation). Uses the verification problems' stress-wave plate.
add_executable(mppm-crack-initiation ${CMAKE_CURRENT_LIST_DIR}/crack_initiation.cpp)
target_link_libraries(mppm-crack-initiation PRIVATE mppm_verification_problems mppm_solver mppm_warnings)
# mppm-bench-mpi: the distributed integrator's throughput and halo traffic under mpirun
# (workflows/benchmarks: make mpi).
add_executable(mppm-bench-mpi ${CMAKE_CURRENT_LIST_DIR}/bench_mpi.cpp)
target_link_libraries(mppm-bench-mpi PRIVATE mppm_solver mppm_warnings MPI::MPI_C)
target_include_directories(mppm-bench-mpi PRIVATE ${PROJECT_SOURCE_DIR})
