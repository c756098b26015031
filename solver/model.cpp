// Assembly of the discrete model: family search, pre-crack cuts, shape tensors.
#include "solver/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/precrack_crossing.hpp"
#include "solver/bond_breakage.hpp"
#include "solver/crack_area.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/plasticity/material_registry.hpp"
#include "solver/point_stability.hpp"
#include "solver/shape_tensor.hpp"

namespace mppm::solver {

namespace {

// Marks the bond entries whose segment touches a pre-crack element with the broken bit (nothing
// is broken before the first step, so the bit is free and no per-bond flag array is needed: 1 B
// per bond entry at the start-up's peak); returns false without pre-cracks. The crossing test is
// symmetric in its end points, so a bond is cut from both ends or from neither.
bool mark_bonds_cut_by_precracks(const PointCloud& cloud, const PointData& p, BondFamilies& f, double horizon) {
  if (cloud.precrack_vertices.empty()) return false;  // (not used with periodic lattices)
  const PrecrackIndex index(cloud.dimension, cloud.precrack_vertices, horizon);
  if (index.empty()) return false;
  const int D = p.dimension;
  const auto n = static_cast<std::int64_t>(p.owned);
#pragma omp parallel for schedule(static) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    Point3 a{0, 0, 0}, b{0, 0, 0};
    for (int c = 0; c < D; ++c) a[c] = p.position[i * D + c];
    // Twice the horizon: every bond is shorter. Most points are far from every pre-crack.
    if (!index.may_cross_within(a, 2 * horizon)) continue;
    for (std::int64_t k = f.offset[i]; k < f.offset[i + 1]; ++k) {
      // The same call (lower global id first, stored positions) from both ends gives the same
      // answer, so a bond is cut from both ends or from neither, on any process.
      const std::size_t j = f.neighbor_of(k);
      for (int c = 0; c < D; ++c) b[c] = p.position[j * D + c];
      if (p.global_index(j) > p.global_index(i) ? index.crosses(a, b) : index.crosses(b, a)) f.break_bond(k);
    }
  }
  return true;
}

// Removes the cut bonds from both ends before the first step; returns the bond entries removed (of
// this process's points: a pair within them counts twice). With
// `keep`, they are kept aside in `kept` for the crack area (crack_area.hpp).
std::size_t cut_precrack_bonds(const PointCloud& cloud, PointData& p, BondFamilies& f, double horizon, bool keep,
                               PrecrackCutBonds& kept) {
  if (!mark_bonds_cut_by_precracks(cloud, p, f, horizon)) return 0;
  if (keep) kept = record_cut_bonds(f);
  const std::size_t before = f.bond_count();
  remove_bonds(f, [&](std::size_t, std::size_t k) { return !f.acting(static_cast<std::int64_t>(k)); });
  return before - f.bond_count();
}

// The drain bonds to inert layers that touch a pre-crack are dropped (cracks do not conduct), with the
// test the families' cuts use (the lower index first).
void cut_precrack_drain_bonds(const PointCloud& cloud, const PointData& p, std::vector<DrainBond>& drains,
                              double horizon) {
  if (cloud.precrack_vertices.empty() || drains.empty()) return;
  const PrecrackIndex index(cloud.dimension, cloud.precrack_vertices, horizon);
  if (index.empty()) return;
  const int D = p.dimension;
  auto point = [&](std::size_t i) {
    Point3 x{0, 0, 0};
    for (int c = 0; c < D; ++c) x[c] = p.position[i * D + c];
    return x;
  };
  std::erase_if(drains, [&](const DrainBond& d) {
    const auto i = static_cast<std::size_t>(d.body), j = static_cast<std::size_t>(d.layer);
    return j > i ? index.crosses(point(i), point(j)) : index.crosses(point(j), point(i));
  });
}

// Point i inside a box (a 2-D box's z range is unbounded).
bool inside(const PointData& p, std::size_t i, const std::array<std::array<double, 3>, 2>& box) {
  return inside_box(&p.position[i * static_cast<std::size_t>(p.dimension)], p.dimension, box);
}

}  // namespace

