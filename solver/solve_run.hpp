// One run of mppm-solve as a library call: scene + points -> run directory (docs/stages.md).
// Throws InputError for bad input (exit 2) and NumericalFailure after writing the run
// directory up to the last good snapshot (exit 3).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "common/checkpoint_file.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/phase_timer.hpp"
#include "solver/process_group.hpp"
#include "solver/test_hooks.hpp"

namespace mppm::solver {

struct SolveOptions {
  std::string run_directory;
  std::string points_file = "points";  // named in messages
  bool force = false;                  // overwrite an earlier run in run_directory
  bool quiet = true;                   // no progress display
  // The start-up so far: the phases before the call (mppm-solve: reading the scene, the points or
  // the checkpoint), whose start is also the start of the run's wall time; none: both start with
  // the call.
  std::optional<PhaseTimer> start_up;
  // Faults on purpose, for tests (solver/test_hooks.hpp; none by default).
  TestHooks test_hooks;
  // A distributed run's processes (mppm-solve under mpirun; docs/theory.md section 13), every one
  // calling solve() with the same arguments; null: one process.
  const ProcessGroup* processes = nullptr;
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
// The same, emptying `cloud` as soon as the model is built from it, so that the points as read do
// not stay in memory beside the model's copy for the whole run (mppm-solve).
SolveResult solve(const Scene& scene, PointCloud&& cloud, const SolveOptions& options);

// RUN_DIR/checkpoint/state.ckpt; read_checkpoint_file of it says "no checkpoint" when it is missing.
std::string checkpoint_path(const std::string& run_directory);

// Continues the run in options.run_directory from `checkpoint` (read from checkpoint_path of it)
// to time.end: the scene is the run's scene.resolved.yaml, the points must be those the run was
// started with. The tables are cut back to the checkpoint's step and the snapshots written after
// it are removed, so that the run directory at the end is the one an uninterrupted run leaves
// (bit for bit: snapshots, load.csv, energy.csv). Throws InputError (exit 2) when the scene or
// the points changed since the checkpoint, or when the tables do not hold the checkpoint's rows.
SolveResult restart(const PointCloud& cloud, const CheckpointFile& checkpoint, const SolveOptions& options);
SolveResult restart(PointCloud&& cloud, const CheckpointFile& checkpoint, const SolveOptions& options);

}  // namespace mppm::solver
