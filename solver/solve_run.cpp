// The run loop of mppm-solve: model, boundary conditions, time step, integration, output,
// numerical guards.
#include "solver/solve_run.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/checksummed_binary.hpp"
#include "common/input_error.hpp"
#include "common/progress.hpp"
#include "common/run_directory.hpp"
#include "common/units.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/checkpoint.hpp"
#include "common/memory_estimate.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/energy_guard.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/interruption.hpp"
#include "solver/model.hpp"
#include "solver/plasticity/material_registry.hpp"
#include "solver/run_writer.hpp"
#include "solver/snapshot_fields.hpp"

namespace mppm::solver {

namespace {

std::string text(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// The scene and the points file must describe the same discretization.
void check_points_match_scene(const Scene& scene, const PointCloud& cloud, const std::string& file) {
  if (cloud.dimension != scene.dimension)
    throw InputError(file + ": the points are " + std::to_string(cloud.dimension) + "-D but the scene has dimension " +
                     std::to_string(scene.dimension) + " (rerun mppm-preprocess with this scene)");
  if (cloud.size() == 0) throw InputError(file + ": holds no points");
  const double dx = scene.geometry.spacing;
  auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); };
  if (cloud.spacing > 0.0 && !close(cloud.spacing, dx))
    throw InputError(file + ": made with spacing " + text(cloud.spacing) + " m but the scene's geometry.spacing is " +
                     text(dx) + " m (rerun mppm-preprocess with this scene)");
  if (cloud.horizon > 0.0 && !close(cloud.horizon, scene.geometry.horizon()))
    throw InputError(file + ": made with horizon " + text(cloud.horizon) + " m but the scene asks for " +
                     text(scene.geometry.horizon()) +
                     " m (geometry.horizon_factor; the boundary layers depend on it: rerun mppm-preprocess)");
}

// Steps at which something periodic happens: the first step at or after each multiple of the
// interval (every step for interval 0 when `every_step_if_zero`).
class Schedule {
 public:
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
  double interval_, dt_;
  bool every_;
  double next_ = 1.0;
};

// "1.5e-3, 2e-3" for the position of point i.
std::string position_of(const PointData& p, std::size_t i) {
  std::string s;
  for (int c = 0; c < p.dimension; ++c) s += (c ? ", " : "") + text(p.position[i * p.dimension + c]);
  return "(" + s + ") m";
}

// The reason of a stop on non-finite values: which point (the lowest index), which field, how many.
std::string non_finite_reason(const ExplicitDynamics& dynamics) {
  const auto bad = dynamics.first_non_finite();
  if (!bad) return "non-finite displacement, rotation or velocity";
  const PointData& p = dynamics.model().points;
  return "non-finite " + bad->field + " at point " + std::to_string(bad->point) + " of the points file (0-based; region " +
         std::to_string(p.region[bad->point]) + ", position " + position_of(p, bad->point) + "); " +
         std::to_string(bad->points) + " point(s) non-finite";
}

// The value of a test hook (--inject-nan, --inject-kick) cut at its colons.
std::vector<std::string> hook_parts(const std::string& value) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t at; (at = value.find(':', start)) != std::string::npos; start = at + 1)
    parts.push_back(value.substr(start, at - start));
  parts.push_back(value.substr(start));
  return parts;
}

// A 1-based ("3") or 0-based ("17") non-negative integer of a test hook; `form` says what the
// hook expects, for the message.
std::int64_t hook_integer(const std::string& hook, const std::string& value, const std::string& part,
                          const std::string& what, const std::string& form) {
  std::size_t used = 0;
  long long v = -1;
  try {
    v = std::stoll(part, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != part.size() || part.empty() || v < 0)
    throw InputError("mppm-solve: " + hook + " " + value + ": " + what + " '" + part + "' is not a non-negative integer" +
                     form);
  return v;
}

// The step of a test hook, from 1.
std::int64_t hook_step(const std::string& hook, const std::string& value, const std::string& part,
                       const std::string& form) {
  const std::int64_t step = hook_integer(hook, value, part, "STEP", form);
  if (step < 1) throw InputError("mppm-solve: " + hook + " " + value + ": STEP counts from 1 (the first step)");
  return step;
}

}  // namespace

