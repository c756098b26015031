// Velocity-Verlet stepping with prescribed layers and energy bookkeeping. Every loop writes only
// per-point data; sums over points are serial and in index order, so any thread count gives the
// same bits.
#include "solver/parallel_policy.hpp"
#include "solver/explicit_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mppm::solver {

ExplicitDynamics::ExplicitDynamics(Model& model, const BoundaryConditions& conditions, double time_step,
                                   std::array<double, 3> gravity)
    : model_(model), conditions_(conditions), dt_(time_step), gravity_(gravity),
      use_gravity_(model.effects.gravity) {
  const PointData& p = model_.points;
  body_force_.assign(p.total() * p.dimension, 0.0);
  body_force_prev_ = body_force_;
  force_prev_.assign(p.force.size(), 0.0);
  moment_prev_.assign(p.moment.size(), 0.0);
  work_increment_.assign(p.owned, 0.0);
}

void ExplicitDynamics::compute_loads_and_forces(bool with_energy, bool advance) {
  PointData& p = model_.points;
  const int D = p.dimension;
  if (advance) {
    model_.advance_internal_forces(dt_, with_energy);
  } else {
    model_.compute_internal_forces(with_energy);
  }
  std::fill(body_force_.begin(), body_force_.end(), 0.0);
  if (use_gravity_) {
    const double rho = model_.constants.density;
    for (std::size_t i = 0; i < p.owned; ++i)
      for (int c = 0; c < D; ++c) body_force_[i * D + c] = rho * gravity_[c];
  }
  conditions_.add_surface_loads(p, time_, body_force_);
}

void ExplicitDynamics::evaluate_energy() {
  const PointData& p = model_.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  const auto& fixed_u = conditions_.prescribed_displacement();
  const auto& fixed_w = conditions_.prescribed_rotation();
  const double rho = model_.constants.density;
  const double inertia = model_.constants.micro_inertia;
  // Kinetic energy of the central-difference scheme, 1/2 M v^{n-1/2} . v^{n+1/2}
  // = 1/2 M (v^n . v^n - (dt/2)^2 a^n . a^n): with it, kinetic + stored energy changes exactly by
  // the trapezoid-rule work of the loads for a linear elastic model (the plain 1/2 M v^n . v^n
  // differs from it by O((omega dt)^2) in the highest modes).
  const double h2 = 0.25 * dt_ * dt_;
  double kinetic = 0.0, rotational = 0.0, terms = 0.0;
  for (std::size_t i = 0; i < p.owned; ++i) {
    double v2 = 0.0, t2 = 0.0;
    for (int c = 0; c < D; ++c) {
      const std::size_t k = i * D + c;
      if (fixed_u[k]) continue;
      const double a = (p.force[k] + body_force_[k]) / rho;
      v2 += p.velocity[k] * p.velocity[k] - h2 * a * a;
      t2 += p.velocity[k] * p.velocity[k] + h2 * a * a;
    }
    kinetic += 0.5 * rho * p.volume[i] * v2;
    terms += 0.5 * rho * p.volume[i] * t2;
    if (R > 0) {
      double s2 = 0.0, r2 = 0.0;
      for (int c = 0; c < R; ++c) {
        const std::size_t k = i * R + c;
        if (fixed_w[k]) continue;
        const double a = p.moment[k] / inertia;
        s2 += p.spin[k] * p.spin[k] - h2 * a * a;
        r2 += p.spin[k] * p.spin[k] + h2 * a * a;
      }
      rotational += 0.5 * inertia * p.volume[i] * s2;
      terms += 0.5 * inertia * p.volume[i] * r2;
    }
  }
  energy_.kinetic_terms = terms;
  const InternalEnergy e = internal_energy(model_);
  energy_.kinetic = kinetic;
  energy_.rotational_kinetic = rotational;
  energy_.elastic = e.elastic();
  energy_.stabilization = e.stabilization;
}

void ExplicitDynamics::initialize() {
  time_ = 0.0;
  steps_ = 0;
  conditions_.prescribe(model_.points, time_);
  compute_loads_and_forces(true, false);
  energy_.external_work = 0.0;
  energy_.plastic_dissipation = 0.0;
  energy_.fracture_dissipation = 0.0;
  evaluate_energy();
  initial_total_ = energy_.total();
}

void ExplicitDynamics::restore(const Carried& carried, const std::vector<double>& body_force) {
  time_ = carried.time;
  steps_ = carried.steps;
  energy_ = carried.energy;
  initial_total_ = carried.initial_total;
  finite_ = true;  // a checkpoint is written only after the step's non-finite guard passed
  body_force_ = body_force;
}

