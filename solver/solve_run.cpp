// The run loop of mppm-solve: model, boundary conditions, time step, integration, output,
// numerical guards.
#include "solver/solve_run.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/checksummed_binary.hpp"
#include "common/input_error.hpp"
#include "common/memory_estimate.hpp"
#include "common/progress.hpp"
#include "common/run_directory.hpp"
#include "solver/agreed_failure.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/checkpoint.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/distributed_model.hpp"
#include "solver/distributed_snapshot.hpp"
#include "solver/energy_guard.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/interruption.hpp"
#include "solver/log_number.hpp"
#include "solver/model.hpp"
#include "solver/plasticity/material_registry.hpp"
#include "solver/run_writer.hpp"
#include "solver/snapshot_fields.hpp"

namespace mppm::solver {

namespace {

// The scene and the points file must describe the same discretization.
void check_points_match_scene(const Scene& scene, const PointCloud& cloud, const std::string& file) {
  if (cloud.dimension != scene.dimension)
    throw InputError(file + ": the points are " + std::to_string(cloud.dimension) + "-D but the scene has dimension " +
                     std::to_string(scene.dimension) + " (rerun mppm-preprocess with this scene)");
  if (cloud.size() == 0) throw InputError(file + ": holds no points");
  const double dx = scene.geometry.spacing;
  auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); };
  if (cloud.spacing > 0.0 && !close(cloud.spacing, dx))
    throw InputError(file + ": made with spacing " + log_number(cloud.spacing) +
                     " m but the scene's geometry.spacing is " + log_number(dx) +
                     " m (rerun mppm-preprocess with this scene)");
  if (cloud.horizon > 0.0 && !close(cloud.horizon, scene.geometry.horizon()))
    throw InputError(file + ": made with horizon " + log_number(cloud.horizon) + " m but the scene asks for " +
                     log_number(scene.geometry.horizon()) +
                     " m (geometry.horizon_factor; the boundary layers depend on it: rerun mppm-preprocess)");
}

// Steps at which something periodic happens: the first step at or after each multiple of the
// interval (every step for interval 0 when `every_step_if_zero`).
class Schedule {
 public:
  Schedule() = default;  // never due
  Schedule(double interval, double dt, bool every_step_if_zero)
      : interval_(interval), dt_(dt), every_(interval <= 0.0 && every_step_if_zero) {}
  bool due(std::int64_t step) {
    if (every_) return true;
    if (interval_ <= 0.0) return false;
    const double t = static_cast<double>(step) * dt_;
    if (t + 1e-9 * dt_ >= next_ * interval_) {
      next_ = std::floor((t + 1e-9 * dt_) / interval_) + 1.0;
      return true;
    }
    return false;
  }
  // The next multiple of the interval (a checkpoint stores it; a restart puts it back).
  double next() const { return next_; }
  void restore(double next) { next_ = next; }

 private:
  double interval_ = 0.0, dt_ = 0.0;
  bool every_ = false;
  double next_ = 1.0;
};

// A wall time of the start-up line in milliseconds' precision: "0.120".
std::string log_seconds(double seconds) {
  std::ostringstream s;
  s << std::fixed;
  s.precision(3);
  s << seconds;
  return s.str();
}

// Where a point of the points file is: its position and region, from the process that owns it
// (collective in a distributed run: the owner's values, exactly, on every process).
struct PointWhereabouts {
  std::string position;  // "(1.5e-3, 2e-3) m", and in a distributed run ", on process 2 of 3"
  std::int64_t region = 0;
};

PointWhereabouts whereabouts(const PointData& p, std::size_t point) {
  const auto i = owned_index(p, point);
  std::vector<ExactSum> x(static_cast<std::size_t>(p.dimension));
  for (int c = 0; c < p.dimension && i; ++c) x[static_cast<std::size_t>(c)].add(p.position[*i * p.dimension + c]);
  const std::vector<double> position = p.processes ? p.processes->sum(x) : ProcessGroup::single().sum(x);
  const std::int64_t region = i ? p.region[*i] : 0;
  PointWhereabouts w;
  for (std::size_t c = 0; c < position.size(); ++c) w.position += (c ? ", " : "") + log_number(position[c]);
  w.position = "(" + w.position + ") m";
  w.region = p.processes ? p.processes->total(region) : region;
  if (p.processes)
    w.position += ", on process " + std::to_string(p.processes->total(i ? p.processes->rank() : 0)) + " of " +
                  std::to_string(p.processes->size());
  return w;
}

// The reason of a stop on non-finite values: which point (the lowest index), which field, how many.
// Collective in a distributed run.
std::string non_finite_reason(const ExplicitDynamics& dynamics) {
  const auto bad = dynamics.first_non_finite();
  if (!bad) return "non-finite displacement, rotation or velocity";
  const PointData& p = dynamics.model().points;
  const PointWhereabouts where = whereabouts(p, bad->point);
  if (bad->field == "pore_pressure")
    return "no pore pressure holds the fluid content of point " + std::to_string(bad->point) +
           " of the points file (0-based; position " + where.position +
           "): the retention curve's inverse failed there, the point was drained below the liquid its pores hold "
           "at the largest suction (check the fluid_flux outflow, the permeability or the time step); " +
           std::to_string(bad->points) + " point(s) so";
  return "non-finite " + bad->field + " at point " + std::to_string(bad->point) +
         " of the points file (0-based; region " + std::to_string(where.region) + ", position " + where.position +
         "); " + std::to_string(bad->points) + " point(s) non-finite";
}

}  // namespace

// The bytes of the points as read (every array of the cloud).
static std::uint64_t point_cloud_bytes(const PointCloud& c) {
  auto bytes = [](const auto& v) { return static_cast<std::uint64_t>(v.size() * sizeof(v[0])); };
  return bytes(c.x) + bytes(c.y) + bytes(c.z) + bytes(c.volume) + bytes(c.region) + bytes(c.boundary_id) +
         bytes(c.normal_x) + bytes(c.normal_y) + bytes(c.normal_z) + bytes(c.precrack_vertices);
}

