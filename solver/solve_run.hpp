// One run of mppm-solve as a library call: scene + points -> run directory (SCENE.md).
// Throws InputError for bad input (exit 2) and NumericalFailure after writing the run
// directory up to the last good snapshot (exit 3).
#pragma once
#include <cstdint>
#include <string>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"

namespace mppm::solver {

struct SolveOptions {
  std::string run_directory;
  std::string points_file = "points";  // named in messages
  bool force = false;                  // overwrite an earlier run in run_directory
  bool quiet = true;                   // no progress display
};

struct SolveResult {
  std::int64_t steps = 0;
  double time_step = 0.0;
  double critical_time_step = 0.0;
  std::string limiting_mode;
  double final_balance_error = 0.0;
  bool interrupted = false;  // SIGINT / SIGTERM: stopped cleanly, status "interrupted"
  std::string message;
};

SolveResult solve(const Scene& scene, const PointCloud& cloud, const SolveOptions& options);

}  // namespace mppm::solver
