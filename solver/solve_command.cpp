// The mppm-solve command line (SCENE.md "Commands").
#include "solver/solve_command.hpp"

#include <iostream>
#include <utility>

#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "common/checkpoint_file.hpp"
#include "solver/solve_run.hpp"

namespace mppm::solver {

int solve_command(int argc, char** argv) {
  mppm::CommandLineSpec spec;
  spec.program = "mppm-solve";
  spec.usage =
      "usage: mppm-solve SCENE.yaml --points POINTS.vtp -o RUN_DIR [options]\n"
      "       mppm-solve --restart RUN_DIR [--points POINTS.vtp] [--threads N] [--quiet]\n"
      "\n"
      "Runs the explicit micro-polar periporomechanics solver on the points made by\n"
      "mppm-preprocess and writes the run directory (resolved scene, snapshots, load.csv,\n"
      "energy.csv, log.txt, run_info.json).\n"
      "\n"
      "options:\n"
      "  --points FILE       points file from mppm-preprocess (required)\n"
      "  -o RUN_DIR          run directory to create (required)\n"
      "  --set key.path=v    override a scene entry (repeatable; units allowed, e.g. 7us)\n"
      "  --threads N         OpenMP threads (results are identical for any N)\n"
      "  --force             overwrite an earlier run in RUN_DIR\n"
      "  --quiet             no progress display\n"
      "  --restart RUN_DIR   continue the run in RUN_DIR from its checkpoint (RUN_DIR/checkpoint/,\n"
      "                      written every output.checkpoint_interval of simulated time and on\n"
      "                      Ctrl-C / SIGTERM) to time.end, with the run's scene.resolved.yaml and\n"
      "                      the points it was started with (or --points, which must be the same);\n"
      "                      the result is bit for bit that of the uninterrupted run. Refused\n"
      "                      (exit 2): no checkpoint, a corrupted one, the scene or the points\n"
      "                      changed since\n"
      "  --help, --version\n"
      "\n"
      "exit codes: 0 success, 2 bad input or a write error (disk full: the previous files and\n"
      "checkpoint stay intact), 3 numerical failure (run directory kept up to the last good\n"
      "snapshot), 1 other errors or interrupted (Ctrl-C / SIGTERM: the run stops cleanly after\n"
      "its step with a last snapshot, a checkpoint when checkpoints are on, and status\n"
      "\"interrupted\")\n";
  // --inject-nan STEP:POINT[:FIELD[:COMPONENT]], --inject-kick STEP:POINT:COMPONENT:VELOCITY and
  // --fail-checkpoint-write K are test hooks (solver/README.md "Test hooks"), not listed in the
  // usage: they make the run fail on purpose.
  spec.value_options = {"-o", "--points", "--inject-nan", "--inject-kick", "--restart", "--fail-checkpoint-write"};
  spec.flag_options = {"--force"};
  return mppm::run_stage(argc, argv, spec, [](const mppm::CommandLine& cl) {
    int fail_checkpoint_write = 0;
    if (const auto hook = cl.option("--fail-checkpoint-write")) {
      try {
        std::size_t used = 0;
        fail_checkpoint_write = std::stoi(*hook, &used);
        if (used != hook->size() || fail_checkpoint_write < 1) throw std::invalid_argument(*hook);
      } catch (const std::exception&) {
        throw mppm::InputError("mppm-solve: --fail-checkpoint-write " + *hook +
                               ": expected K >= 1 (the K-th checkpoint write fails)");
      }
    }
    if (const auto run_directory = cl.option("--restart")) {
      if (!cl.positional.empty() || cl.option("-o") || !cl.overrides.empty() || cl.has_flag("--force"))
        throw mppm::InputError("mppm-solve: --restart " + *run_directory +
                               " takes the scene and the output directory of that run: no SCENE.yaml, -o, --set "
                               "or --force with it (see --help)");
      if (cl.option("--inject-nan")) throw mppm::InputError("mppm-solve: --inject-nan cannot be combined with --restart");
      if (cl.option("--inject-kick")) throw mppm::InputError("mppm-solve: --inject-kick cannot be combined with --restart");
      const mppm::CheckpointFile checkpoint = mppm::read_checkpoint_file(mppm::solver::checkpoint_path(*run_directory));
      mppm::solver::SolveOptions options;
      options.run_directory = *run_directory;
      options.points_file = cl.option("--points").value_or(checkpoint.text("points_file"));
      options.quiet = cl.quiet;
      options.fail_checkpoint_write = fail_checkpoint_write;
      mppm::PointCloud cloud = mppm::read_point_cloud(options.points_file);
      const mppm::solver::SolveResult result = mppm::solver::restart(std::move(cloud), checkpoint, options);
      if (result.interrupted) {
        std::cerr << "mppm-solve: " << result.message << " (" << options.run_directory << ")\n";
        return mppm::kExitOther;
      }
      return mppm::kExitSuccess;
    }
    if (cl.positional.size() != 1)
      throw mppm::InputError("mppm-solve: expected exactly one scene file (see --help)");
    const auto points = cl.option("--points");
    const auto out = cl.option("-o");
    if (!points) throw mppm::InputError("mppm-solve: --points POINTS.vtp is required (see --help)");
    if (!out) throw mppm::InputError("mppm-solve: -o RUN_DIR is required (see --help)");
    std::optional<mppm::solver::NanInjection> inject_nan;
    if (const auto hook = cl.option("--inject-nan")) inject_nan = mppm::solver::parse_nan_injection(*hook);
    std::optional<mppm::solver::VelocityKick> inject_kick;
    if (const auto hook = cl.option("--inject-kick")) inject_kick = mppm::solver::parse_velocity_kick(*hook);
    const mppm::Scene scene = mppm::load_scene(cl.positional[0], cl.overrides);
    mppm::PointCloud cloud = mppm::read_point_cloud(*points);
    mppm::solver::SolveOptions options;
    options.run_directory = *out;
    options.points_file = *points;
    options.force = cl.has_flag("--force");
    options.quiet = cl.quiet;
    options.inject_nan = inject_nan;
    options.inject_kick = inject_kick;
    options.fail_checkpoint_write = fail_checkpoint_write;
    const mppm::solver::SolveResult result = mppm::solver::solve(scene, std::move(cloud), options);
    if (result.interrupted) {
      std::cerr << "mppm-solve: " << result.message << " (" << options.run_directory << ")\n";
      return mppm::kExitOther;
    }
    return mppm::kExitSuccess;
  });
}

}  // namespace mppm::solver