void ExplicitDynamics::step(bool with_energy) {
  PointData& p = model_.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  const auto n = static_cast<std::int64_t>(p.owned);
  const double inv_rho = 1.0 / model_.constants.density;
  const double inv_inertia = R > 0 ? 1.0 / model_.constants.micro_inertia : 0.0;
  const double rho = model_.constants.density;
  const double inertia = model_.constants.micro_inertia;
  const double half = 0.5 * dt_;
  const double dt = dt_;
  const bool threaded = thread_point_loop(p.owned);

  // First half kick and drift; remember the start-of-step state for the work increments.
  force_prev_.swap(p.force);
  moment_prev_.swap(p.moment);
  body_force_prev_.swap(body_force_);
  displacement_prev_ = p.displacement;
  if (R > 0) rotation_prev_ = p.rotation;
  // Mass-proportional damping (numerics.damping, c): force density -c rho v (and -c I spin),
  // explicit in the first half kick, implicit in the second (so any c is stable); its work
  // (negative) is accumulated with the external work by the trapezoid rule.
  const double c_damp = damping_;
  const auto& fixed_u = conditions_.prescribed_displacement();
  const auto& fixed_w = conditions_.prescribed_rotation();
#pragma omp parallel for schedule(static) if (threaded)
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    double work = 0.0;
    for (int c = 0; c < D; ++c) {
      const std::size_t k = i * D + c;
      const double damp = c_damp * p.velocity[k];  // per unit mass
      p.velocity[k] += half * ((force_prev_[k] + body_force_prev_[k]) * inv_rho - damp);
      p.displacement[k] += dt * p.velocity[k];
      if (!fixed_u[k]) work -= 0.5 * damp * dt * p.velocity[k];
    }
    double rot_work = 0.0;
    for (int c = 0; c < R; ++c) {
      const std::size_t k = i * R + c;
      const double damp = c_damp * p.spin[k];
      p.spin[k] += half * (moment_prev_[k] * inv_inertia - damp);
      p.rotation[k] += dt * p.spin[k];
      if (!fixed_w[k]) rot_work -= 0.5 * damp * dt * p.spin[k];
    }
    work_increment_[i] = c_damp > 0.0 ? p.volume[i] * (rho * work + inertia * rot_work) : 0.0;
  }
  // The clock is recomputed from the step count (no drift over many steps); with set_clock the
  // last step lands exactly on the end time.
  time_ = clock_steps_ > 0 ? static_cast<double>(steps_ + 1) / static_cast<double>(clock_steps_) * clock_end_
                           : static_cast<double>(steps_ + 1) * dt_;
  conditions_.prescribe(p, time_);
  compute_loads_and_forces(with_energy, true);
  if (injection_ && injection_->step == steps_ + 1) inject_nan();

  // Damage: where breaks refreshed the forces (Model::advance_internal_forces), this step's kick
  // and next step's use the forces without the broken bonds, as they must (a bond past its
  // breaking would do work nothing accounts for), while the step that ends here ran with the
  // bonds. The energy bookkeeping takes that from the forces before the refresh: the layers'
  // reaction work over this step uses them at its end (the trapezoid rule of the bonds as they
  // were), and on a free component the new force changes the scheme's kinetic energy
  // 1/2 M v^(n-1/2) . v^(n+1/2) by dt/2 v^(n-1/2) . (f_new - f_old) V, which the breaks dissipate
  // (O(dt): the work the broken bonds would have done over the rest of the step). With the stored
  // energy they release, kinetic + stored + dissipated - external work then stays conserved.
  double breakage_kick = 0.0, breakage_work = 0.0;
  if (model_.effects.damage) {
    const auto& refreshed = p.refreshed_points;
    for (std::size_t r = 0; r < refreshed.size(); ++r) {
      const std::size_t i = refreshed[r];
      for (int c = 0; c < D; ++c) {
        const std::size_t k = i * D + c;
        const double change = p.force_before_refresh[r * D + c] - p.force[k];  // f_old - f_new
        if (fixed_u[k]) breakage_work -= 0.5 * change * (p.displacement[k] - displacement_prev_[k]) * p.volume[i];
        else breakage_kick += half * p.velocity[k] * change * p.volume[i];
      }
      for (int c = 0; c < R; ++c) {
        const std::size_t k = i * R + c;
        const double change = p.moment_before_refresh[r * R + c] - p.moment[k];
        if (fixed_w[k]) breakage_work -= 0.5 * change * (p.rotation[k] - rotation_prev_[k]) * p.volume[i];
        else breakage_kick += half * p.spin[k] * change * p.volume[i];
      }
    }
  }

  // Second half kick, work increments (trapezoid: mean of the start and end forces times the
  // increment), non-finite guard.
  const double damp_factor = 1.0 / (1.0 + half * c_damp);
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad) if (threaded)
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    double work = 0.0;
    for (int c = 0; c < D; ++c) {
      const std::size_t k = i * D + c;
      const double du = p.displacement[k] - displacement_prev_[k];
      if (fixed_u[k]) {
        // The reaction -f V does the work of the prescribed motion (layer inertia excluded).
        work -= 0.5 * (force_prev_[k] + p.force[k]) * du;
      } else {
        p.velocity[k] = (p.velocity[k] + half * (p.force[k] + body_force_[k]) * inv_rho) * damp_factor;
        work += 0.5 * (body_force_prev_[k] + body_force_[k]) * du;
        if (c_damp > 0.0) work -= 0.5 * c_damp * rho * p.velocity[k] * du;
      }
      bad |= !std::isfinite(p.velocity[k]) || !std::isfinite(p.displacement[k]);
    }
    for (int c = 0; c < R; ++c) {
      const std::size_t k = i * R + c;
      const double dw = p.rotation[k] - rotation_prev_[k];
      if (fixed_w[k]) {
        work -= 0.5 * (moment_prev_[k] + p.moment[k]) * dw;
      } else {
        p.spin[k] = (p.spin[k] + half * p.moment[k] * inv_inertia) * damp_factor;
        if (c_damp > 0.0) work -= 0.5 * c_damp * inertia * p.spin[k] * dw;
      }
      bad |= !std::isfinite(p.spin[k]) || !std::isfinite(p.rotation[k]);
    }
    work_increment_[i] += work * p.volume[i];
  }
  if (bad) finite_ = false;
  double work = 0.0;
  for (std::size_t i = 0; i < p.owned; ++i) work += work_increment_[i];
  energy_.external_work += work;
  if (!p.plastic_dissipation.empty()) {
    double dissipated = 0.0;
    for (std::size_t i = 0; i < p.owned; ++i) dissipated += p.plastic_dissipation[i];
    energy_.plastic_dissipation += dissipated;
  }
  if (model_.effects.damage) {
    energy_.external_work += breakage_work;
    energy_.fracture_dissipation += model_.last_fracture_dissipation + breakage_kick;
  }
  ++steps_;
  if (with_energy) evaluate_energy();
}

