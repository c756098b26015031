// The mppm-solve command line (docs/stages.md "Commands").
#include "solver/solve_command.hpp"

#include <mpi.h>
#include <omp.h>

#include <cstdlib>
#include <iostream>
#include <optional>
#include <streambuf>
#include <utility>

#include "common/checkpoint_file.hpp"
#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/agreed_failure.hpp"
#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"
#include "solver/process_group.hpp"
#include "solver/run_estimate.hpp"
#include "solver/solve_run.hpp"
#include "solver/test_hooks.hpp"

namespace mppm::solver {

namespace {

mppm::CommandLineSpec solve_command_spec() {
  mppm::CommandLineSpec spec;
  spec.program = "mppm-solve";
  spec.usage =
      "usage: mppm-solve SCENE.yaml --points POINTS.vtp -o RUN_DIR [options]\n"
      "       mppm-solve --restart RUN_DIR [--points POINTS.vtp] [--threads N] [--quiet]\n"
      "       mppm-solve SCENE.yaml --points POINTS.vtp --estimate [--threads N]\n"
      "\n"
      "Runs the explicit micro-polar periporomechanics solver on the points made by\n"
      "mppm-preprocess and writes the run directory (resolved scene, snapshots, load.csv,\n"
      "energy.csv, log.txt, run_info.json). Under mpirun -np P it runs across P processes (a new run\n"
      "or --restart), with the files of the one-process run (not with damage, pore_fluid or\n"
      "--estimate).\n"
      "\n"
      "options:\n"
      "  --points FILE       points file from mppm-preprocess (required)\n"
      "  -o RUN_DIR          run directory to create (required)\n"
      "  --set key.path=v    override a scene entry (repeatable; units allowed, e.g. 7us)\n"
      "  --threads N         OpenMP threads (results are identical for any N)\n"
      "  --force             overwrite an earlier run in RUN_DIR\n"
      "  --quiet             no progress display\n"
      "  --estimate          print the points, bonds, time step, steps, predicted wall time at\n"
      "                      --threads and peak memory of the run, without running it (no -o)\n"
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
  // --fail-checkpoint-write K are test hooks (solver/test_hooks.hpp, solver/README.md "Test hooks"),
  // not listed in the usage: they make the run fail on purpose.
  spec.value_options = {"-o", "--points", "--inject-nan", "--inject-kick", "--restart", "--fail-checkpoint-write"};
  spec.flag_options = {"--force", "--estimate"};
  return spec;
}

// An interrupted run is exit 1 with the message; a completed one exit 0.
int exit_code(const SolveResult& result, const SolveOptions& options) {
  if (result.interrupted) {
    std::cerr << "mppm-solve: " << result.message << " (" << options.run_directory << ")\n";
    return mppm::kExitOther;
  }
  return mppm::kExitSuccess;
}

// mppm-solve --restart RUN_DIR: the run's own scene and directory; of the test hooks only
// --fail-checkpoint-write. On one process or on every process of `group` (each reads the whole
// checkpoint and the points; a checkpoint written by any number of processes continues on any).
int continue_run(const mppm::CommandLine& cl, const std::string& run_directory, const TestHooks& hooks,
                 const ProcessGroup& group) {
  mppm::CheckpointFile checkpoint;
  mppm::PointCloud cloud;
  SolveOptions options;
  run_agreed(group, [&] {
    if (!cl.positional.empty() || cl.option("-o") || !cl.overrides.empty() || cl.has_flag("--force"))
      throw mppm::InputError("--restart " + run_directory +
                             " takes the scene and the output directory of that run: no SCENE.yaml, -o, --set "
                             "or --force with it (see --help)");
    hooks.refuse_with_restart();  // before the checkpoint is read: the option is the user's mistake
    PhaseTimer start_up;
    checkpoint = mppm::read_checkpoint_file(checkpoint_path(run_directory));
    start_up.mark("read checkpoint");
    options.run_directory = run_directory;
    options.points_file = cl.option("--points").value_or(checkpoint.text("points_file"));
    options.quiet = cl.quiet || group.rank() != 0;
    options.test_hooks = hooks;
    if (group.distributed()) options.processes = &group;
    cloud = mppm::read_point_cloud(options.points_file);
    start_up.mark("read points");
    options.start_up = std::move(start_up);
  });
  return exit_code(restart(std::move(cloud), checkpoint, options), options);
}

// mppm-solve SCENE.yaml --points POINTS --estimate: what the run would cost (solver/run_estimate.hpp),
// its bonds counted from the families.
int estimate_only(const mppm::CommandLine& cl) {
  if (cl.positional.size() != 1) throw mppm::InputError("expected exactly one scene file (see --help)");
  const auto points = cl.option("--points");
  if (!points) throw mppm::InputError("--points POINTS.vtp is required (see --help)");
  if (cl.option("-o") || cl.has_flag("--force"))
    throw mppm::InputError("--estimate runs nothing: no -o or --force with it (see --help)");
  const mppm::Scene scene = mppm::load_scene(cl.positional[0], cl.overrides);
  const mppm::PointCloud cloud = mppm::read_point_cloud(*points);
  if (cloud.dimension != scene.dimension)
    throw mppm::InputError(*points + ": a " + std::to_string(cloud.dimension) + "-D points file for a " +
                           std::to_string(scene.dimension) + "-D scene");
  const PointData data = make_point_data(cloud, scene.effects);
  FamilyOptions families;
  families.horizon = scene.geometry.horizon();
  families.spacing = scene.geometry.spacing;
  const std::uint64_t bonds = build_families(data, families).bond_count();
  const RunEstimate estimate = estimate_run(scene, cloud, bonds, omp_get_max_threads());
  std::cout << format_run_estimate(scene, estimate);
  return mppm::kExitSuccess;
}

// mppm-solve SCENE.yaml --points POINTS -o RUN_DIR: a new run, on one process or on every process
// of `group` (each reads the scene and the points; a failure to read them anywhere stops all).
int start_run(const mppm::CommandLine& cl, const TestHooks& hooks, const ProcessGroup& group) {
  std::optional<mppm::Scene> scene;
  mppm::PointCloud cloud;
  SolveOptions options;
  run_agreed(group, [&] {
    if (cl.positional.size() != 1) throw mppm::InputError("expected exactly one scene file (see --help)");
    const auto points = cl.option("--points");
    const auto out = cl.option("-o");
    if (!points) throw mppm::InputError("--points POINTS.vtp is required (see --help)");
    if (!out) throw mppm::InputError("-o RUN_DIR is required (see --help)");
    PhaseTimer start_up;
    scene = mppm::load_scene(cl.positional[0], cl.overrides);
    start_up.mark("read scene");
    cloud = mppm::read_point_cloud(*points);
    start_up.mark("read points");
    options.run_directory = *out;
    options.points_file = *points;
    options.force = cl.has_flag("--force");
    options.quiet = cl.quiet || group.rank() != 0;  // one progress display
    options.test_hooks = hooks;
    options.start_up = std::move(start_up);
    if (group.distributed()) options.processes = &group;
  });
  return exit_code(solve(*scene, std::move(cloud), options), options);
}

// The number of processes when a launcher (mpirun of OpenMPI, or a PMI launcher such as MPICH's or
// Slurm's) started several copies; 1 otherwise.
int launched_processes() {
  for (const char* size : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* n = std::getenv(size)) return std::atoi(n);
  return 1;
}

// The test hooks of both forms; continue_run refuses the two that a restart cannot take.
TestHooks test_hooks_of(const mppm::CommandLine& cl) {
  TestHooks hooks;
  if (const auto k = cl.option("--fail-checkpoint-write"))
    hooks.fail_checkpoint_write = parse_checkpoint_write_failure(*k);
  if (const auto hook = cl.option("--inject-nan")) hooks.inject_nan = parse_nan_injection(*hook);
  if (const auto hook = cl.option("--inject-kick")) hooks.inject_kick = parse_velocity_kick(*hook);
  return hooks;
}

// One process: the three forms of the command.
int run_one_process(const mppm::CommandLine& cl) {
  const TestHooks hooks = test_hooks_of(cl);
  const ProcessGroup one = ProcessGroup::single();
  if (const auto run_directory = cl.option("--restart")) return continue_run(cl, *run_directory, hooks, one);
  if (cl.has_flag("--estimate")) return estimate_only(cl);
  return start_run(cl, hooks, one);
}

// Several processes (mpirun): a new run or a restart across them (docs/theory.md section 13).
int run_distributed(const mppm::CommandLine& cl, const ProcessGroup& group) {
  TestHooks hooks;
  run_agreed(group, [&] {
    if (cl.has_flag("--estimate"))
      throw mppm::InputError("--estimate runs nothing: run it on one process, without mpirun");
    hooks = test_hooks_of(cl);
  });
  if (const auto run_directory = cl.option("--restart")) return continue_run(cl, *run_directory, hooks, group);
  return start_run(cl, hooks, group);
}

// A writer that drops everything: the output of the processes other than the first.
class DiscardingBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
};

// mppm-solve under mpirun: every process runs the command; only the first prints. The failures of a
// run are agreed by all processes (solver/agreed_failure.hpp) and so the same everywhere; a failure
// on one process alone (an internal error) is printed by that process and ends the whole run
// (MPI_Abort) instead of leaving the others waiting for it.
int solve_distributed(int argc, char** argv, const mppm::CommandLineSpec& spec) {
  MpiSession mpi(argc, argv);
  const ProcessGroup group = ProcessGroup::world();
  DiscardingBuffer discard;
  std::streambuf* const cerr_buffer = std::cerr.rdbuf();
  std::streambuf* const cout_buffer = std::cout.rdbuf();
  if (group.rank() != 0) {
    std::cerr.rdbuf(&discard);
    std::cout.rdbuf(&discard);
  }
  // The streams get their buffers back before `discard` goes (they outlive this function).
  const auto restore = [&] {
    std::cerr.rdbuf(cerr_buffer);
    std::cout.rdbuf(cout_buffer);
  };
  bool alone = false;
  const int code = mppm::run_stage(argc, argv, spec, [&](const mppm::CommandLine& cl) {
    try {
      return run_distributed(cl, group);
    } catch (...) {
      alone = !failure_was_agreed(std::current_exception());
      if (alone) restore();
      throw;
    }
  });
  restore();
  if (alone) {
    std::cerr << "mppm-solve: process " << group.rank() << " of " << group.size()
              << " failed alone: ending the run on every process\n";
    MPI_Abort(MPI_COMM_WORLD, code);
  }
  return code;
}

}  // namespace

int solve_command(int argc, char** argv) {
  if (launched_processes() > 1) return solve_distributed(argc, argv, solve_command_spec());
  return mppm::run_stage(argc, argv, solve_command_spec(), run_one_process);
}

}  // namespace mppm::solver