// Before anything big is allocated: the memory estimate (common/memory_estimate.hpp) against what
// this machine has available (MemAvailable, or MPPM_MEMORY_AVAILABLE in bytes: a budget a user or
// a test sets), refused with the estimate and the advice. In a distributed run each process checks
// its share against the machine's memory over the processes on it: the largest share of the points
// (the ghosts, a layer one horizon deep around each share, are not counted) and the whole points
// file, which every process reads and holds until its model is built.
static void refuse_runs_that_do_not_fit(const Scene& scene, const PointCloud& cloud, const ProcessGroup& group) {
  const int sharing = group.processes_on_this_machine();  // collective: before any return
  MemoryEstimateInput in;
  const auto processes = static_cast<std::uint64_t>(group.size());
  in.points = (cloud.size() + processes - 1) / processes;
  in.horizon_factor = scene.geometry.horizon_factor;
  in.dimension = scene.dimension;
  in.effects = scene.effects.names();
  in.snapshot_fields = scene.output.fields;
  in.damping = scene.numerics.damping != 0.0;
  in.unsaturated = scene.material.pore_fluid && scene.material.pore_fluid->retention;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    in.boundary_points +=
        (!cloud.region.empty() && cloud.region[i] > 0) || (!cloud.boundary_id.empty() && cloud.boundary_id[i] > 0);
  std::optional<std::uint64_t> available = available_memory_bytes();
  if (const char* budget = std::getenv("MPPM_MEMORY_AVAILABLE")) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(budget, &end, 10);
    if (!*budget || *end != '\0')
      throw InputError(std::string("MPPM_MEMORY_AVAILABLE: expected a number of bytes, got '") + budget + "'");
    available = v;
  }
  if (!available) return;
  MemoryEstimate estimate = estimate_run_memory(in);
  if (!group.distributed()) return require_memory_fits(estimate, *available, scene.path);
  estimate.total_bytes += point_cloud_bytes(cloud);
  require_memory_fits(estimate, *available / static_cast<std::uint64_t>(sharing),
                      scene.path + " (process " + std::to_string(group.rank()) + " of " + std::to_string(group.size()) +
                          ", one of " + std::to_string(sharing) + " sharing this machine's memory)",
                      "; or spread the processes over more machines (each process holds its share of the points "
                      "and the whole points file, so more processes on the same machine do not help)");
}

namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": not found or not readable");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first `bytes` of a table the run flushed before its checkpoint, checked against the
// checkpoint's fingerprint: the rows a run wrote after its checkpoint are dropped.
std::string table_up_to_checkpoint(const std::string& path, std::uint64_t bytes, std::uint64_t fingerprint,
                                   std::int64_t step) {
  std::string text = file_text(path);
  if (text.size() < bytes || fnv1a(text.substr(0, bytes)) != fingerprint)
    throw InputError(path + ": does not hold the rows the run had written at its checkpoint (step " +
                     std::to_string(step) + "): the table was changed or replaced since; cannot restart");
  text.resize(bytes);
  return text;
}

// A restart puts the run directory back to its checkpoint: snapshots the run wrote after it (and
// the snapshot of an interruption) are removed, as are the temporaries of a run killed while
// writing. The continued run writes the scheduled snapshots again, with the same bytes.
void remove_output_after_checkpoint(const std::string& directory, const std::vector<RunWriter::SnapshotRecord>& kept) {
  namespace fs = std::filesystem;
  std::vector<std::string> keep;
  for (const auto& k : kept) keep.push_back(fs::path(k.file).filename().string());
  for (const char* sub : {".", run_layout::snapshot_dir, run_layout::checkpoint_dir}) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(fs::path(directory) / sub, ec)) {
      const std::string name = entry.path().filename().string();
      const bool temporary = name.find(".tmp-") != std::string::npos;
      const bool later_snapshot = std::string(sub) == run_layout::snapshot_dir && name.rfind("snapshot_", 0) == 0 &&
                                  std::find(keep.begin(), keep.end(), name) == keep.end();
      if (temporary || later_snapshot) fs::remove(entry.path(), ec);
    }
  }
}

// A new run (resume null) or a restart from `resume`, by a RunDriver (below). `release`: the
// caller's cloud (the same object as `cloud`), emptied once the model and the boundary conditions
// are built from it; null to leave it as it is.
SolveResult run(const Scene& scene_in, const PointCloud& cloud, const SolveOptions& options,
                const CheckpointFile* resume, PointCloud* release);

}  // namespace

std::string checkpoint_path(const std::string& run_directory) { return run_directory + "/" + run_layout::checkpoint; }

SolveResult solve(const Scene& scene, const PointCloud& cloud, const SolveOptions& options) {
  return run(scene, cloud, options, nullptr, nullptr);
}

SolveResult solve(const Scene& scene, PointCloud&& cloud, const SolveOptions& options) {
  return run(scene, cloud, options, nullptr, &cloud);
}

namespace {

// The run's scene, after the checks that the checkpoint is of this run's scene and points.
Scene restart_scene(const PointCloud& cloud, const CheckpointFile& checkpoint, SolveOptions& options) {
  const std::string scene_file = options.run_directory + "/" + run_layout::resolved_scene;
  if (fnv1a(file_text(scene_file)) != checkpoint.header.scene_fingerprint)
    throw InputError(scene_file + ": changed since the checkpoint " + checkpoint.path +
                     " was written; a restart continues the run with the scene it was started with "
                     "(for another scene start a new run: mppm-solve SCENE.yaml --points POINTS -o NEW_RUN_DIR)");
  if (point_cloud_fingerprint(cloud) != checkpoint.header.points_fingerprint)
    throw InputError(options.points_file + ": not the points the run in " + options.run_directory +
                     " was started with (the points file changed since the checkpoint " + checkpoint.path +
                     "; a restart needs the same points)");
  options.test_hooks.refuse_with_restart();
  options.start_up->mark("checkpoint identity");
  Scene scene = load_scene(scene_file);
  options.start_up->mark("read scene");
  return scene;
}

SolveResult restart_run(const PointCloud& cloud, const CheckpointFile& checkpoint, const SolveOptions& options_in,
                        PointCloud* release) {
  SolveOptions options = options_in;
  if (!options.start_up) options.start_up.emplace();
  const ProcessGroup one = ProcessGroup::single();
  std::optional<Scene> scene;
  // Every process reads the same files: a refusal is agreed (solver/agreed_failure.hpp).
  run_agreed(options.processes ? *options.processes : one, [&] { scene = restart_scene(cloud, checkpoint, options); });
  return run(*scene, cloud, options, &checkpoint, release);
}

}  // namespace

SolveResult restart(const PointCloud& cloud, const CheckpointFile& checkpoint, const SolveOptions& options) {
  return restart_run(cloud, checkpoint, options, nullptr);
}

SolveResult restart(PointCloud&& cloud, const CheckpointFile& checkpoint, const SolveOptions& options) {
  return restart_run(cloud, checkpoint, options, &cloud);
}

