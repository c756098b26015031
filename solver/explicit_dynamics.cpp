// Velocity-Verlet stepping with prescribed layers and energy bookkeeping. Every loop writes only
// per-point data; sums over points are exact (exact_sum.hpp, exact_point_sums.hpp), so any thread
// count gives the same bits.
#include "solver/explicit_dynamics.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>

#include "solver/exact_point_sums.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/pressure_change_forces.hpp"

namespace mppm::solver {

ExplicitDynamics::ExplicitDynamics(Model& model, const BoundaryConditions& conditions, double time_step,
                                   std::array<double, 3> gravity)
    : model_(model), conditions_(conditions), dt_(time_step), gravity_(gravity), use_gravity_(model.effects.gravity) {
  lay_out_tracked_points();
}

void ExplicitDynamics::set_damping(double c) {
  damping_ = c;
  lay_out_tracked_points();
}

void ExplicitDynamics::lay_out_tracked_points() {
  const PointData& p = model_.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  track_all_ = use_gravity_ || damping_ != 0.0;
  tracked_.clear();
  load_rows_.clear();
  if (!track_all_) {
    for (std::size_t i = 0; i < p.owned; ++i)
      if (conditions_.prescribed(i) != 0) tracked_.push_back(static_cast<std::int32_t>(i));
    for (const LoadedSurface& s : conditions_.surfaces())
      tracked_.insert(tracked_.end(), s.points.begin(), s.points.end());
    std::sort(tracked_.begin(), tracked_.end());
    tracked_.erase(std::unique(tracked_.begin(), tracked_.end()), tracked_.end());
    tracked_.shrink_to_fit();
    for (const LoadedSurface& s : conditions_.surfaces())
      for (const std::int32_t i : s.points)
        load_rows_.push_back(static_cast<std::int32_t>(tracked_row(static_cast<std::size_t>(i))));
  }
  const std::size_t n = tracked_count();
  body_force_.assign(n * D, 0.0);
  body_force_prev_.assign(n * D, 0.0);
  force_prev_.assign(n * D, 0.0);
  moment_prev_.assign(n * R, 0.0);
  displacement_prev_.assign(n * D, 0.0);
  rotation_prev_.assign(n * R, 0.0);
  work_increment_.assign(n, 0.0);
}

std::size_t ExplicitDynamics::tracked_count() const { return track_all_ ? model_.points.owned : tracked_.size(); }

std::ptrdiff_t ExplicitDynamics::tracked_row(std::size_t i) const {
  if (track_all_) return static_cast<std::ptrdiff_t>(i);
  const auto it = std::lower_bound(tracked_.begin(), tracked_.end(), static_cast<std::int32_t>(i));
  return it != tracked_.end() && *it == static_cast<std::int32_t>(i) ? it - tracked_.begin() : -1;
}

template <class Visit>
int ExplicitDynamics::for_each_point_in(std::size_t lo, std::size_t hi, Visit&& visit) const {
  // The tracked points are sorted: one search for the range's first, then a walk along it.
  std::size_t k =
      track_all_
          ? lo
          : static_cast<std::size_t>(std::lower_bound(tracked_.begin(), tracked_.end(), static_cast<std::int32_t>(lo)) -
                                     tracked_.begin());
  int result = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    std::ptrdiff_t row = -1;
    if (track_all_)
      row = static_cast<std::ptrdiff_t>(i);
    else if (k < tracked_.size() && static_cast<std::size_t>(tracked_[k]) == i)
      row = static_cast<std::ptrdiff_t>(k++);
    result |= visit(i, row);
  }
  return result;
}

template <class Visit>
int ExplicitDynamics::for_each_point(bool threaded, Visit&& visit) const {
  const std::size_t n = model_.points.owned;
  int result = 0;
#pragma omp parallel if (threaded) reduction(| : result)
  {
    const auto threads = static_cast<std::size_t>(omp_get_num_threads());
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    result |= for_each_point_in(n * thread / threads, n * (thread + 1) / threads, visit);
  }
  return result;
}

