// When a loop is worth running on several threads. Small lattices are faster on one thread (a
// parallel region costs microseconds, and far more on an oversubscribed machine); the results
// are the same bits either way, since every loop writes per-point data only.
#pragma once
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <vector>

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

// Whether tasks can run side by side: the process has more than one thread.
inline bool runs_side_by_side() { return omp_get_max_threads() > 1; }

// Independent tasks on the threads, each on one (the next free thread takes the next task), or one
// after the other on one thread. Each must write only its own data. A parallel region inside a
// task runs on that task's thread alone (OpenMP's default of one active level; with nesting turned
// on it would take more threads, and give the same bits, as every loop of the solver does), so each
// task gives the bits it gives on its own. An exception cannot leave an OpenMP region: each task's
// is kept, and the first in task order is rethrown once all the tasks have ended.
inline void run_tasks(const std::vector<std::function<void()>>& tasks) {
  const auto count = static_cast<std::int64_t>(tasks.size());
  std::vector<std::exception_ptr> failed(tasks.size());
  const int threads = static_cast<int>(std::min<std::int64_t>(count, omp_get_max_threads()));
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto u = static_cast<std::size_t>(k);
    try {
      tasks[u]();
    } catch (...) {
      failed[u] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
}

// Two independent tasks side by side (run_tasks).
template <class First, class Second>
void side_by_side(First&& first, Second&& second) {
  run_tasks({std::ref(first), std::ref(second)});
}

}  // namespace mppm::solver