namespace {

// After a snapshot, the tables, the log and run_info.json are rewritten (each atomically, with
// an fsync of the file and of the directory) only when kTableFlushInterval of wall time has
// passed since their last rewrite; at checkpoints, stops, failures and the end always. Ten
// fsyncs cost about 13 ms on the development VM: after every one of the crack-branching case's
// 241 snapshots that was 3 s of its 17 s. A run killed between rewrites leaves every file
// whole, the tables up to a second behind the newest snapshot. The snapshots written since the
// last rewrite are fsynced in one batch by the next one (run_writer.hpp), before run_info.json
// lists them.
constexpr std::chrono::duration<double> kTableFlushInterval{1.0};

// The time step of a run and what it was fitted to.
struct TimeStepPlan {
  CriticalTimeStep critical;
  double damage_step = 0.0;  // the largest step of a damage run (Model::damage_critical_step)
  double dt = 0.0;
  std::int64_t steps = 0;
  FlowSchedule flow;  // pore fluid: the flow updates against dt (solver/pore_fluid.hpp)
};

// A whole number of steps ends exactly at time.end (the step only shrinks; a given step that
// divides time.end is kept as written). An automatic step is also fitted to output.interval
// when that divides time.end, so that snapshots fall on the interval's multiples.
void fit_step_to_end(const Scene& scene, bool step_given, TimeStepPlan& plan) {
  const double end = scene.time.end;
  auto divides = [](double whole, double part) {
    const double ratio = whole / part;
    return std::abs(ratio - std::round(ratio)) <= 1e-9 * ratio;
  };
  double dt = plan.dt;
  if (!step_given && scene.output.interval > 0.0 && scene.output.interval < end && divides(end, scene.output.interval))
    dt = scene.output.interval / std::ceil(scene.output.interval / dt - 1e-9);
  const auto steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(end / dt - 1e-9)));
  if (std::abs(static_cast<double>(steps) * dt - end) > 1e-9 * end) dt = end / static_cast<double>(steps);
  plan.dt = dt;
  plan.steps = steps;
}

// One run of mppm-solve, from the scene and the points (or a checkpoint) to the finished run
// directory: run() lists the steps; the driver owns what they share.
class RunDriver {
 public:
  RunDriver(const Scene& scene_in, const SolveOptions& options, const CheckpointFile* resume)
      : scene_in_(scene_in),
        options_(options),
        group_(options.processes ? *options.processes : one_process_),
        resume_(resume),
        start_up_(options.start_up.value_or(PhaseTimer{})),
        scene_(scene_in),
        checkpointing_(scene_in.output.checkpoint_interval > 0.0),
        guard_(scene_in.numerics.energy_check_tolerance, scene_in.numerics.energy_check_start_step) {}

  // `release`: the caller's cloud (the same object as `cloud`), emptied once the model and the
  // boundary conditions are built from it; null to leave it as it is.
  // In a distributed run every step that may fail on one process alone runs through run_agreed
  // (solver/agreed_failure.hpp): all processes go on, or all stop with the same failure.
  SolveResult run(const PointCloud& cloud, PointCloud* release) {
    run_agreed(group_, [&] { check_inputs(cloud); });
    run_agreed(group_, [&] { build_model_and_conditions(cloud, release); });
    run_agreed(group_, [&] { options_.test_hooks.check_against_model(model(), totals_.points, options_.points_file); });
    run_agreed(group_, [&] {
      fit_time_step();
      options_.test_hooks.check_against_steps(plan_.steps);
    });
    run_agreed(group_, [&] { open_run_directory(); });
    log_start();  // its reads agreed inside
    start_up_.mark("run directory");
    if (!resume_) write_reference();
    run_agreed(group_, [&] { start_dynamics(); });
    start_up_.mark("initial forces");
    if (resume_)
      restore_from_checkpoint();
    else
      write_initial_state();
    start_time_loop();
    Progress progress("mppm-solve", plan_.steps, options_.quiet);
    const InterruptionHandlers handlers;
    if (advance(progress)) finish_completed();
    progress.finish("t = " + log_number(dynamics().time()) + " s");
    return result();
  }

 private:
  Model& model() { return distributed_ ? distributed_->model : *model_; }
  const Model& model() const { return distributed_ ? distributed_->model : *model_; }
  RunWriter& writer() { return *writer_; }
  ExplicitDynamics& dynamics() { return *dynamics_; }

  // Set-up, in this order: each step may refuse the run (InputError, NumericalFailure) before
  // the next one allocates or writes anything.
  void check_inputs(const PointCloud& cloud);
  void build_model_and_conditions(const PointCloud& cloud, PointCloud* release);
  void build_distributed(const PointCloud& cloud, const ModelOptions& settings);
  void fit_time_step();
  void open_run_directory();
  void write_reference();
  void fill_run_info();
  void log_start();
  void log_start_up_report();
  void log_test_hooks();
  void log_fields_not_produced();
  void log_fluid_boundaries();
  void start_dynamics();
  void restore_from_checkpoint();
  void write_initial_state();
  void start_time_loop();
  std::string start_up_line() const;
  // The time loop; true when it reached time.end, false when it stopped on an interruption.
  bool advance(Progress& progress);
  void check_and_record(std::int64_t s, bool row);
  void stop_on_interruption(std::int64_t s, bool snapshot_written);
  void finish_completed();
  SolveResult result() const;

  // What the steps of the loop share.
  void record_rows();
  void update_info(const std::string& status, const std::string& message);
  void snapshot();
  void write_snapshot();
  void flush_files();
  [[noreturn]] void fail(const std::string& reason);
  void checkpoint();
  RunLoopState loop_state() const;
  [[noreturn]] void stop_on_checkpoint_write_error(const InputError& e);
  std::string damage_summary() const;

  const Scene& scene_in_;  // as given: scene_.time.step is the step the run arrives at
  const SolveOptions& options_;
  const ProcessGroup one_process_ = ProcessGroup::single();
  const ProcessGroup& group_;     // options_.processes, or one_process_
  const CheckpointFile* resume_;  // null for a new run
  // The start-up phases (run_info.json "start_up_seconds"); their start is that of the run's wall
  // time, their end that of the time loop.
  PhaseTimer start_up_;
  std::optional<std::chrono::steady_clock::time_point> loop_start_;
  Scene scene_;
  // Checkpoints (output.checkpoint_interval; nothing of this is computed without it) identify the
  // run's inputs by the resolved scene as written and the points.
  const bool checkpointing_;
  RunIdentity identity_;
  std::optional<BoundaryConditions> conditions_;
  std::optional<Model> model_;                   // one process ...
  std::optional<DistributedModel> distributed_;  // ... or this process's part of a distributed run
  // The whole model's counts (over all processes).
  struct Totals {
    std::uint64_t points = 0, bonds = 0, precrack_cut_pairs = 0, detached_points = 0;
  } totals_;
  std::uint64_t total_detached_points() const;
  // A file of the run directory read by the first process (a failure agreed), on every process.
  std::string read_on_first_process(const std::function<std::string()>& read) const;
  // A distributed run's processes and partition for the checkpoint (null on one process).
  const CheckpointProcesses* checkpoint_processes();
  std::optional<CheckpointProcesses> checkpoint_processes_;
  TimeStepPlan plan_;
  std::optional<RunWriter> writer_;
  RunInfo info_;
  std::optional<ExplicitDynamics> dynamics_;
  Schedule rows_, snapshots_, checkpoints_;
  EnergyGuard guard_;
  // The energy check stops growth; energy that disappears without a dissipation that accounts for
  // it is not an instability but a wrong answer all the same: reported at the end.
  double worst_balance_ = 0.0;
  std::string points_file_;  // absolute: a checkpoint stores it
  std::int64_t first_step_ = 1;
  std::optional<std::chrono::steady_clock::time_point> last_flush_;
  int checkpoints_written_ = 0;
  std::int64_t last_checkpoint_step_ = -1;
  SolveResult result_;
};