void ExplicitDynamics::compute_loads_and_forces(bool with_energy, bool advance) {
  PointData& p = model_.points;
  const int D = p.dimension;
  if (advance) {
    model_.advance_internal_forces(dt_, time_, with_energy);
  } else {
    model_.compute_internal_forces(with_energy);
  }
  std::fill(body_force_.begin(), body_force_.end(), 0.0);
  if (use_gravity_) {  // every point is tracked then
    const double rho = model_.constants.density;
    for (std::size_t i = 0; i < p.owned; ++i)
      for (int c = 0; c < D; ++c) body_force_[i * D + c] = rho * gravity_[c];
  }
  conditions_.add_surface_loads(p, time_, body_force_, track_all_ ? nullptr : &load_rows_);
}

std::array<double, 3> ExplicitDynamics::kinetic_sums() const {
  const PointData& p = model_.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  const double rho = model_.constants.density;
  const double inertia = model_.constants.micro_inertia;
  // Kinetic energy of the central-difference scheme, 1/2 M v^{n-1/2} . v^{n+1/2}
  // = 1/2 M (v^n . v^n - (dt/2)^2 a^n . a^n): with it, kinetic + stored energy changes exactly by
  // the trapezoid-rule work of the loads for a linear elastic model (the plain 1/2 M v^n . v^n
  // differs from it by O((omega dt)^2) in the highest modes).
  const double h2 = 0.25 * dt_ * dt_;
  // Summed exactly (exact_point_sums.hpp): the same bits for any thread count.
  return exact_point_sums<3>(p, [&](std::size_t lo, std::size_t hi, ExactSums<3>& acc) {
    for_each_point_in(lo, hi, [&](std::size_t i, std::ptrdiff_t tracked_at) {
      // A point that is not tracked has no body force.
      const bool tracked = tracked_at >= 0;
      const auto row = static_cast<std::size_t>(tracked ? tracked_at : 0);
      const unsigned fixed = conditions_.prescribed(i);
      double v2 = 0.0, t2 = 0.0;
      for (int c = 0; c < D; ++c) {
        const std::size_t k = i * D + c;
        if ((fixed >> c) & 1u) continue;
        const double a = (p.force[k] + (tracked ? body_force_[row * D + c] : 0.0)) / rho;
        v2 += p.velocity[k] * p.velocity[k] - h2 * a * a;
        t2 += p.velocity[k] * p.velocity[k] + h2 * a * a;
      }
      acc[0] += 0.5 * rho * p.volume[i] * v2;
      acc[2] += 0.5 * rho * p.volume[i] * t2;
      if (R > 0) {
        double s2 = 0.0, r2 = 0.0;
        for (int c = 0; c < R; ++c) {
          const std::size_t k = i * R + c;
          if ((fixed >> (BoundaryConditions::kRotationBit + c)) & 1u) continue;
          const double a = p.moment[k] / inertia;
          s2 += p.spin[k] * p.spin[k] - h2 * a * a;
          r2 += p.spin[k] * p.spin[k] + h2 * a * a;
        }
        acc[1] += 0.5 * inertia * p.volume[i] * s2;
        acc[2] += 0.5 * inertia * p.volume[i] * r2;
      }
      return 0;
    });
  });
}

void ExplicitDynamics::evaluate_energy() {
  const PointData& p = model_.points;
  const auto sums = kinetic_sums();
  const double kinetic = sums[0], rotational = sums[1], terms = sums[2];
  energy_.kinetic_terms = terms;
  const StoredEnergy e = internal_energy(model_);
  energy_.kinetic = kinetic;
  energy_.rotational_kinetic = rotational;
  energy_.elastic = e.elastic();
  energy_.stabilization = e.stabilization;
  if (model_.fluid) {
    energy_.fluid_stored = e.fluid;
    energy_.fluid_volume = fluid_volume(p, *model_.fluid);
    double out = 0.0;  // in scene order
    for (std::size_t k = 0; k < boundary_volume_.size(); ++k)
      out += conditions_.drained_condition(k) ? boundary_volume_[k] : -boundary_volume_[k];
    energy_.fluid_net_outflow = out;
  }
}

bool ExplicitDynamics::flow_due() const {
  return model_.fluid && (flow_.substeps > 1 || flow_.stages > 1 || steps_ % flow_.interval == 0);
}

