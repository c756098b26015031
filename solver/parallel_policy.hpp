// When a loop is worth running on several threads. Small lattices are faster on one thread (a
// parallel region costs microseconds, and far more on an oversubscribed machine); the results
// are the same bits either way, since every loop writes per-point data only.
#pragma once
#include <omp.h>

#include <cstddef>
#include <exception>

namespace mppm::solver {

struct ParallelThresholds {
  std::size_t bonds = 100000;  // loops over bonds (force kernel, families, shape tensors, cuts)
  std::size_t points = 4096;   // loops doing a few operations per point (integrator)
  std::size_t blocks = 64;     // loops of per-point stiffness blocks (an eigenvalue problem over
                               // the point's bonds each: the breakage update's stability check)
};

// Process-wide thresholds; tests lower them to exercise the threaded paths on small lattices.
inline ParallelThresholds& parallel_thresholds() {
  static ParallelThresholds thresholds;
  return thresholds;
}

inline bool thread_bond_loop(std::size_t bonds) { return bonds >= parallel_thresholds().bonds; }
inline bool thread_point_loop(std::size_t points) { return points >= parallel_thresholds().points; }
inline bool thread_block_loop(std::size_t blocks) { return blocks >= parallel_thresholds().blocks; }

// Two independent tasks, side by side on two threads when the process has them (runs_side_by_side),
// else one after the other. Each must write only its own data. A parallel region inside a task
// runs on that task's thread alone (OpenMP's default of one active level; with nesting turned on
// it would take more threads, and give the same bits, as every loop of the solver does), so each
// task gives the bits it gives on its own. An exception from either is rethrown here once both
// have ended (the first task's if both failed).
inline bool runs_side_by_side() { return omp_get_max_threads() > 1; }
template <class First, class Second>
void side_by_side(First&& first, Second&& second) {
  std::exception_ptr failed[2];
  const auto guarded = [&failed](int k, auto& task) {
    try {
      task();
    } catch (...) {
      failed[k] = std::current_exception();
    }
  };
#pragma omp parallel sections num_threads(2) if (runs_side_by_side())
  {
#pragma omp section
    guarded(0, first);
#pragma omp section
    guarded(1, second);
  }
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace mppm::solver