NanInjection parse_nan_injection(const std::string& value) {
  const std::vector<std::string> parts = hook_parts(value);
  const std::string hook = "--inject-nan";
  const std::string form = " (expected STEP:POINT[:FIELD[:COMPONENT]], e.g. 200:17:velocity)";
  if (parts.size() < 2 || parts.size() > 4) throw InputError("mppm-solve: " + hook + " " + value + ":" + form);
  NanInjection k;
  k.step = hook_step(hook, value, parts[0], form);
  k.point = static_cast<std::size_t>(hook_integer(hook, value, parts[1], "POINT", form));
  if (parts.size() > 2) {
    using F = NanInjection::Field;
    bool known = false;
    for (F f : {F::displacement, F::velocity, F::rotation, F::rotation_rate, F::force})
      if (parts[2] == NanInjection::name(f)) {
        k.field = f;
        known = true;
      }
    if (!known)
      throw InputError("mppm-solve: --inject-nan " + value + ": unknown FIELD '" + parts[2] +
                       "' (expected displacement, velocity, rotation, rotation_rate or force)");
  }
  if (parts.size() > 3) k.component = static_cast<int>(hook_integer(hook, value, parts[3], "COMPONENT", form));
  return k;
}

VelocityKick parse_velocity_kick(const std::string& value) {
  const std::vector<std::string> parts = hook_parts(value);
  const std::string hook = "--inject-kick";
  const std::string form = " (expected STEP:POINT:COMPONENT:VELOCITY, e.g. 60:17:0:50)";
  if (parts.size() != 4) throw InputError("mppm-solve: " + hook + " " + value + ":" + form);
  VelocityKick k;
  k.step = hook_step(hook, value, parts[0], form);
  k.point = static_cast<std::size_t>(hook_integer(hook, value, parts[1], "POINT", form));
  k.component = static_cast<int>(hook_integer(hook, value, parts[2], "COMPONENT", form));
  try {
    k.velocity = parse_quantity_as(parts[3], dim::velocity);
  } catch (const std::invalid_argument& e) {
    throw InputError("mppm-solve: --inject-kick " + value + ": VELOCITY: " + e.what() + form);
  }
  if (!std::isfinite(k.velocity)) throw InputError("mppm-solve: --inject-kick " + value + ": VELOCITY must be finite" + form);
  return k;
}

// Before anything big is allocated: the memory estimate (common/memory_estimate.hpp) against what
// this machine has available (MemAvailable, or MPPM_MEMORY_AVAILABLE in bytes: a budget a user or
// a test sets), refused with the estimate and the advice.
static void refuse_runs_that_do_not_fit(const Scene& scene, const PointCloud& cloud) {
  MemoryEstimateInput in;
  in.points = cloud.size();
  in.horizon_factor = scene.geometry.horizon_factor;
  in.dimension = scene.dimension;
  in.effects = scene.effects.names();
  in.snapshot_fields = scene.output.fields;
  in.damping = scene.numerics.damping != 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    in.boundary_points += (!cloud.region.empty() && cloud.region[i] > 0) || (!cloud.boundary_id.empty() && cloud.boundary_id[i] > 0);
  std::optional<std::uint64_t> available = available_memory_bytes();
  if (const char* budget = std::getenv("MPPM_MEMORY_AVAILABLE")) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(budget, &end, 10);
    if (!*budget || *end != '\0')
      throw InputError(std::string("MPPM_MEMORY_AVAILABLE: expected a number of bytes, got '") + budget + "'");
    available = v;
  }
  if (available) require_memory_fits(estimate_run_memory(in), *available, scene.path);
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