void ExplicitDynamics::advance_flow() {
  // The boundaries at the step's end, the time of the state the updates start from (without fluid
  // boundaries their lists are empty: the plain flow).
  conditions_.prescribe_pore_pressure(model_.points, time_);
  flow_boundaries_.drains = &model_.drains;
  flow_boundaries_.sources.clear();
  for (const FedSurface& s : conditions_.fed())
    flow_boundaries_.sources.push_back({&s.points, s.value.component_at(time_, 0) * s.area / s.volume_sum});
  boundary_volume_start_ = boundary_volume_;  // (sized at initialize(): no allocation)
  // Unsaturated: the limit at the present saturations (the layers' prescribed pressures set above).
  if (flow_.follows_saturation)
    flow_ = unsaturated_flow_schedule(fluid_step_limit(model_.points, model_.bonds, *model_.fluid, &model_.drains), dt_,
                                      flow_.integration);
  // The span the flow advances: a step (substeps or a super step), or the interval's steps.
  const double span = flow_.substeps > 1 || flow_.stages > 1 ? dt_ : dt_ * static_cast<double>(flow_.interval);
  if (flow_.stages > 1) {
    energy_.flow_dissipation += flow_super_step(model_.points, model_.bonds, *model_.fluid, span, flow_.stages,
                                                &flow_boundaries_, pressure_before_flow_, super_step_work_);
    book_boundary_volumes(span);
  } else {
    const std::int64_t updates = flow_.substeps > 1 ? flow_.substeps : 1;
    for (std::int64_t k = 0; k < updates; ++k) flow_update_with_boundaries(span / static_cast<double>(updates));
  }
  for (std::size_t c = 0; c < boundary_volume_.size(); ++c)
    boundary_rate_[c] = (boundary_volume_[c] - boundary_volume_start_[c]) / span;
  // A content no pressure gives (the retention inverse failed: NaN) stops the run at this step.
  if (model_.fluid->retention && first_unrecovered_pressure()) finite_ = false;
}

std::optional<std::size_t> ExplicitDynamics::first_unrecovered_pressure() const {
  const PointData& p = model_.points;
  if (p.pore_pressure.empty()) return std::nullopt;
  for (std::size_t i = 0; i < p.owned; ++i)
    if (p.region[i] == 0 && !std::isfinite(p.pore_pressure[i])) return i;
  return std::nullopt;
}

void ExplicitDynamics::flow_update_with_boundaries(double h) {
  energy_.flow_dissipation += flow_update(model_.points, model_.bonds, *model_.fluid, h, &flow_boundaries_);
  book_boundary_volumes(h);
}

void ExplicitDynamics::book_boundary_volumes(double h) {
  const std::vector<DrainedLayer>& drained = conditions_.drained();
  for (std::size_t k = 0; k < drained.size(); ++k) boundary_volume_[drained[k].condition] += model_.drains.outflow[k];
  const std::vector<FedSurface>& fed = conditions_.fed();
  for (std::size_t k = 0; k < fed.size(); ++k)
    boundary_volume_[fed[k].condition] += h * flow_boundaries_.sources[k].rate * fed[k].volume_sum;
}

ExplicitDynamics::FluidBoundaryFlow ExplicitDynamics::fluid_boundary_flow(std::size_t k) const {
  if (k >= boundary_volume_.size()) return {};
  return {boundary_rate_[k], boundary_volume_[k]};
}

ExplicitDynamics::Carried ExplicitDynamics::carried() const {
  Carried c{time_, steps_, energy_, initial_total_, {}};
  if (has_fluid_boundaries()) {
    c.fluid_boundary_flows = boundary_volume_;
    c.fluid_boundary_flows.insert(c.fluid_boundary_flows.end(), boundary_rate_.begin(), boundary_rate_.end());
  }
  return c;
}

void ExplicitDynamics::initialize() {
  time_ = 0.0;
  steps_ = 0;
  conditions_.prescribe(model_.points, time_);
  if (model_.fluid && has_fluid_boundaries()) {
    conditions_.prescribe_pore_pressure(model_.points, time_);
    boundary_volume_.assign(conditions_.condition_count(), 0.0);
    boundary_volume_start_.assign(conditions_.condition_count(), 0.0);
    boundary_rate_.assign(conditions_.condition_count(), 0.0);
  }
  compute_loads_and_forces(true, false);
  // The points the pre-crack cuts put on the crack path are on it from the start.
  if (model_.effects.damage) model_.crack_arrivals.start(model_.points, model_.bonds, time_);
  energy_.external_work = 0.0;
  energy_.plastic_dissipation = 0.0;
  energy_.fracture_dissipation = 0.0;
  energy_.flow_dissipation = 0.0;
  energy_.flow_splitting = 0.0;
  evaluate_energy();
  energy_.initial_fluid_volume = energy_.fluid_volume;
  initial_total_ = energy_.total();
}