ModelOptions model_options(const Scene& scene) {
  ModelOptions mo;
  mo.constants = cosserat_constants(scene);
  mo.effects = scene.effects;
  mo.horizon = scene.geometry.horizon();
  mo.spacing = scene.geometry.spacing;
  if (scene.effects.damage && scene.material.damage) {
    mo.no_fail_depth = scene.material.damage->no_fail_depth;
    if (scene.material.damage->region) mo.damage_region = scene.material.damage->region->box;
  }
  if (scene.effects.viscoplasticity && scene.material.viscoplasticity && scene.material.viscoplasticity->region)
    mo.plastic_region = scene.material.viscoplasticity->region->box;
  if (scene.effects.viscoplasticity)
    mo.viscoplastic_model = plasticity::make_viscoplastic_model(scene.material, scene.path);
  if (scene.effects.pore_fluid && scene.material.pore_fluid) {
    mo.fluid = fluid_constants(scene);
    mo.initial_pressure = scene.material.pore_fluid->initial_pressure;
    mo.free_surface = scene.material.pore_fluid->free_surface;
  }
  return mo;
}

namespace {

// Everything after the points: `cloud` is read for its pre-cracks only.
Model complete_model(PointData points, const PointCloud& cloud, const ModelOptions& o, PhaseTimer* phases) {
  auto mark = [phases](const char* phase) {
    if (phases) phases->mark(phase);
  };
  Model m;
  m.constants = o.constants;
  m.effects = o.effects;
  m.horizon = o.horizon;
  m.points = std::move(points);
  FamilyOptions fo;
  fo.horizon = o.horizon;
  fo.spacing = o.spacing;
  fo.period = o.period;
  m.bonds = build_families(m.points, fo);
  // The inert drained layers leave the mechanics before anything reads the families (docs/theory.md
  // section 12): the rest of the model is that of the run without them.
  std::vector<DrainBond> inert_drains;
  if (o.effects.pore_fluid) inert_drains = take_out_inert_layers(m.points, m.bonds, o.fluid_boundaries);
  mark("bond families");
  if (o.effects.damage && !cloud.precrack_vertices.empty()) {
    // The family volumes before the cuts are kept for the points that lost bonds to them, so that
    // the notch shows as damage from the start; in 3-D the cut bonds themselves are kept for the
    // crack area, which counts them as broken (crack_area.hpp).
    const std::vector<double> before_cuts = family_volumes(m.points, m.bonds);
    m.precrack_cut_entries =
        cut_precrack_bonds(cloud, m.points, m.bonds, o.horizon, m.dimension() == 3, m.precrack_cuts);
    record_precut_family_volumes(m.points, m.bonds, before_cuts);
  } else {
    m.precrack_cut_entries = cut_precrack_bonds(cloud, m.points, m.bonds, o.horizon, false, m.precrack_cuts);
  }
  cut_precrack_drain_bonds(cloud, m.points, inert_drains, o.horizon);
  mark("pre-crack cuts");
  if (o.effects.damage) {
    index_bond_pairs(m.bonds, PointOrder(m.points));
    // The ghosts' flags too: the bond work and the breakage read both ends'.
    const bool distributed = !m.points.global_id.empty();
    mark_no_fail_zone(m.points, o.no_fail_depth, o.fluid_boundaries.fluid_only_ids, distributed ? &cloud : nullptr);
    if (o.damage_region)
      for (std::size_t i = 0; i < m.points.total(); ++i)
        if (!inside(m.points, i, *o.damage_region)) m.points.no_fail[i] = 1;
  }
  if (o.effects.viscoplasticity && o.plastic_region)
    for (std::size_t i = 0; i < m.points.owned; ++i)
      m.points.plastic_active[i] = inside(m.points, i, *o.plastic_region) ? 1 : 0;
  mark("damage set-up");
  m.detached_points = update_shape_tensors(m.points, m.bonds, m.constants);
  // Pass 2 reads the neighbours' shape-tensor terms: the ghosts' come from their owners; with
  // damage the stability blocks read the neighbours' K^-1 and detachment too.
  share_shape_terms(m.points, o.effects.damage);
  if (o.effects.viscoplasticity) {
    if (!o.viscoplastic_model)
      throw std::logic_error("build_model: the viscoplasticity effect needs ModelOptions::viscoplastic_model");
    m.viscoplastic_model = o.viscoplastic_model;
  }
  if (o.effects.pore_fluid) {
    if (!o.fluid) throw std::logic_error("build_model: the pore_fluid effect needs ModelOptions::fluid");
    m.fluid = o.fluid;
    start_fluid(m.points, *o.fluid, o.initial_pressure, o.free_surface);
    m.drains = make_drain_bonds(m.points, m.bonds, o.fluid_boundaries, std::move(inert_drains));
    for (const DrainedPoints& layer : o.fluid_boundaries.drained)
      if (layer.inert)
        for (const std::int32_t i : layer.points) {
          ++m.inert_points;
          if (m.points.detached[static_cast<std::size_t>(i)]) --m.detached_points;  // they have no bonds
        }
  }
  m.kernel = internal_force_functions(m.points.dimension, o.effects);
  mark("shape tensors");
  return m;
}

}  // namespace

