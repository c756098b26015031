// The mppm-solve command line (SCENE.md "Commands").
#include "solver/solve_command.hpp"

#include <iostream>

#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/solve_run.hpp"

namespace mppm::solver {

int solve_command(int argc, char** argv) {
  mppm::CommandLineSpec spec;
  spec.program = "mppm-solve";
  spec.usage =
      "usage: mppm-solve SCENE.yaml --points POINTS.vtp -o RUN_DIR [options]\n"
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
      "  --help, --version\n"
      "\n"
      "exit codes: 0 success, 2 bad input, 3 numerical failure (run directory kept up to the\n"
      "last good snapshot), 1 other errors or interrupted (Ctrl-C: the run stops cleanly after\n"
      "its step with a last snapshot and status \"interrupted\")\n";
  // --inject-nan STEP:POINT[:FIELD[:COMPONENT]] is a test hook (solver/README.md "Test hooks"), not
  // listed in the usage: it makes the run fail on purpose.
  spec.value_options = {"-o", "--points", "--inject-nan"};
  spec.flag_options = {"--force"};
  return mppm::run_stage(argc, argv, spec, [](const mppm::CommandLine& cl) {
    if (cl.positional.size() != 1)
      throw mppm::InputError("mppm-solve: expected exactly one scene file (see --help)");
    const auto points = cl.option("--points");
    const auto out = cl.option("-o");
    if (!points) throw mppm::InputError("mppm-solve: --points POINTS.vtp is required (see --help)");
    if (!out) throw mppm::InputError("mppm-solve: -o RUN_DIR is required (see --help)");
    std::optional<mppm::solver::NanInjection> inject_nan;
    if (const auto hook = cl.option("--inject-nan")) inject_nan = mppm::solver::parse_nan_injection(*hook);
    const mppm::Scene scene = mppm::load_scene(cl.positional[0], cl.overrides);
    const mppm::PointCloud cloud = mppm::read_point_cloud(*points);
    mppm::solver::SolveOptions options;
    options.run_directory = *out;
    options.points_file = *points;
    options.force = cl.has_flag("--force");
    options.quiet = cl.quiet;
    options.inject_nan = inject_nan;
    const mppm::solver::SolveResult result = mppm::solver::solve(scene, cloud, options);
    if (result.interrupted) {
      std::cerr << "mppm-solve: " << result.message << " (" << options.run_directory << ")\n";
      return mppm::kExitOther;
    }
    return mppm::kExitSuccess;
  });
}

}  // namespace mppm::solver