void ExplicitDynamics::restore(const Carried& carried, const std::vector<double>& body_force) {
  time_ = carried.time;
  steps_ = carried.steps;
  energy_ = carried.energy;
  initial_total_ = carried.initial_total;
  finite_ = true;  // a checkpoint is written only after the step's non-finite guard passed
  body_force_ = body_force;
  const std::size_t n = boundary_volume_.size();
  if (carried.fluid_boundary_flows.size() == 2 * n) {
    boundary_volume_.assign(carried.fluid_boundary_flows.begin(), carried.fluid_boundary_flows.begin() + n);
    boundary_rate_.assign(carried.fluid_boundary_flows.begin() + n, carried.fluid_boundary_flows.end());
  }
}

ExplicitDynamics::StepConstants ExplicitDynamics::step_constants() const {
  const PointData& p = model_.points;
  StepConstants sc;
  sc.D = p.dimension;
  sc.R = p.rotation_components;
  sc.inv_rho = 1.0 / model_.constants.density;
  sc.inv_inertia = sc.R > 0 ? 1.0 / model_.constants.micro_inertia : 0.0;
  sc.rho = model_.constants.density;
  sc.inertia = model_.constants.micro_inertia;
  sc.half = 0.5 * dt_;
  sc.dt = dt_;
  sc.c_damp = damping_;
  sc.threaded = thread_point_loop(p.owned);
  return sc;
}

void ExplicitDynamics::advance_to_forces(bool with_energy) {
  // Remember the start-of-step body force of the tracked points for the work increments (the
  // force evaluation overwrites it).
  body_force_prev_.swap(body_force_);
  first_half_kick_and_drift(step_constants());
  // The clock is recomputed from the step count (no drift over many steps); with set_clock the
  // last step lands exactly on the end time.
  time_ = clock_steps_ > 0 ? static_cast<double>(steps_ + 1) / static_cast<double>(clock_steps_) * clock_end_
                           : static_cast<double>(steps_ + 1) * dt_;
  conditions_.prescribe(model_.points, time_);
  compute_loads_and_forces(with_energy, true);
}

void ExplicitDynamics::complete_step(bool with_energy) {
  const StepConstants sc = step_constants();
  const BreakageEnergy breakage = model_.effects.damage ? breakage_energy(sc) : BreakageEnergy{};
  if (second_half_kick(sc)) finite_ = false;
  // Distributed: every process stops at the step any one of them found a non-finite value.
  if (const ProcessGroup* group = model_.points.processes) finite_ = !group->any(!finite_);
  book_step_energy(breakage);
  ++steps_;
  // The flow at the skeleton's new configuration, before the energies of the step's end
  // (docs/theory.md section 12: the fractional step), and the forces again at the fluid content it
  // left: the next step's first half kick must see that pressure (a kick with the forces of before
  // the flow can pump energy into the fastest modes of the skeleton). The forces are linear in the
  // pressure: corrected by its change (solver/pressure_change_forces.hpp), not evaluated again.
  // The correction changes the accelerations in the scheme's kinetic energy 1/2 M (v.v - (dt/2)^2 a.a)
  // at fixed velocities: that change is the fractional step's splitting term (O(dt^2)), booked on its
  // own (docs/theory.md section 12).
  if (flow_due()) {
    const auto kinetic_before = kinetic_sums();
    pressure_before_flow_ = model_.points.pore_pressure;  // (the vector keeps its capacity)
    advance_flow();
    add_pressure_change_forces(model_.points, model_.bonds, model_.constants, pressure_before_flow_);
    const auto kinetic_after = kinetic_sums();
    energy_.flow_splitting += kinetic_before[0] + kinetic_before[1] - kinetic_after[0] - kinetic_after[1];
  }
  if (with_energy) evaluate_energy();
}

