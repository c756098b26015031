// The run estimate (see run_estimate.hpp).
#include "solver/run_estimate.hpp"

#include <cmath>
#include <sstream>

#include "common/memory_estimate.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/model.hpp"
#include "solver/pore_fluid.hpp"
#include "solver/regular_lattice.hpp"

namespace mppm::solver {

namespace {

// The critical step of a sample block of the scene's lattice: its spacing, horizon, material and
// effects, a little more than two horizons across, with free faces, edges and corners, where the
// cut families raise the highest frequency (the quickstart plate: a periodic sample of the bulk
// gives 1.47x the plate's critical step, the block 1.0x). The run computes its own.
struct SampleSteps {
  double critical = 0.0, damage = 0.0;
  double fluid = 0.0;  // the flow's step limit of an interior point (pore fluid only)
};
SampleSteps sample_block_steps(const Scene& scene) {
  const int cells = static_cast<int>(std::ceil(2.0 * scene.geometry.horizon_factor)) + 3;
  const double dx = scene.geometry.spacing;
  const PointCloud sample = make_regular_lattice(scene.dimension, {cells, cells, cells}, dx, scene.thickness);
  Model model = build_model(sample, model_options(scene));
  SampleSteps s;
  s.critical = coupled_critical_time_step(model).step;  // the mode is not named here
  s.damage = model.damage_critical_step(s.critical);
  if (model.fluid) s.fluid = fluid_step_limit(model.points, model.bonds, *model.fluid);
  return s;
}

std::uint64_t boundary_points(const PointCloud& cloud) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    n += (!cloud.region.empty() && cloud.region[i] > 0) || (!cloud.boundary_id.empty() && cloud.boundary_id[i] > 0);
  return n;
}

std::string seconds_text(double s) {
  std::ostringstream out;
  out.precision(3);
  if (s < 120.0)
    out << s << " s";
  else if (s < 7200.0)
    out << s / 60.0 << " min";
  else
    out << s / 3600.0 << " h";
  return out.str();
}

}  // namespace

RunEstimate estimate_run(const Scene& scene, const PointCloud& cloud, std::uint64_t bonds, int threads) {
  RunEstimate e;
  e.points = cloud.size();
  e.bonds_counted = bonds > 0;
  e.bonds = bonds > 0 ? bonds : estimated_bond_entries(e.points, scene.geometry.horizon_factor, scene.dimension);
  e.threads = threads;
  const SampleSteps sample = sample_block_steps(scene);
  e.critical_step = sample.critical;
  CriticalTimeStep critical;
  critical.step = sample.critical;
  critical.translational = sample.critical;
  critical.limiting_mode = "translational";
  critical.driver = "the material's moduli over its density (a sample block of the lattice)";
  e.step_given = scene.time.step.has_value();
  e.time_step = choose_time_step(scene, critical, sample.damage);
  e.steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(scene.time.end / e.time_step - 1e-9)));
  RunCostInput cost;
  cost.dimension = scene.dimension;
  cost.effects = scene.effects.names();
  cost.points = e.points;
  cost.bonds = e.bonds;
  cost.steps = e.steps;
  cost.threads = threads;
  if (sample.fluid > 0.0) {
    // Unsaturated: the start's schedule, every step, and the limit's bond loop before each update.
    const bool unsaturated = scene.material.pore_fluid && scene.material.pore_fluid->retention;
    const FlowSchedule flow =
        unsaturated ? unsaturated_flow_schedule(sample.fluid, e.time_step, scene.numerics.flow_integration)
                    : flow_schedule(sample.fluid, e.time_step, scene.numerics.flow_integration);
    cost.flow_evaluations_per_step = flow.rate_evaluations_per_step();
  }
  // The snapshots at t = 0, at every output.interval and at the end (common/run_directory.hpp).
  cost.snapshots = scene.output.interval > 0.0
                       ? static_cast<std::int64_t>(std::floor(scene.time.end / scene.output.interval + 1e-9)) + 1
                       : 2;
  const std::uint64_t rotation = scene.effects.micropolar ? (scene.dimension == 3 ? 3 : 1) : 0;
  for (const auto& field : scene.output.fields)
    cost.snapshot_values_per_point +=
        snapshot_field_components(field, static_cast<std::uint64_t>(scene.dimension), rotation);
  e.snapshots = cost.snapshots;
  e.cost = estimate_run_cost(cost);
  MemoryEstimateInput memory;
  memory.points = e.points;
  memory.bonds = e.bonds;
  memory.horizon_factor = scene.geometry.horizon_factor;
  memory.dimension = scene.dimension;
  memory.effects = scene.effects.names();
  memory.snapshot_fields = scene.output.fields;
  memory.damping = scene.numerics.damping != 0.0;
  memory.unsaturated = scene.material.pore_fluid && scene.material.pore_fluid->retention;
  memory.boundary_points = boundary_points(cloud);
  e.memory_bytes = estimate_run_memory(memory).total_bytes;
  return e;
}

std::string format_run_estimate(const Scene& scene, const RunEstimate& e) {
  std::ostringstream s;
  s.precision(4);
  std::string effects;
  for (const auto& name : scene.effects.names()) effects += (effects.empty() ? "" : ", ") + name;
  s << "estimate for " << scene.path << " (" << scene.dimension << "-D, effects "
    << (effects.empty() ? "none" : effects) << ", " << e.threads << " thread" << (e.threads > 1 ? "s" : "") << "):\n";
  s << "  points       " << e.points << "\n";
  s << "  bonds        " << e.bonds << (e.bonds_counted ? "" : " (lattice estimate)") << " (stored from both ends)\n";
  s << "  time step    " << e.time_step << " s (";
  if (e.step_given)
    s << "given";
  else
    s << "auto: safety " << scene.time.safety;
  s << "; critical " << e.critical_step << " s of a sample block)\n";
  s << "  steps        " << e.steps << " to " << scene.time.end << " s\n";
  s << "  wall time    ~" << seconds_text(e.cost.total_seconds) << " (start-up ~"
    << seconds_text(e.cost.start_up_seconds) << ", " << e.steps << " steps x " << e.cost.seconds_per_step * 1e3
    << " ms, " << e.snapshots << " snapshots x " << e.cost.snapshot_seconds * 1e3 << " ms)\n";
  s << "  peak memory  ~" << format_memory(e.memory_bytes) << "\n";
  s << "  (wall time from the costs measured on the development machine, common/run_cost_model.cpp;\n"
       "   scale it by this machine's speed)\n";
  return s.str();
}

}  // namespace mppm::solver