// The points against the scene, the end time, and whether the run fits in memory.
void RunDriver::check_inputs(const PointCloud& cloud) {
  check_points_match_scene(scene_, cloud, options_.points_file);
  if (!(scene_.time.end > 0.0)) throw InputError(scene_.path + ": time.end: must be positive");
  refuse_runs_that_do_not_fit(scene_, cloud, group_);
  start_up_.mark("memory estimate");
}

// The boundary conditions and the model; with `release` the model takes the cloud's arrays over
// instead of copying them, and the rest of the cloud is emptied: `cloud` (the same object) is
// not read after this.
void RunDriver::build_model_and_conditions(const PointCloud& cloud, PointCloud* release) {
  // Bad viscoplastic parameters are an InputError naming the key.
  ModelOptions model_settings = model_options(scene_);
  if (resume_) {
    identity_.scene_fingerprint = resume_->header.scene_fingerprint;  // checked by restart()
    identity_.points_fingerprint = resume_->header.points_fingerprint;
  } else if (checkpointing_) {
    identity_.points_fingerprint = point_cloud_fingerprint(cloud);
  }
  conditions_.emplace(scene_, cloud, options_.points_file);
  if (scene_.effects.pore_fluid) model_settings.fluid_boundaries = conditions_->fluid_layout();
  start_up_.mark("boundary conditions");
  if (group_.distributed())
    build_distributed(cloud, model_settings);
  else
    model_.emplace(release ? build_model(std::move(*release), model_settings, &start_up_)
                           : build_model(cloud, model_settings, &start_up_));
  if (release) *release = PointCloud{};
  totals_.points = static_cast<std::uint64_t>(group_.total(static_cast<std::int64_t>(model().points.owned)));
  totals_.bonds = static_cast<std::uint64_t>(group_.total(static_cast<std::int64_t>(model().bonds.bond_count())));
  totals_.precrack_cut_pairs =
      static_cast<std::uint64_t>(group_.total(static_cast<std::int64_t>(model().precrack_cut_entries))) / 2;
  totals_.detached_points = total_detached_points();
  if (totals_.detached_points == totals_.points)
    throw InputError(options_.points_file + ": every point is detached (fewer than d+1 bonds within the horizon " +
                     log_number(scene_.geometry.horizon()) +
                     " m): nothing holds the body together (expected geometry.horizon_factor of about 2 to 4)");
}

// A distributed run's model: this process's points and their ghosts (solver/distributed_model.hpp),
// the conditions keeping this process's points, and the partition's summary for the log and
// run_info.json. The effects that do not run across processes yet are refused as bad input.
void RunDriver::build_distributed(const PointCloud& cloud, const ModelOptions& settings) {
  try {
    distributed_.emplace(build_distributed_model(cloud, settings, group_));
  } catch (const std::invalid_argument& e) {
    throw InputError(scene_.path + ": " + e.what() + " (mppm-solve under mpirun; docs/theory.md section 13)");
  }
  start_up_.mark("distributed model");
  conditions_->keep_owned(distributed_->local);
  info_.partition = summarize_partition(model(), group_);
}

std::string RunDriver::read_on_first_process(const std::function<std::string()>& read) const {
  std::string text;
  run_agreed(group_, [&] {
    if (group_.rank() == 0) text = read();
  });
  return group_.broadcast(text, 0);
}

const CheckpointProcesses* RunDriver::checkpoint_processes() {
  if (!distributed_) return nullptr;
  if (!checkpoint_processes_) checkpoint_processes_.emplace(CheckpointProcesses{group_, distributed_->part});
  return &*checkpoint_processes_;
}

std::uint64_t RunDriver::total_detached_points() const {
  return static_cast<std::uint64_t>(group_.total(static_cast<std::int64_t>(model().detached_points)));
}

// The critical step of the model, the step the run takes (fit_step_to_end) and the breakage's
// view of it; the resolved scene records the step.
void RunDriver::fit_time_step() {
  // The stiffest points centre the step's and the naming's patches, and the stiffest body point
  // sets the damage run's step limit: all found in one pass over the point blocks.
  Model& m = model();
  const StiffestPoints stiffest = patches_need_stiffest_points(m, scene_.numerics.step_estimate) || m.effects.damage
                                      ? stiffest_points(m.points, m.bonds, m.constants)
                                      : StiffestPoints{};
  start_up_.mark("stiffest points");
  std::optional<StepPatch> step_patch;  // the naming's first patch
  plan_.critical = estimate_critical_step(m, scene_.numerics.step_estimate, stiffest, &step_patch);
  start_up_.mark("critical time step");
  if (!(plan_.critical.step > 0.0 && std::isfinite(plan_.critical.step)))
    throw NumericalFailure(options_.run_directory + ": the critical time step could not be estimated (" +
                           log_number(plan_.critical.step) + " s): the discrete operator is not positive");
  name_limiting_mode(m, plan_.critical, patch_centre(m, stiffest.any), &step_patch);
  start_up_.mark("mode naming");
  plan_.damage_step = model().damage_critical_step(plan_.critical.step, stiffest.body.block_eigenvalue);
  plan_.dt = choose_time_step(scene_, plan_.critical, plan_.damage_step);
  fit_step_to_end(scene_, scene_in_.time.step.has_value(), plan_);
  scene_.time.step = plan_.dt;
  start_up_.mark("damage step limit");
  if (model().fluid) {
    const double limit = fluid_step_limit(model().points, model().bonds, *model().fluid, &model().drains);
    plan_.flow = model().fluid->retention ? unsaturated_flow_schedule(limit, plan_.dt, scene_.numerics.flow_integration)
                                          : flow_schedule(limit, plan_.dt, scene_.numerics.flow_integration);
    start_up_.mark("fluid step limit");
  }
}