// First half kick and drift; the start-of-step state of the tracked points kept for the work
// increments (the force evaluation overwrites the force). Mass-proportional damping
// (numerics.damping, c): force density -c rho v (and -c I spin), explicit in the first half kick,
// implicit in the second (so any c is stable); its work (negative) is accumulated with the
// external work by the trapezoid rule.
void ExplicitDynamics::first_half_kick_and_drift(const StepConstants& sc) {
  PointData& p = model_.points;
  const int D = sc.D, R = sc.R;
  const double half = sc.half, dt = sc.dt, c_damp = sc.c_damp;
  const double inv_rho = sc.inv_rho, inv_inertia = sc.inv_inertia, rho = sc.rho, inertia = sc.inertia;
  for_each_point(sc.threaded, [&](std::size_t i, std::ptrdiff_t row) {
    const bool tracked = row >= 0;
    const auto t = static_cast<std::size_t>(row);
    if (tracked) {
      for (int c = 0; c < D; ++c) {
        force_prev_[t * D + c] = p.force[i * D + c];
        displacement_prev_[t * D + c] = p.displacement[i * D + c];
      }
      for (int c = 0; c < R; ++c) {
        moment_prev_[t * R + c] = p.moment[i * R + c];
        rotation_prev_[t * R + c] = p.rotation[i * R + c];
      }
    }
    // The damping's work over the first half of the step (only with damping, where every point is
    // tracked).
    const bool damping_work = tracked && c_damp > 0.0;
    const unsigned fixed = conditions_.prescribed(i);
    double work = 0.0;
    for (int c = 0; c < D; ++c) {
      const std::size_t k = i * D + c;
      const double damp = c_damp * p.velocity[k];  // per unit mass
      const double body = tracked ? body_force_prev_[t * D + c] : 0.0;
      p.velocity[k] += half * ((p.force[k] + body) * inv_rho - damp);
      p.displacement[k] += dt * p.velocity[k];
      if (damping_work && !((fixed >> c) & 1u)) work -= 0.5 * damp * dt * p.velocity[k];
    }
    double rot_work = 0.0;
    for (int c = 0; c < R; ++c) {
      const std::size_t k = i * R + c;
      const double damp = c_damp * p.spin[k];
      p.spin[k] += half * (p.moment[k] * inv_inertia - damp);
      p.rotation[k] += dt * p.spin[k];
      if (damping_work && !((fixed >> (BoundaryConditions::kRotationBit + c)) & 1u))
        rot_work -= 0.5 * damp * dt * p.spin[k];
    }
    if (tracked) work_increment_[t] = damping_work ? p.volume[i] * (rho * work + inertia * rot_work) : 0.0;
    return 0;
  });
}

// Damage: where breaks refreshed the forces (Model::advance_internal_forces), this step's kick
// and next step's use the forces without the broken bonds, as they must (a bond past its
// breaking would do work nothing accounts for), while the step that ends here ran with the
// bonds. The energy bookkeeping takes that from the forces before the refresh: the layers'
// reaction work over this step uses them at its end (the trapezoid rule of the bonds as they
// were), and on a free component the new force changes the scheme's kinetic energy
// 1/2 M v^(n-1/2) . v^(n+1/2) by dt/2 v^(n-1/2) . (f_new - f_old) V, which the breaks dissipate
// (O(dt): the work the broken bonds would have done over the rest of the step). With the stored
// energy they release, kinetic + stored + dissipated - external work then stays conserved.
ExplicitDynamics::BreakageEnergy ExplicitDynamics::breakage_energy(const StepConstants& sc) const {
  const PointData& p = model_.points;
  const int D = sc.D, R = sc.R;
  const double half = sc.half;
  ExactSum breakage_kick, breakage_work;
  const auto& refreshed = p.refreshed_points;
  for (std::size_t r = 0; r < refreshed.size(); ++r) {
    const std::size_t i = refreshed[r];
    const std::ptrdiff_t row = tracked_row(i);  // every point with a prescribed component is tracked
    const auto t = static_cast<std::size_t>(row);
    for (int c = 0; c < D; ++c) {
      const std::size_t k = i * D + c;
      const double change = p.force_before_refresh[r * D + c] - p.force[k];  // f_old - f_new
      if (conditions_.prescribed_displacement(i, c))
        breakage_work -= 0.5 * change * (p.displacement[k] - displacement_prev_[t * D + c]) * p.volume[i];
      else
        breakage_kick += half * p.velocity[k] * change * p.volume[i];
    }
    for (int c = 0; c < R; ++c) {
      const std::size_t k = i * R + c;
      const double change = p.moment_before_refresh[r * R + c] - p.moment[k];
      if (conditions_.prescribed_rotation(i, c))
        breakage_work -= 0.5 * change * (p.rotation[k] - rotation_prev_[t * R + c]) * p.volume[i];
      else
        breakage_kick += half * p.spin[k] * change * p.volume[i];
    }
  }
  // Distributed: the whole model's, when bonds broke anywhere (a collective call then only).
  if (p.processes && model_.last_breakage_anywhere) {
    const std::array<ExactSum, 2> local{breakage_kick, breakage_work};
    const std::vector<double> whole = p.processes->sum(local);
    return {whole[0], whole[1]};
  }
  return {breakage_kick.value(), breakage_work.value()};
}