Model build_model(const PointCloud& cloud, const ModelOptions& o, PhaseTimer* phases) {
  PointData points = make_point_data(cloud, o.effects);
  if (phases) phases->mark("point data");
  return complete_model(std::move(points), cloud, o, phases);
}

Model build_model(PointCloud&& cloud, const ModelOptions& o, PhaseTimer* phases) {
  PointData points = make_point_data(std::move(cloud), o.effects);
  if (phases) phases->mark("point data");
  return complete_model(std::move(points), cloud, o, phases);
}

Model build_local_model(const PointCloud& cloud, const LocalPoints& local, const GhostExchange& ghosts,
                        const ProcessGroup& processes, const ModelOptions& o, PhaseTimer* phases) {
  if (o.effects.pore_fluid)
    throw std::invalid_argument("effect pore_fluid does not run across processes yet (run it on one process)");
  if (o.period[0] > 0.0 || o.period[1] > 0.0 || o.period[2] > 0.0)
    throw std::invalid_argument("periodic lattices do not run across processes");
  PointData points = make_local_point_data(cloud, local, o.effects);
  points.ghost_source = &ghosts;
  points.processes = &processes;
  if (phases) phases->mark("point data");
  return complete_model(std::move(points), cloud, o, phases);
}

bool Model::holds_history() const {
  const auto nonzero = [](const std::vector<double>& v) {
    return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  };
  const auto broken = [](std::int32_t entry) { return entry < 0; };
  const auto first = bonds.neighbor.begin();
  const auto last = first + static_cast<std::ptrdiff_t>(bonds.offset[points.owned]);
  return std::any_of(first, last, broken) || nonzero(points.plastic_strain) || nonzero(points.plastic_wryness);
}

InternalForceFunction Model::linear_operator_kernel() const {
  double history = holds_history() ? 1.0 : 0.0;
  if (points.processes) history = points.processes->highest(history);
  return history > 0.0 ? kernel.forces : kernel.elastic_forces;
}

void Model::advance_internal_forces(double dt, double end_time, bool with_energy) {
  const StepAdvance step{viscoplastic_model.get(), dt};
  (with_energy ? kernel.forces_and_energy : kernel.forces)(points, bonds, constants, &step);
  if (effects.damage) {
    const BreakageUpdate u =
        update_after_breakage(points, bonds, constants, kernel, block_eigenvalue_limit, breakage_workspace);
    broken_bonds += u.broken_pairs;
    detached_points += u.newly_detached;
    unstable_detached_points += u.unstable_detached;
    energy_detached_points += u.energy_detached;
    last_fracture_dissipation = u.released_energy;
    last_breakage_anywhere = u.broke;
    if (u.broke) crack_arrivals.update(points, bonds, breakage_workspace.sorted, end_time);
  }
}

double Model::damage_critical_step(double critical_step) const {
  if (!effects.damage) return critical_step;
  return damage_critical_step(critical_step, max_point_block_eigenvalue(points, bonds, constants));
}

double Model::damage_critical_step(double critical_step, double largest_point_block) const {
  if (!effects.damage) return critical_step;
  double start = largest_point_block;
  if (points.processes) start = points.processes->highest(start);
  return start > 0.0 ? std::min(critical_step, 2.0 / std::sqrt(constants.damaged_frequency_ratio * start))
                     : critical_step;
}

void Model::set_breakage_time_step(double dt) {
  if (!effects.damage) return;
  block_eigenvalue_limit = 4.0 / (dt * dt) / constants.damaged_frequency_ratio;
}

StoredEnergy internal_energy(const Model& model) {
  return model.kernel.stored_energy_sums(model.points, model.constants);
}

}  // namespace mppm::solver