// The run directory: a new one (the resolved scene written), or the one a restart continues.
void RunDriver::open_run_directory() {
  model().set_breakage_time_step(plan_.dt);
  if (group_.rank() != 0)
    writer_.emplace(options_.run_directory, RunWriter::Silent{});  // the first process writes
  else if (resume_)
    writer_.emplace(options_.run_directory, RunWriter::ContinueExisting{});
  else
    writer_.emplace(options_.run_directory, options_.force);
  if (!resume_) {
    std::vector<std::pair<std::string, double>> derived{{"critical_time_step_s", plan_.critical.step}};
    if (scene_.effects.damage)
      derived.emplace_back("critical_bond_work_J_per_m6", model().constants.critical_bond_work);
    if (model().fluid) {
      derived.emplace_back("fluid_time_step_s", plan_.flow.fluid_step);
      derived.emplace_back("micro_conductivity", model().fluid->micro_conductivity);
    }
    const std::string resolved = writer().write_resolved_scene(scene_, derived);
    if (checkpointing_) identity_.scene_fingerprint = fnv1a(resolved);
  }
  if (scene_.effects.damage) writer().start_crack_path_table();
  fill_run_info();
}

// A new run: the reference configuration (run_layout::reference).
void RunDriver::write_reference() {
  const int D = model().dimension();
  if (!distributed_) {
    writer().write_reference(D, model().points.owned, reference_fields(model().points));
  } else {
    run_agreed(group_, [&] {
      with_gathered_fields(model().points, reference_fields(model().points), distributed_->part, group_,
                           [&](const std::vector<SnapshotFieldSource>& all, std::uint64_t points) {
                             writer().write_reference(D, points, all);
                           });
    });
  }
  start_up_.mark("reference snapshot");
}

void RunDriver::fill_run_info() {
  info_.points = totals_.points;
  info_.bonds = totals_.bonds;
  info_.threads = omp_get_max_threads();
  info_.effects = scene_.effects.names();
  info_.dimension = scene_.dimension;
  info_.time_step = plan_.dt;
  info_.critical_time_step = plan_.critical.step;
  info_.largest_time_step = plan_.damage_step;
  info_.critical_step_estimate =
      plan_.critical.step_patch_points > 0 || plan_.critical.step_from_patch ? "patch" : "whole_model";
  info_.limiting_mode = plan_.critical.limiting_mode;
  info_.detached_points = totals_.detached_points;
  if (model().fluid) info_.flow = plan_.flow;
}

// The pore fluid's line of the start-up report: its constants and how the flow is scheduled.
std::string fluid_report(const FluidConstants& fluid, const FlowSchedule& flow, double dt,
                         FlowIntegration integration) {
  std::string schedule = "a flow update every " + std::to_string(flow.interval) + " steps (of " +
                         log_number(dt * static_cast<double>(flow.interval)) + " s)";
  if (flow.substeps > 1)
    schedule = std::to_string(flow.substeps) + " flow updates per step (of " +
               log_number(dt / static_cast<double>(flow.substeps)) + " s" +
               (integration == FlowIntegration::explicit_substeps ? ", numerics.flow_integration: explicit)" : ")");
  if (flow.stages > 1)
    schedule = "one RKL2 super step of " + std::to_string(flow.stages) + " stages per step (instead of " +
               std::to_string(static_cast<std::int64_t>(std::ceil(dt / (0.9 * flow.fluid_step)))) + " flow updates)";
  if (flow.follows_saturation) schedule += ", chosen again before every update as the saturation changes";
  std::string model = "saturated";
  if (fluid.retention)
    model = "unsaturated: van Genuchten p_e " + log_number(fluid.retention->air_entry_pressure) + " Pa, n " +
            log_number(fluid.retention->n) + ", S_res " + log_number(fluid.retention->residual_saturation) +
            ", Mualem k_r, Bishop chi = S_r";
  return "pore fluid (" + model + "): Biot coefficient " + log_number(fluid.biot_coefficient) + ", Biot modulus " +
         log_number(fluid.biot_modulus) + " Pa, mobility k/mu_f " + log_number(fluid.mobility) +
         " m^2/(Pa s), micro-conductivity " + log_number(fluid.micro_conductivity) +
         " 1/(Pa s m^2); fluid step limit " + log_number(flow.fluid_step) + " s against the time step " +
         log_number(dt) + " s: " + schedule;
}

// The first lines of log.txt: what runs, and the start-up report (a restart has it already in
// its log and says where it continues from).
void RunDriver::log_start() {
  if (resume_) writer().restore_log(read_on_first_process([&] { return file_text(writer().path(run_layout::log)); }));
  if (!resume_) writer().log("mppm-solve " MPPM_VERSION ": scene " + scene_.path + ", points " + options_.points_file);
  if (resume_)
    writer().log("mppm-solve " MPPM_VERSION " --restart: continues from " + resume_->path + " (step " +
                 std::to_string(resume_->header.step) + ", t = " + log_number(resume_->header.time) + " s), points " +
                 options_.points_file + ", threads " + std::to_string(info_.threads) +
                 (info_.partition ? " per process" : "") +
                 "; rows and snapshots after the checkpoint are dropped and written again");
  if (resume_ && info_.partition) writer().log("distributed run, " + describe(*info_.partition));
  if (!resume_) {
    log_start_up_report();
    log_test_hooks();
    log_fields_not_produced();
  }
  std::vector<std::string> load_header{"time_s"};
  for (const auto& bc : scene_.boundary_conditions)
    for (const auto& c : is_fluid(bc.type)
                             ? run_files::fluid_load_columns(bc.name, bc.type == BoundaryType::pore_pressure)
                             : run_files::load_columns(bc.name, scene_.dimension))
      load_header.push_back(c);
  writer().set_load_header(load_header, scene_.effects.pore_fluid);
}

// Where the step was estimated, and what that cost.
std::string step_estimate_cost(const CriticalTimeStep& critical) {
  if (critical.step_patch_points > 0)
    return "estimated on the patch of " + std::to_string(critical.step_patch_points) +
           " points within 4 horizons of the stiffest point, which holds the highest mode, in " +
           std::to_string(critical.iterations) + " applications of the patches' operators";
  return std::to_string(critical.iterations) + " Lanczos iterations on the whole model" +
         (critical.whole_model_reason.empty() ? std::string() : " (" + critical.whole_model_reason + ")");
}