// Second half kick, work increments (trapezoid: mean of the start and end forces times the
// increment), non-finite guard (true when a value of the new state is not finite). A point that is
// not tracked has no prescribed component, no body force and no damping: its work increment is
// zero and is not formed.
bool ExplicitDynamics::second_half_kick(const StepConstants& sc) {
  const double damp_factor = 1.0 / (1.0 + sc.half * sc.c_damp);
  return for_each_point(sc.threaded, [&](std::size_t i, std::ptrdiff_t row) {
           return row < 0 ? second_half_kick_untracked(sc, damp_factor, i)
                          : second_half_kick_tracked(sc, damp_factor, i, static_cast<std::size_t>(row));
         }) != 0;
}

int ExplicitDynamics::second_half_kick_untracked(const StepConstants& sc, double damp_factor, std::size_t i) {
  PointData& p = model_.points;
  const int D = sc.D, R = sc.R;
  const double half = sc.half, inv_rho = sc.inv_rho, inv_inertia = sc.inv_inertia;
  int bad_here = 0;
  for (int c = 0; c < D; ++c) {
    const std::size_t k = i * D + c;
    // "+ 0.0" is the body force of a tracked point (second_half_kick_tracked), which an untracked
    // point has not: it turns a force of -0.0 into +0.0 as that sum does, so that a point's
    // velocity has the same bits whether it is tracked or not (with gravity or damping every point
    // is).
    p.velocity[k] = (p.velocity[k] + half * (p.force[k] + 0.0) * inv_rho) * damp_factor;
    bad_here |= !std::isfinite(p.velocity[k]) || !std::isfinite(p.displacement[k]);
  }
  for (int c = 0; c < R; ++c) {
    const std::size_t k = i * R + c;
    p.spin[k] = (p.spin[k] + half * p.moment[k] * inv_inertia) * damp_factor;
    bad_here |= !std::isfinite(p.spin[k]) || !std::isfinite(p.rotation[k]);
  }
  return bad_here;
}

int ExplicitDynamics::second_half_kick_tracked(const StepConstants& sc, double damp_factor, std::size_t i,
                                               std::size_t t) {
  PointData& p = model_.points;
  const int D = sc.D, R = sc.R;
  const double half = sc.half, inv_rho = sc.inv_rho, inv_inertia = sc.inv_inertia, c_damp = sc.c_damp;
  const double rho = sc.rho, inertia = sc.inertia;
  const unsigned fixed = conditions_.prescribed(i);
  int bad_here = 0;
  double work = 0.0;
  for (int c = 0; c < D; ++c) {
    const std::size_t k = i * D + c;
    const double du = p.displacement[k] - displacement_prev_[t * D + c];
    if ((fixed >> c) & 1u) {
      // The reaction -f V does the work of the prescribed motion (layer inertia excluded).
      work -= 0.5 * (force_prev_[t * D + c] + p.force[k]) * du;
    } else {
      p.velocity[k] = (p.velocity[k] + half * (p.force[k] + body_force_[t * D + c]) * inv_rho) * damp_factor;
      work += 0.5 * (body_force_prev_[t * D + c] + body_force_[t * D + c]) * du;
      if (c_damp > 0.0) work -= 0.5 * c_damp * rho * p.velocity[k] * du;
    }
    bad_here |= !std::isfinite(p.velocity[k]) || !std::isfinite(p.displacement[k]);
  }
  for (int c = 0; c < R; ++c) {
    const std::size_t k = i * R + c;
    const double dw = p.rotation[k] - rotation_prev_[t * R + c];
    if ((fixed >> (BoundaryConditions::kRotationBit + c)) & 1u) {
      work -= 0.5 * (moment_prev_[t * R + c] + p.moment[k]) * dw;
    } else {
      p.spin[k] = (p.spin[k] + half * p.moment[k] * inv_inertia) * damp_factor;
      if (c_damp > 0.0) work -= 0.5 * c_damp * inertia * p.spin[k] * dw;
    }
    bad_here |= !std::isfinite(p.spin[k]) || !std::isfinite(p.rotation[k]);
  }
  work_increment_[t] += work * p.volume[i];
  return bad_here;
}