const char* NanInjection::name(Field f) {
  switch (f) {
    case Field::displacement: return "displacement";
    case Field::velocity: return "velocity";
    case Field::rotation: return "rotation";
    case Field::rotation_rate: return "rotation_rate";
    case Field::force: return "force";
  }
  return "?";
}

void ExplicitDynamics::inject_nan() {
  PointData& p = model_.points;
  const NanInjection& k = *injection_;
  const std::size_t D = static_cast<std::size_t>(p.dimension), R = static_cast<std::size_t>(p.rotation_components);
  const auto c = static_cast<std::size_t>(k.component);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  switch (k.field) {
    case NanInjection::Field::displacement: p.displacement[k.point * D + c] = nan; break;
    case NanInjection::Field::velocity: p.velocity[k.point * D + c] = nan; break;
    case NanInjection::Field::force: p.force[k.point * D + c] = nan; break;
    case NanInjection::Field::rotation: p.rotation[k.point * R + c] = nan; break;
    case NanInjection::Field::rotation_rate: p.spin[k.point * R + c] = nan; break;
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
  for (std::size_t i = 0; i < p.owned; ++i) {
    const char* field = bad(p.displacement, i, D) ? "displacement"
                        : bad(p.velocity, i, D)   ? "velocity"
                        : R > 0 && bad(p.rotation, i, R) ? "rotation"
                        : R > 0 && bad(p.spin, i, R)     ? "rotation_rate"
                                                         : nullptr;
    if (!field) continue;
    if (!out) out = NonFinitePoint{i, field, 0};
    ++out->points;
  }
  return out;
}

double ExplicitDynamics::balance_error() const {
  const double unexplained = energy_.accounted() - initial_total_ - energy_.external_work;
  // Every magnitude the sum is made of: a negative dissipation (energy booked as put in by a
  // process) or a negative work must not leave a scale of round-off behind.
  const double scale = std::max({std::abs(energy_.external_work), std::abs(energy_.accounted()), energy_.total(),
                                 initial_total_, energy_.kinetic_terms, std::abs(energy_.plastic_dissipation),
                                 std::abs(energy_.fracture_dissipation), 1e-300});
  return unexplained / scale;
}

}  // namespace mppm::solver