// What naming the limiting mode cost, and where it was named.
std::string naming_cost(const CriticalTimeStep& critical, int dimension) {
  const std::string step_note =
      critical.step_from_patch ? "; the step is a patch's estimate, which the whole model's fell short of" : "";
  const auto& blocks = critical.naming_block_patch_points;
  if (blocks[0] > 0)
    return "the mode, which mixes both blocks, named on the patches of " + std::to_string(blocks[0]) + " and " +
           std::to_string(blocks[1]) +
           " points around the stiffest points of the translational and the rotational block, in " +
           std::to_string(critical.naming_iterations) + " applications of their operators" + step_note;
  if (critical.naming_patch_points == 0)
    return std::to_string(critical.naming_iterations) + " more to name the mode" + step_note;
  std::string centre;
  for (int a = 0; a < dimension; ++a) centre += (a ? ", " : "") + log_number(critical.naming_patch_centre[a]);
  return "the mode named on the patch of " + std::to_string(critical.naming_patch_points) +
         " points around the stiffest point (" + centre + ") m, where the highest mode lives, in " +
         std::to_string(critical.naming_iterations) + " applications of its operator" + step_note;
}

// The model, the critical and the chosen time step, the damage and viscoplastic settings, the
// scene's warnings.
void RunDriver::log_start_up_report() {
  const Model& m = model();
  const CriticalTimeStep& critical = plan_.critical;
  const double dt = plan_.dt;
  writer().log("points " + std::to_string(info_.points) + ", bonds " + std::to_string(info_.bonds) +
               " (stored from both ends), pre-crack cuts " + std::to_string(totals_.precrack_cut_pairs) +
               " bonds, detached points " + std::to_string(totals_.detached_points));
  if (info_.partition) writer().log("distributed run, " + describe(*info_.partition));
  writer().log("critical time step " + log_number(critical.step) + " s (translational " +
               log_number(critical.translational) + " s" +
               (critical.rotational > 0.0 ? ", rotational " + log_number(critical.rotational) + " s" : std::string()) +
               "; " + step_estimate_cost(critical) + ", " + naming_cost(critical, m.dimension()) + "), limiting mode " +
               critical.limiting_mode + ", driven by " + critical.driver);
  writer().log("time step " + log_number(dt) + " s (" +
               (scene_in_.time.step ? "given" : "auto, safety " + log_number(scene_.time.safety)) + "), " +
               std::to_string(plan_.steps) + " steps, threads " + std::to_string(info_.threads) +
               (info_.partition ? " per process" : ""));
  if (scene_.effects.damage)
    writer().log("damage: critical bond work w_cr " + log_number(m.constants.critical_bond_work) + " J/m^6 (G_cr " +
                 log_number(scene_.material.damage->critical_energy_release_rate) + " J/m^2, " +
                 to_string(scene_.material.damage->calibration) + " calibration), no-fail depth " +
                 log_number(scene_.material.damage->no_fail_depth) + " m; largest step of a damage run " +
                 log_number(plan_.damage_step) + " s (" + log_number(plan_.damage_step / critical.step) +
                 " of the critical step); a point whose lopsided family would need a step below " + log_number(dt) +
                 " s is detached (stiffness block limit " + log_number(m.block_eigenvalue_limit) + " 1/s^2)");
  if (m.fluid) writer().log(fluid_report(*m.fluid, plan_.flow, dt, scene_.numerics.flow_integration));
  if (m.fluid) log_fluid_boundaries();
  if (m.viscoplastic_model)
    writer().log("viscoplastic model " + m.viscoplastic_model->name() +
                 " (return map once per step; the critical step above is the elastic bound, which "
                 "plastic flow does not lower)");
  for (const auto& w : scene_.warnings) writer().log("warning: " + w);
}

// The pore fluid's boundaries: where each drained and fed condition acts (docs/theory.md section 12).
void RunDriver::log_fluid_boundaries() {
  const BoundaryConditions& c = *conditions_;
  if (c.drained().empty() && c.fed().empty()) {
    writer().log("fluid boundaries: none (every face is impermeable)");
    return;
  }
  std::string line = "fluid boundaries:";
  for (const DrainedLayer& layer : c.drained())
    line += " drained '" + layer.name + "' (" + std::to_string(layer.points.size()) + " layer points, " +
            (layer.inert ? "a layer of its own, out of the mechanics" : "a kinematic layer") + ");";
  for (const FedSurface& s : c.fed())
    line += " fed '" + s.name + "' (" + std::to_string(s.points.size()) + " body points, area " + log_number(s.area) +
            " m^2);";
  line += " " + std::to_string(model().drains.bond_count()) + " drain bonds; every other face is impermeable";
  writer().log(line);
}

// The fault hooks armed for this run (solver/test_hooks.hpp).
void RunDriver::log_test_hooks() {
  for (const std::string& line : options_.test_hooks.armed()) writer().log(line);
}

void RunDriver::log_fields_not_produced() {
  const auto available = available_fields(model());
  std::string effects;
  for (const auto& n : info_.effects) effects += (effects.empty() ? "" : ", ") + n;
  if (effects.empty()) effects = "none";
  for (const auto& f : scene_.output.fields)
    if (std::find(available.begin(), available.end(), f) == available.end())
      writer().log("note: output field '" + f + "' is not produced by this run (effects: " + effects + ")");
}

// The integrator at t = 0, the schedules and the energy check.
void RunDriver::start_dynamics() {
  dynamics_.emplace(model(), *conditions_, plan_.dt, scene_.gravity);
  dynamics().set_damping(scene_.numerics.damping);
  dynamics().set_flow_schedule(plan_.flow);
  dynamics().set_clock(scene_.time.end, plan_.steps);
  dynamics().initialize();
  rows_ = Schedule(scene_.output.load_interval, plan_.dt, true);
  snapshots_ = Schedule(scene_.output.interval, plan_.dt, false);
  checkpoints_ = Schedule(scene_.output.checkpoint_interval, plan_.dt, false);
  points_file_ = std::filesystem::absolute(options_.points_file).string();
}