// `release`: the caller's cloud (the same object as `cloud`), emptied once the model and the
// boundary conditions are built from it; null to leave it as it is.
SolveResult run(const Scene& scene_in, const PointCloud& cloud, const SolveOptions& options,
                const CheckpointFile* resume, PointCloud* release);

}  // namespace

std::string checkpoint_path(const std::string& run_directory) {
  return run_directory + "/" + run_layout::checkpoint;
}

SolveResult solve(const Scene& scene, const PointCloud& cloud, const SolveOptions& options) {
  return run(scene, cloud, options, nullptr, nullptr);
}

SolveResult solve(const Scene& scene, PointCloud&& cloud, const SolveOptions& options) {
  return run(scene, cloud, options, nullptr, &cloud);
}

namespace {

SolveResult restart_run(const PointCloud& cloud, const CheckpointFile& checkpoint, const SolveOptions& options,
                        PointCloud* release) {
  const std::string scene_file = options.run_directory + "/" + run_layout::resolved_scene;
  if (fnv1a(file_text(scene_file)) != checkpoint.header.scene_fingerprint)
    throw InputError(scene_file + ": changed since the checkpoint " + checkpoint.path +
                     " was written; a restart continues the run with the scene it was started with "
                     "(for another scene start a new run: mppm-solve SCENE.yaml --points POINTS -o NEW_RUN_DIR)");
  if (point_cloud_fingerprint(cloud) != checkpoint.header.points_fingerprint)
    throw InputError(options.points_file + ": not the points the run in " + options.run_directory +
                     " was started with (the points file changed since the checkpoint " + checkpoint.path +
                     "; a restart needs the same points)");
  if (options.inject_nan) throw InputError("mppm-solve: --inject-nan cannot be combined with --restart");
  if (options.inject_kick) throw InputError("mppm-solve: --inject-kick cannot be combined with --restart");
  return run(load_scene(scene_file), cloud, options, &checkpoint, release);
}

}  // namespace

SolveResult restart(const PointCloud& cloud, const CheckpointFile& checkpoint, const SolveOptions& options) {
  return restart_run(cloud, checkpoint, options, nullptr);
}

SolveResult restart(PointCloud&& cloud, const CheckpointFile& checkpoint, const SolveOptions& options) {
  return restart_run(cloud, checkpoint, options, &cloud);
}

