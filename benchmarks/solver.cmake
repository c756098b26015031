# mppm-bench-solver: bond updates per second of the solver kernel and whole steps.
add_executable(mppm-bench-solver bench_solver.cpp)
target_link_libraries(mppm-bench-solver PRIVATE mppm_solver mppm_warnings)