// A restart: the state, the schedules, the energy check and the tables of the checkpoint; the
// output written after it removed.
void RunDriver::restore_from_checkpoint() {
  RunLoopState loop;
  // The same file on every process: a refusal is the same everywhere.
  run_agreed(group_, [&] {
    loop = restore_checkpoint(*resume_, identity_, model(), dynamics(), checkpoint_processes());
    if (loop.time_step != plan_.dt)
      throw InputError(resume_->path + ": the checkpoint's time step " + log_number(loop.time_step) +
                       " s is not the one this run arrives at (" + log_number(plan_.dt) +
                       " s); cannot continue it bit for bit");
  });
  rows_.restore(loop.next_row);
  snapshots_.restore(loop.next_snapshot);
  checkpoints_.restore(loop.next_checkpoint);
  guard_.restore(loop.guard);
  worst_balance_ = loop.worst_balance;
  const std::int64_t step = resume_->header.step;
  // The first process reads the run directory; the others keep the same tables.
  writer().restore_tables(read_on_first_process([&] {
                            return table_up_to_checkpoint(writer().path(run_layout::load), loop.load_table_bytes,
                                                          loop.load_table_fingerprint, step);
                          }),
                          read_on_first_process([&] {
                            return table_up_to_checkpoint(writer().path(run_layout::energy), loop.energy_table_bytes,
                                                          loop.energy_table_fingerprint, step);
                          }));
  if (group_.rank() == 0) remove_output_after_checkpoint(writer().directory(), loop.snapshots);
  writer().restore_snapshots(std::move(loop.snapshots));
  first_step_ = dynamics().steps() + 1;
  last_checkpoint_step_ = step;
  update_info("running", "");
  flush_files();
}

// A new run: the rows and the snapshot of t = 0.
void RunDriver::write_initial_state() {
  record_rows();
  snapshot();
}

// The end of the start-up, the start of the time loop: the "start-up:" line of log.txt.
void RunDriver::start_time_loop() {
  loop_start_ = start_up_.mark(resume_ ? "restore state" : "initial snapshot");
  info_.start_up = start_up_.phases();
  writer().log(start_up_line());
}

// "start-up: read points 0.12 s, bond families 0.8 s, ... (total 2.3 s)"
std::string RunDriver::start_up_line() const {
  std::string line = "start-up:";
  for (const PhaseTimer::Phase& p : start_up_.phases())
    line += (line.back() == ':' ? " " : ", ") + p.name + " " + log_seconds(p.seconds) + " s";
  return line + " (total " + log_seconds(start_up_.total_seconds()) + " s)";
}

// Per step: step, guards, row, scheduled snapshot, checkpoint, interruption.
bool RunDriver::advance(Progress& progress) {
  const std::int64_t steps = plan_.steps;
  for (std::int64_t s = first_step_; s <= steps; ++s) {
    const bool row = rows_.due(s) || s == steps;
    const bool snap = snapshots_.due(s) || s == steps;
    // A finished run needs no checkpoint to continue from.
    const bool checkpoint_due = checkpoints_.due(s) && s < steps;
    dynamics().step(row,
                    [this](PointData& points, std::int64_t step) { options_.test_hooks.after_forces(points, step); });
    check_and_record(s, row);
    if (snap) snapshot();
    // A signal may reach the processes of a distributed run in different steps: agreed each step.
    const bool interrupted = group_.any(interruption_requested() || options_.test_hooks.interrupts_after(s));
    // With checkpoints on, an interruption (SIGINT, SIGTERM) writes one too, before the snapshot of
    // the interruption (which the checkpoint does not count, so that a restart removes it).
    if (checkpointing_ && (checkpoint_due || interrupted)) checkpoint();
    if (interrupted) {
      stop_on_interruption(s, snap);
      return false;
    }
    progress.update(s, "t = " + log_number(dynamics().time()) + " s");
  }
  return true;
}

// The guards of step s (non-finite values; at a row, the energy check) and its row.
void RunDriver::check_and_record(std::int64_t s, bool row) {
  if (!dynamics().finite()) fail(non_finite_reason(dynamics()));
  if (!row) return;
  record_rows();
  if (const auto reason = guard_.check(s, dynamics().energy(), dynamics().initial_total_energy())) fail(*reason);
  // Watched from the step the energy check starts at (numerics.energy_check_start_step), like the check.
  if (s >= scene_.numerics.energy_check_start_step && std::abs(dynamics().balance_error()) > std::abs(worst_balance_))
    worst_balance_ = dynamics().balance_error();
}

// SIGINT / SIGTERM (or the interrupt_after_step hook) after step s: a last snapshot, status
// "interrupted".
void RunDriver::stop_on_interruption(std::int64_t s, bool snapshot_written) {
  clear_interruption();
  if (!snapshot_written) write_snapshot();
  const std::string message = "interrupted at step " + std::to_string(s) + " of " + std::to_string(plan_.steps) +
                              ", t = " + log_number(dynamics().time()) + " s; the state there is the last snapshot" +
                              (checkpointing_ ? "; mppm-solve --restart " + writer().directory() +
                                                    " continues from the checkpoint written there"
                                              : std::string());
  writer().log(message);
  update_info("interrupted", message);
  flush_files();
  result_.interrupted = true;
  result_.message = message;
}

// ", broken bonds ... detached points ... (... of them for the time step's sake)"
std::string RunDriver::damage_summary() const {
  // Each process counts its share (bond_breakage.hpp): the sums are the model's.
  const Model& m = model();
  auto total = [&](std::size_t share) { return std::to_string(group_.total(static_cast<std::int64_t>(share))); };
  return "broken bonds " + total(m.broken_bonds) + " (pairs), fracture dissipation " +
         log_number(dynamics_->energy().fracture_dissipation) + " J, detached points " + total(m.detached_points) +
         " (" + total(m.unstable_detached_points) + " of them for the time step's sake)";
}

// The end of a run that reached time.end: the balance warning, the summary, the files.
void RunDriver::finish_completed() {
  std::string warning;
  const double tolerance = scene_.numerics.energy_check_tolerance;
  if (std::abs(worst_balance_) > tolerance)
    warning = "warning: the energy balance error reached " + log_number(worst_balance_) +
              " (beyond numerics.energy_check_tolerance " + log_number(tolerance) + "): energy " +
              (worst_balance_ < 0.0 ? "disappeared" : "appeared") +
              " that neither the external work nor a dissipation accounts for (energy.csv, balance_error)";
  if (!warning.empty()) writer().log(warning);
  update_info("completed", warning);
  writer().log("completed " + std::to_string(plan_.steps) + " steps in " + log_number(info_.wall_seconds) +
               " s, final balance error " + log_number(dynamics().balance_error()) +
               (scene_.effects.damage ? ", " + damage_summary() : std::string()));
  flush_files();
}

SolveResult RunDriver::result() const {
  SolveResult r = result_;
  r.steps = dynamics_->steps();
  r.time_step = plan_.dt;
  r.critical_time_step = plan_.critical.step;
  r.limiting_mode = plan_.critical.limiting_mode;
  r.final_balance_error = dynamics_->balance_error();
  return r;
}

