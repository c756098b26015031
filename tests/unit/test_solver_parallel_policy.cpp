// run_tasks and side_by_side (solver/parallel_policy.hpp): independent tasks, on the threads when
// the process has them. All always run to their end; a failure in any reaches the caller after all
// ended, the first task's in task order when several fail.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/parallel_policy.hpp"

namespace mppm::solver {
namespace {

TEST(SolverParallelPolicy, SideBySideRunsBothTasksOnOneAndTwoThreads) {
  const int saved = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    EXPECT_EQ(runs_side_by_side(), threads > 1);
    int first = 0, second = 0;
    side_by_side([&] { first = 1; }, [&] { second = 2; });
    EXPECT_EQ(first, 1) << threads << " threads";
    EXPECT_EQ(second, 2) << threads << " threads";
  }
  omp_set_num_threads(saved);
}

TEST(SolverParallelPolicy, SideBySideRethrowsAFailureOnceBothTasksEnded) {
  const int saved = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    std::atomic<int> ended{0};
    EXPECT_THROW(side_by_side([&] { ++ended; }, [&] { throw std::runtime_error("second"); }), std::runtime_error);
    EXPECT_THROW(side_by_side([] { throw std::invalid_argument("first"); }, [&] { ++ended; }), std::invalid_argument);
    // Both failing: the first task's failure, and the second still ran to its throw.
    try {
      side_by_side([] { throw std::invalid_argument("first"); },
                   [&] {
                     ++ended;
                     throw std::runtime_error("second");
                   });
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "first");
    }
    EXPECT_EQ(ended.load(), 3) << threads << " threads";
  }
  omp_set_num_threads(saved);
}

// More tasks than threads: every task runs once, and of several failures the first in task order
// is the one rethrown, whichever thread ran it.
TEST(SolverParallelPolicy, RunTasksRunsEveryTaskAndRethrowsTheFirstFailure) {
  const int saved = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    std::vector<int> runs(7, 0);
    std::vector<std::function<void()>> tasks;
    for (std::size_t k = 0; k < runs.size(); ++k)
      tasks.emplace_back([&runs, k] {
        ++runs[k];
        if (k == 2 || k == 5) throw std::runtime_error("task " + std::to_string(k));
      });
    try {
      run_tasks(tasks);
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 2") << threads << " threads";
    }
    EXPECT_EQ(runs, std::vector<int>(7, 1)) << threads << " threads";
  }
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace mppm::solver
