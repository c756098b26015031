// Test helper: runs a block at a given OpenMP thread count with every loop threaded (even on the
// tests' small lattices), and restores both on leaving it, by return or by exception.
#pragma once
#include <omp.h>

#include "solver/parallel_policy.hpp"

namespace mppm::solver::testing {

class ThreadCountScope {
 public:
  explicit ThreadCountScope(int threads) : saved_threads_(omp_get_max_threads()), saved_(parallel_thresholds()) {
    parallel_thresholds() = ParallelThresholds{1, 1, 1};
    omp_set_num_threads(threads);
  }
  ~ThreadCountScope() {
    omp_set_num_threads(saved_threads_);
    parallel_thresholds() = saved_;
  }
  ThreadCountScope(const ThreadCountScope&) = delete;
  ThreadCountScope& operator=(const ThreadCountScope&) = delete;

 private:
  int saved_threads_;
  ParallelThresholds saved_;
};

}  // namespace mppm::solver::testing