// The step's energy row items: the external work (in point order), the plastic dissipation and,
// with damage, the breaks' share.
void ExplicitDynamics::book_step_energy(const BreakageEnergy& breakage) {
  const PointData& p = model_.points;
  ExactSum work;
  for (const double w : work_increment_) work += w;
  energy_.external_work += p.processes ? p.processes->sum(work) : work.value();
  if (!p.plastic_dissipation.empty()) {
    const auto dissipated = exact_point_sums<1>(p, [&](std::size_t lo, std::size_t hi, ExactSums<1>& acc) {
      for (std::size_t i = lo; i < hi; ++i) acc[0] += p.plastic_dissipation[i];
    });
    energy_.plastic_dissipation += dissipated[0];
  }
  if (model_.effects.damage) {
    energy_.external_work += breakage.work;
    energy_.fracture_dissipation += model_.last_fracture_dissipation + breakage.kick;
  }
}

std::optional<NonFinitePoint> ExplicitDynamics::first_non_finite() const {
  const PointData& p = model_.points;
  const auto D = static_cast<std::size_t>(p.dimension), R = static_cast<std::size_t>(p.rotation_components);
  auto bad = [](const std::vector<double>& v, std::size_t i, std::size_t n) {
    for (std::size_t c = 0; c < n; ++c)
      if (!std::isfinite(v[i * n + c])) return true;
    return false;
  };
  std::optional<NonFinitePoint> out;
  // A pore pressure first: it is the cause when the retention inverse failed (its forces follow).
  if (const auto i = first_unrecovered_pressure()) {
    out = NonFinitePoint{*i, "pore_pressure", 0};
    for (std::size_t j = *i; j < p.owned; ++j) out->points += p.region[j] == 0 && !std::isfinite(p.pore_pressure[j]);
    return p.processes ? first_non_finite_of_all(out) : out;
  }
  for (std::size_t i = 0; i < p.owned; ++i) {
    const char* field = bad(p.displacement, i, D)        ? "displacement"
                        : bad(p.velocity, i, D)          ? "velocity"
                        : R > 0 && bad(p.rotation, i, R) ? "rotation"
                        : R > 0 && bad(p.spin, i, R)     ? "rotation_rate"
                                                         : nullptr;
    if (!field) continue;
    if (!out) out = NonFinitePoint{i, field, 0};
    ++out->points;
  }
  if (p.processes) return first_non_finite_of_all(out);
  return out;
}

// Distributed: the lowest global id holding a non-finite value on any process, its field (from
// the process that owns it) and the count over all processes, the same on every process.
std::optional<NonFinitePoint> ExplicitDynamics::first_non_finite_of_all(
    const std::optional<NonFinitePoint>& mine) const {
  static constexpr const char* kFields[] = {"pore_pressure", "displacement", "velocity", "rotation", "rotation_rate"};
  const PointData& p = model_.points;
  const ProcessGroup& group = *p.processes;
  constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();
  const std::int64_t id = mine ? p.global_id[mine->point] : kNone;
  const std::int64_t lowest = group.lowest(id);
  const std::int64_t points = group.total(mine ? static_cast<std::int64_t>(mine->points) : 0);
  std::int64_t code = kNone;
  if (mine && id == lowest)
    code = std::find_if(std::begin(kFields), std::end(kFields), [&](const char* f) { return mine->field == f; }) -
           std::begin(kFields);
  code = group.lowest(code);
  if (lowest == kNone) return std::nullopt;
  return NonFinitePoint{static_cast<std::size_t>(lowest), kFields[code], static_cast<std::size_t>(points)};
}

double ExplicitDynamics::balance_error() const {
  const double unexplained = energy_.accounted() - initial_total_ - energy_.external_work;
  // Every magnitude the sum is made of: a negative dissipation (energy booked as put in by a
  // process) or a negative work must not leave a scale of round-off behind.
  const double scale = std::max({std::abs(energy_.external_work), std::abs(energy_.accounted()), energy_.total(),
                                 initial_total_, energy_.kinetic_terms, std::abs(energy_.plastic_dissipation),
                                 std::abs(energy_.fracture_dissipation), std::abs(energy_.flow_dissipation), 1e-300});
  return unexplained / scale;
}

}  // namespace mppm::solver