namespace {

SolveResult run(const Scene& scene_in, const PointCloud& cloud, const SolveOptions& options,
                const CheckpointFile* resume, PointCloud* release) {
  const auto wall_start = std::chrono::steady_clock::now();
  Scene scene = scene_in;
  check_points_match_scene(scene, cloud, options.points_file);
  if (!(scene.time.end > 0.0)) throw InputError(scene.path + ": time.end: must be positive");
  refuse_runs_that_do_not_fit(scene, cloud);

  // Bad viscoplastic parameters are an InputError naming the key.
  const ModelOptions model_settings = model_options(scene);
  // Checkpoints (output.checkpoint_interval; nothing of this is computed without it) identify the
  // run's inputs by the resolved scene as written and the points.
  const bool checkpointing = scene.output.checkpoint_interval > 0.0;
  RunIdentity identity;
  if (resume) {
    identity.scene_fingerprint = resume->header.scene_fingerprint;  // checked by restart()
    identity.points_fingerprint = resume->header.points_fingerprint;
  } else if (checkpointing) {
    identity.points_fingerprint = point_cloud_fingerprint(cloud);
  }
  const BoundaryConditions conditions(scene, cloud, options.points_file);
  // With `release` the model takes the cloud's arrays over instead of copying them, and the rest
  // of the cloud is emptied: `cloud` (the same object) is not read after this.
  Model model = release ? build_model(std::move(*release), model_settings) : build_model(cloud, model_settings);
  if (release) *release = PointCloud{};

  if (model.detached_points == model.points.owned)
    throw InputError(options.points_file + ": every point is detached (fewer than d+1 bonds within the horizon " +
                     text(scene.geometry.horizon()) +
                     " m): nothing holds the body together (expected geometry.horizon_factor of about 2 to 4)");
  if (const auto& k = options.inject_nan) {
    // Checked against the points before anything is written (exit 2 like any bad option).
    const bool rotational = k->field == NanInjection::Field::rotation || k->field == NanInjection::Field::rotation_rate;
    const int components = rotational ? model.points.rotation_components : model.dimension();
    if (k->point >= model.points.owned)
      throw InputError("mppm-solve: --inject-nan: POINT " + std::to_string(k->point) + " is not a point of " +
                       options.points_file + " (expected 0 to " + std::to_string(model.points.owned - 1) + ")");
    if (components == 0)
      throw InputError(std::string("mppm-solve: --inject-nan: FIELD ") + NanInjection::name(k->field) +
                       " needs the micropolar effect (this run has no micro-rotation)");
    if (k->component >= components)
      throw InputError("mppm-solve: --inject-nan: COMPONENT " + std::to_string(k->component) + " of " +
                       NanInjection::name(k->field) + " (expected 0 to " + std::to_string(components - 1) + ")");
  }
  if (const auto& k = options.inject_kick) {
    if (k->point >= model.points.owned)
      throw InputError("mppm-solve: --inject-kick: POINT " + std::to_string(k->point) + " is not a point of " +
                       options.points_file + " (expected 0 to " + std::to_string(model.points.owned - 1) + ")");
    if (k->component >= model.dimension())
      throw InputError("mppm-solve: --inject-kick: COMPONENT " + std::to_string(k->component) +
                       " of the velocity (expected 0 to " + std::to_string(model.dimension() - 1) + ")");
  }
  const CriticalTimeStep critical = critical_time_step(model);
  if (!(critical.step > 0.0 && std::isfinite(critical.step)))
    throw NumericalFailure(options.run_directory + ": the critical time step could not be estimated (" +
                           text(critical.step) + " s): the discrete operator is not positive");
  const double damage_step = model.damage_critical_step(critical.step);
  double dt = choose_time_step(scene, critical, damage_step);
  // A whole number of steps ends exactly at time.end (the step only shrinks; a given step that
  // divides time.end is kept as written). An automatic step is also fitted to output.interval
  // when that divides time.end, so that snapshots fall on the interval's multiples.
  const double end = scene.time.end;
  auto divides = [](double whole, double part) {
    const double ratio = whole / part;
    return std::abs(ratio - std::round(ratio)) <= 1e-9 * ratio;
  };
  if (!scene_in.time.step && scene.output.interval > 0.0 && scene.output.interval < end &&
      divides(end, scene.output.interval))
    dt = scene.output.interval / std::ceil(scene.output.interval / dt - 1e-9);
  const auto steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(end / dt - 1e-9)));
  if (std::abs(static_cast<double>(steps) * dt - end) > 1e-9 * end) dt = end / static_cast<double>(steps);
  scene.time.step = dt;
  if (options.inject_nan && options.inject_nan->step > steps)
    throw InputError("mppm-solve: --inject-nan: STEP " + std::to_string(options.inject_nan->step) +
                     " is beyond the run's " + std::to_string(steps) + " steps (expected 1 to " +
                     std::to_string(steps) + ")");
  if (options.inject_kick && options.inject_kick->step > steps)
    throw InputError("mppm-solve: --inject-kick: STEP " + std::to_string(options.inject_kick->step) +
                     " is beyond the run's " + std::to_string(steps) + " steps (expected 1 to " +
                     std::to_string(steps) + ")");
  model.set_breakage_time_step(dt);

  std::optional<RunWriter> writer_storage;
  if (resume) writer_storage.emplace(options.run_directory, RunWriter::ContinueExisting{});
  else writer_storage.emplace(options.run_directory, options.force);
  RunWriter& writer = *writer_storage;
  if (!resume) {
    std::vector<std::pair<std::string, double>> derived{{"critical_time_step_s", critical.step}};
    if (scene.effects.damage) derived.emplace_back("critical_bond_work_J_per_m6", model.constants.critical_bond_work);
    const std::string resolved = writer.write_resolved_scene(scene, derived);
    if (checkpointing) identity.scene_fingerprint = fnv1a(resolved);
    writer.write_reference(model.points);
  }

  RunInfo info;
  info.points = model.points.owned;
  info.bonds = model.bonds.bond_count();
  info.threads = omp_get_max_threads();
  info.effects = scene.effects.names();
  info.dimension = scene.dimension;
  info.time_step = dt;
  info.critical_time_step = critical.step;
  info.largest_time_step = damage_step;
  info.limiting_mode = critical.limiting_mode;
  info.detached_points = model.detached_points;

  if (resume) writer.restore_log(file_text(writer.path(run_layout::log)));
  else writer.log("mppm-solve " MPPM_VERSION ": scene " + scene.path + ", points " + options.points_file);
  if (resume)
    writer.log("mppm-solve " MPPM_VERSION " --restart: continues from " + resume->path + " (step " +
               std::to_string(resume->header.step) + ", t = " + text(resume->header.time) + " s), points " +
               options.points_file + ", threads " + std::to_string(info.threads) +
               "; rows and snapshots after the checkpoint are dropped and written again");
  // The run's start-up report (a restart has it already in its log).
  if (!resume) {
    writer.log("points " + std::to_string(info.points) + ", bonds " + std::to_string(info.bonds) +
               " (stored from both ends), pre-crack cuts " + std::to_string(model.precrack_cut_bonds) +
               " bonds, detached points " + std::to_string(model.detached_points));
    writer.log("critical time step " + text(critical.step) + " s (translational " + text(critical.translational) +
               " s" + (critical.rotational > 0.0 ? ", rotational " + text(critical.rotational) + " s" : std::string()) +
               "; " + std::to_string(critical.iterations) + " Lanczos iterations), limiting mode " + critical.limiting_mode +
               ", driven by " + critical.driver);
    writer.log("time step " + text(dt) + " s (" + (scene_in.time.step ? "given" : "auto, safety " + text(scene.time.safety)) +
               "), " + std::to_string(steps) + " steps, threads " + std::to_string(info.threads));
    if (scene.effects.damage)
      writer.log("damage: critical bond work w_cr " + text(model.constants.critical_bond_work) + " J/m^6 (G_cr " +
                 text(scene.material.damage->critical_energy_release_rate) + " J/m^2, " +
                 to_string(scene.material.damage->calibration) + " calibration), no-fail depth " +
                 text(scene.material.damage->no_fail_depth) + " m; largest step of a damage run " + text(damage_step) +
                 " s (" + text(damage_step / critical.step) +
                 " of the critical step); a point whose lopsided family would need a step below " + text(dt) +
                 " s is detached (stiffness block limit " + text(model.block_eigenvalue_limit) + " 1/s^2)");
    if (model.viscoplastic_model)
      writer.log("viscoplastic model " + model.viscoplastic_model->name() +
                 " (return map once per step; the critical step above is the elastic bound, which "
                 "plastic flow does not lower)");
    for (const auto& w : scene.warnings) writer.log("warning: " + w);
    if (const auto& k = options.inject_nan)
        writer.log("test hook (--inject-nan): a NaN will be written into " + std::string(NanInjection::name(k->field)) +
                 " component " + std::to_string(k->component) + " of point " + std::to_string(k->point) + " in step " +
                 std::to_string(k->step));
    if (const auto& k = options.inject_kick)
      writer.log("test hook (--inject-kick): " + text(k->velocity) + " m/s will be added to velocity component " +
                 std::to_string(k->component) + " of point " + std::to_string(k->point) + " in step " +
                 std::to_string(k->step) + " (kinetic energy that nothing accounts for)");
    const auto available = available_fields(model);
    for (const auto& f : scene.output.fields)
      if (std::find(available.begin(), available.end(), f) == available.end())
        writer.log("note: output field '" + f + "' is not produced by this run (effects: " +
                   [&] {
                     std::string e;
                     for (const auto& n : info.effects) e += (e.empty() ? "" : ", ") + n;
                     return e.empty() ? std::string("none") : e;
                   }() + ")");
  }  // start-up report

  std::vector<std::string> load_header{"time_s"};
  for (const auto& bc : scene.boundary_conditions)
    for (const auto& c : run_files::load_columns(bc.name, scene.dimension)) load_header.push_back(c);
  writer.set_load_header(load_header);

  ExplicitDynamics dynamics(model, conditions, dt, scene.gravity);
  dynamics.set_damping(scene.numerics.damping);
  dynamics.set_clock(end, steps);
  dynamics.set_nan_injection(options.inject_nan);
  dynamics.set_velocity_kick(options.inject_kick);
  dynamics.initialize();
  const auto loop_start = std::chrono::steady_clock::now();

  auto record_rows = [&] {
    std::vector<double> row{dynamics.time()};
    for (const auto& v : conditions.load_values(model.points, dynamics.time())) {
      row.insert(row.end(), v.displacement.begin(), v.displacement.end());
      row.insert(row.end(), v.force.begin(), v.force.end());
    }
    writer.add_load_row(row);
    const EnergyState& e = dynamics.energy();
    writer.add_energy_row({dynamics.time(), e.kinetic, e.rotational_kinetic, e.elastic, e.stabilization,
                           e.plastic_dissipation, e.fracture_dissipation, e.external_work,
                           dynamics.balance_error()});
  };
  auto update_info = [&](const std::string& status, const std::string& message) {
    info.status = status;
    info.message = message;
    info.steps = dynamics.steps();
    info.time = dynamics.time();
    const auto now = std::chrono::steady_clock::now();
    info.wall_seconds = std::chrono::duration<double>(now - wall_start).count();
    info.loop_wall_seconds = std::chrono::duration<double>(now - loop_start).count();
    info.detached_points = model.detached_points;
  };
  // After a snapshot, the tables, the log and run_info.json are rewritten (each atomically, with
  // an fsync of the file and of the directory) only when kTableFlushInterval of wall time has
  // passed since their last rewrite; at checkpoints, stops, failures and the end always. Ten
  // fsyncs cost about 13 ms on the development VM: after every one of the crack-branching case's
  // 241 snapshots that was 3 s of its 17 s. A run killed between rewrites leaves every file
  // whole, the tables up to a second behind the newest snapshot. The snapshot's own fsyncs run
  // on the run writer's background thread (run_writer.hpp); a rewrite waits for them, so that
  // run_info.json lists only snapshots that are complete under their names.
  constexpr std::chrono::duration<double> kTableFlushInterval{1.0};
  std::optional<std::chrono::steady_clock::time_point> last_flush;
  auto snapshot = [&] {
    writer.write_snapshot(model.dimension(), dynamics.steps(), dynamics.time(), model.points.owned,
                          snapshot_sources(model, scene.output.fields));
    const auto now = std::chrono::steady_clock::now();
    if (last_flush && now - *last_flush < kTableFlushInterval) return;
    update_info("running", "");
    writer.flush(info);
    last_flush = now;
  };
  auto fail = [&](const std::string& reason) {
    const std::string message = "numerical failure at step " + std::to_string(dynamics.steps()) + ", t = " +
                                text(dynamics.time()) + " s: " + reason +
                                "; the last good snapshot is kept (try a smaller time.step or check the material)";
    if (scene.effects.damage)
      writer.log("at the failure: broken bonds " + std::to_string(model.broken_bonds) + " (pairs), fracture dissipation " +
                 text(dynamics.energy().fracture_dissipation) + " J, detached points " +
                 std::to_string(model.detached_points) + " (" + std::to_string(model.unstable_detached_points) +
                 " of them for the time step's sake)");
    writer.log(message);
    update_info("numerical_failure", message);
    writer.flush(info);
    throw NumericalFailure(options.run_directory + ": " + message);
  };

  Schedule rows(scene.output.load_interval, dt, true);
  Schedule snapshots(scene.output.interval, dt, false);
  Schedule checkpoints(scene.output.checkpoint_interval, dt, false);
  const std::int64_t guard_start_step = scene.numerics.energy_check_start_step;
  EnergyGuard guard(scene.numerics.energy_check_tolerance, guard_start_step);
  // The energy check stops growth; energy that disappears without a dissipation that accounts for
  // it is not an instability but a wrong answer all the same: reported at the end.
  double worst_balance = 0.0;
  const std::string points_file = std::filesystem::absolute(options.points_file).string();

  std::int64_t first_step = 1;
  if (resume) {
    RunLoopState loop = restore_checkpoint(*resume, identity, model, dynamics);
    if (loop.time_step != dt)
      throw InputError(resume->path + ": the checkpoint's time step " + text(loop.time_step) +
                       " s is not the one this run arrives at (" + text(dt) + " s); cannot continue it bit for bit");
    rows.restore(loop.next_row);
    snapshots.restore(loop.next_snapshot);
    checkpoints.restore(loop.next_checkpoint);
    guard.restore(loop.guard);
    worst_balance = loop.worst_balance;
    writer.restore_tables(table_up_to_checkpoint(writer.path(run_layout::load), loop.load_table_bytes,
                                                 loop.load_table_fingerprint, resume->header.step),
                          table_up_to_checkpoint(writer.path(run_layout::energy), loop.energy_table_bytes,
                                                 loop.energy_table_fingerprint, resume->header.step));
    remove_output_after_checkpoint(writer.directory(), loop.snapshots);
    writer.restore_snapshots(std::move(loop.snapshots));
    first_step = dynamics.steps() + 1;
    update_info("running", "");
    writer.flush(info);
  } else {
    record_rows();
    snapshot();
  }

  // A checkpoint after step s: the tables are flushed first, so that
  // load.csv and energy.csv on disk hold every row the checkpoint counts. A write error stops the
  // run (exit 2) with the previous checkpoint intact.
  int checkpoints_written = 0;
  std::int64_t last_checkpoint_step = resume ? resume->header.step : -1;
  auto checkpoint = [&] {
    update_info("running", "");
    writer.flush(info);
    last_flush = std::chrono::steady_clock::now();
    RunLoopState loop;
    loop.next_row = rows.next();
    loop.next_snapshot = snapshots.next();
    loop.next_checkpoint = checkpoints.next();
    loop.worst_balance = worst_balance;
    loop.guard = guard.history();
    loop.snapshots = writer.snapshots();
    loop.load_table_bytes = writer.load_table().size();
    loop.load_table_fingerprint = fnv1a(writer.load_table());
    loop.energy_table_bytes = writer.energy_table().size();
    loop.energy_table_fingerprint = fnv1a(writer.energy_table());
    loop.points_file = points_file;
    loop.time_step = dt;
    ++checkpoints_written;
    try {
      write_checkpoint(checkpoint_path(writer.directory()), identity, model, dynamics, loop,
                       options.fail_checkpoint_write == checkpoints_written);
    } catch (const InputError& e) {
      const std::string message =
          std::string(e.what()) + "; the run stopped at step " + std::to_string(dynamics.steps()) +
          (last_checkpoint_step >= 0 ? "; the previous checkpoint (step " + std::to_string(last_checkpoint_step) +
                                           ") is intact: free space, then mppm-solve --restart " + writer.directory() +
                                           " continues from it"
                                     : std::string("; no checkpoint was written before"));
      writer.log(message);
      update_info("write_error", message);
      try {
        writer.flush(info);
      } catch (const InputError&) {
        // The disk that refused the checkpoint may refuse the tables too: the message above is
        // what matters, and the tables of the last flush are intact.
      }
      throw InputError(message);
    }
    last_checkpoint_step = dynamics.steps();
  };

  Progress progress("mppm-solve", steps, options.quiet);
  const InterruptionHandlers handlers;
  SolveResult r;
  for (std::int64_t s = first_step; s <= steps; ++s) {
    const bool row = rows.due(s) || s == steps;
    const bool snap = snapshots.due(s) || s == steps;
    // A finished run needs no checkpoint to continue from.
    const bool checkpoint_due = checkpoints.due(s) && s < steps;
    dynamics.step(row);
    if (!dynamics.finite()) fail(non_finite_reason(dynamics));
    if (row) {
      record_rows();
      if (const auto reason = guard.check(s, dynamics.energy(), dynamics.initial_total_energy())) fail(*reason);
      if (s >= guard_start_step && std::abs(dynamics.balance_error()) > std::abs(worst_balance))
        worst_balance = dynamics.balance_error();
    }
    if (snap) snapshot();
    const bool interrupted = interruption_requested() || options.interrupt_after_step == s;
    // With checkpoints on, an interruption (SIGINT, SIGTERM) writes one too, before the snapshot of
    // the interruption (which the checkpoint does not count, so that a restart removes it).
    if (checkpointing && (checkpoint_due || interrupted)) checkpoint();
    if (interrupted) {
      clear_interruption();
      if (!snap)
        writer.write_snapshot(model.dimension(), dynamics.steps(), dynamics.time(), model.points.owned,
                              snapshot_sources(model, scene.output.fields));
      const std::string message = "interrupted at step " + std::to_string(s) + " of " + std::to_string(steps) +
                                  ", t = " + text(dynamics.time()) + " s; the state there is the last snapshot" +
                                  (checkpointing ? "; mppm-solve --restart " + writer.directory() +
                                                       " continues from the checkpoint written there"
                                                 : std::string());
      writer.log(message);
      update_info("interrupted", message);
      writer.flush(info);
      r.interrupted = true;
      r.message = message;
      break;
    }
    progress.update(s, "t = " + text(dynamics.time()) + " s");
  }
  if (!r.interrupted) {
    std::string warning;
    if (std::abs(worst_balance) > scene.numerics.energy_check_tolerance)
      warning = "warning: the energy balance error reached " + text(worst_balance) +
                " (beyond numerics.energy_check_tolerance " + text(scene.numerics.energy_check_tolerance) +
                "): energy " + (worst_balance < 0.0 ? "disappeared" : "appeared") +
                " that neither the external work nor a dissipation accounts for (energy.csv, balance_error)";
    if (!warning.empty()) writer.log(warning);
    update_info("completed", warning);
    writer.log("completed " + std::to_string(steps) + " steps in " + text(info.wall_seconds) +
               " s, final balance error " + text(dynamics.balance_error()) +
               (scene.effects.damage ? ", broken bonds " + std::to_string(model.broken_bonds) + " (pairs), fracture dissipation " +
                                           text(dynamics.energy().fracture_dissipation) + " J, detached points " +
                                           std::to_string(model.detached_points) + " (" +
                                           std::to_string(model.unstable_detached_points) +
                                           " of them for the time step's sake)"
                                     : std::string()));
    writer.flush(info);
  }
  progress.finish("t = " + text(dynamics.time()) + " s");

  r.steps = dynamics.steps();
  r.time_step = dt;
  r.critical_time_step = critical.step;
  r.limiting_mode = critical.limiting_mode;
  r.final_balance_error = dynamics.balance_error();
  return r;
}

}  // namespace

}  // namespace mppm::solver