void RunDriver::record_rows() {
  const double t = dynamics().time();
  std::vector<double> row{t};
  const auto values = conditions_->load_values(model().points, t);
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (is_fluid(scene_.boundary_conditions[k].type)) {
      const auto flow = dynamics().fluid_boundary_flow(k);
      row.insert(row.end(), {flow.rate, flow.volume});
      continue;
    }
    row.insert(row.end(), values[k].displacement.begin(), values[k].displacement.end());
    row.insert(row.end(), values[k].force.begin(), values[k].force.end());
  }
  writer().add_load_row(row);
  const EnergyState& e = dynamics().energy();
  std::vector<double> energy_row{t,
                                 e.kinetic,
                                 e.rotational_kinetic,
                                 e.elastic,
                                 e.stabilization,
                                 e.plastic_dissipation,
                                 e.fracture_dissipation,
                                 e.external_work,
                                 dynamics().balance_error()};
  if (model().fluid)
    energy_row.insert(energy_row.end(), {e.fluid_stored, e.flow_dissipation, e.fluid_mass_balance(), e.flow_splitting});
  writer().add_energy_row(energy_row);
}

void RunDriver::update_info(const std::string& status, const std::string& message) {
  info_.status = status;
  info_.message = message;
  info_.steps = dynamics().steps();
  info_.time = dynamics().time();
  const auto now = std::chrono::steady_clock::now();
  info_.wall_seconds = std::chrono::duration<double>(now - start_up_.start()).count();
  // 0 until the time loop starts (a rewrite during the start-up).
  info_.loop_wall_seconds = loop_start_ ? std::chrono::duration<double>(now - *loop_start_).count() : 0.0;
  if (!loop_start_) info_.start_up = start_up_.phases();
  info_.detached_points = total_detached_points();
}

// The tables, the log and run_info.json rewritten (RunWriter::flush), with the crack arrivals since
// the last rewrite added to crack_path.csv first.
void RunDriver::flush_files() {
  if (scene_.effects.damage)
    for (const CrackArrivals::Row& row : model().crack_arrivals.take_new_rows(model().points, group_))
      writer().add_crack_path_row(row.point, row.position, row.time);
  // The first process writes (the others' writers are silent); a write error stops every process.
  run_agreed(group_, [&] { writer().flush(info_); });
}

void RunDriver::write_snapshot() {
  const int D = model().dimension();
  const std::int64_t step = dynamics().steps();
  const double t = dynamics().time();
  if (!distributed_) {
    writer().write_snapshot(D, step, t, model().points.owned, snapshot_sources(model(), scene_.output.fields));
    return;
  }
  run_agreed(group_, [&] {
    with_gathered_fields(model(), scene_.output.fields, distributed_->part, group_,
                         [&](const std::vector<SnapshotFieldSource>& all, std::uint64_t points) {
                           writer().write_snapshot(D, step, t, points, all);
                         });
  });
}

// A scheduled snapshot, then the files when kTableFlushInterval has passed since their last rewrite.
void RunDriver::snapshot() {
  write_snapshot();
  const auto now = std::chrono::steady_clock::now();
  // The first process's clock decides for all (it is the one that writes).
  if (!group_.any(group_.rank() == 0 && !(last_flush_ && now - *last_flush_ < kTableFlushInterval))) return;
  update_info("running", "");
  flush_files();
  last_flush_ = now;
}

// A numerical failure (exit 3): the run directory keeps everything up to the last good snapshot.
void RunDriver::fail(const std::string& reason) {
  const std::string message = "numerical failure at step " + std::to_string(dynamics().steps()) +
                              ", t = " + log_number(dynamics().time()) + " s: " + reason +
                              "; the last good snapshot is kept (try a smaller time.step or check the material)";
  if (scene_.effects.damage) writer().log("at the failure: " + damage_summary());
  writer().log(message);
  update_info("numerical_failure", message);
  flush_files();
  // Every process arrives here at the same step (the guards decide on values summed over all), and
  // throws the same failure, agreed so that the top of mppm-solve knows that no process is left
  // waiting.
  run_agreed(group_, [&] { throw NumericalFailure(options_.run_directory + ": " + message); });
  throw std::logic_error("RunDriver::fail: run_agreed returned after a failure on every process");
}

// The loop's state after the last step, as a checkpoint stores it.
RunLoopState RunDriver::loop_state() const {
  const RunWriter& w = *writer_;
  RunLoopState loop;
  loop.next_row = rows_.next();
  loop.next_snapshot = snapshots_.next();
  loop.next_checkpoint = checkpoints_.next();
  loop.worst_balance = worst_balance_;
  loop.guard = guard_.history();
  loop.snapshots = w.snapshots();
  loop.load_table_bytes = w.load_table().size();
  loop.load_table_fingerprint = fnv1a(w.load_table());
  loop.energy_table_bytes = w.energy_table().size();
  loop.energy_table_fingerprint = fnv1a(w.energy_table());
  loop.points_file = points_file_;
  loop.time_step = plan_.dt;
  return loop;
}

// A checkpoint after the last step: the tables are flushed first, so that load.csv and energy.csv
// on disk hold every row the checkpoint counts. A write error stops the run (exit 2) with the
// previous checkpoint intact.
void RunDriver::checkpoint() {
  update_info("running", "");
  flush_files();
  last_flush_ = std::chrono::steady_clock::now();
  const RunLoopState loop = loop_state();
  ++checkpoints_written_;
  try {
    run_agreed(group_, [&] {
      write_checkpoint(checkpoint_path(writer().directory()), identity_, model(), dynamics(), loop,
                       options_.test_hooks.fails_checkpoint_write(checkpoints_written_), checkpoint_processes());
    });
  } catch (const InputError& e) {
    stop_on_checkpoint_write_error(e);
  }
  last_checkpoint_step_ = dynamics().steps();
}

void RunDriver::stop_on_checkpoint_write_error(const InputError& e) {
  const std::string message =
      std::string(e.what()) + "; the run stopped at step " + std::to_string(dynamics().steps()) +
      (last_checkpoint_step_ >= 0
           ? "; the previous checkpoint (step " + std::to_string(last_checkpoint_step_) +
                 ") is intact: free space, then mppm-solve --restart " + writer().directory() + " continues from it"
           : std::string("; no checkpoint was written before"));
  writer().log(message);
  update_info("write_error", message);
  try {
    flush_files();
  } catch (const InputError&) {
    // The disk that refused the checkpoint may refuse the tables too: the message above is
    // what matters, and the tables of the last flush are intact.
  }
  // Every process is here (the write error was agreed): the same failure everywhere.
  run_agreed(group_, [&] { throw InputError(message); });
  throw std::logic_error("RunDriver: run_agreed returned after a failure on every process");
}

SolveResult run(const Scene& scene_in, const PointCloud& cloud, const SolveOptions& options,
                const CheckpointFile* resume, PointCloud* release) {
  return RunDriver(scene_in, options, resume).run(cloud, release);
}

}  // namespace

}  // namespace mppm::solver
