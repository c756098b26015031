// Explicit central-difference integration of u and w (docs/theory.md section 9, velocity-Verlet form:
// half kick, drift, prescribe, forces, half kick) with the energy bookkeeping of the run:
// kinetic (translational, rotational), stored elastic, stabilization, and the external work of
// surface loads, gravity and the prescribed layers (trapezoid rule on force . increment), and
// the viscoplastic dissipation (the return map runs in the one force evaluation of each step),
// and the fracture dissipation (bonds break in that evaluation too).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/boundary_conditions.hpp"
#include "solver/flow_super_step.hpp"
#include "solver/model.hpp"
#include "solver/pore_fluid.hpp"

namespace mppm::solver {

struct EnergyState {
  // Kinetic energies of the scheme, 1/2 M v^{n-1/2}.v^{n+1/2}, over free components.
  double kinetic = 0.0;             // rho V
  double rotational_kinetic = 0.0;  // I V
  double elastic = 0.0;             // 1/2 eps:sigma + 1/2 kap:m
  double stabilization = 0.0;
  double external_work = 0.0;         // loads, prescribed layers, and damping (negative)
  double plastic_dissipation = 0.0;   // accumulated every step (trapezoid rule, like the work)
  double fracture_dissipation = 0.0;  // stored energy released by the bonds broken so far
  // Pore fluid (docs/theory.md section 12; zero without it): the fluid's stored energy V p^2 / (2 M),
  // the stored energy the flow updates removed so far (the energy the fluid carried out through the
  // boundaries included), the fluid volume sum V zeta at the start and at the last row, and the
  // volume that left through the boundaries so far (outflow of the drained ones less the inflow of
  // the fed ones).
  double fluid_stored = 0.0;
  double flow_dissipation = 0.0;
  // The scheme's kinetic energy the flow updates removed so far by changing the accelerations at
  // fixed velocities (the pressure change's force correction): the fractional step's splitting
  // term, O(dt^2) (docs/theory.md section 12).
  double flow_splitting = 0.0;
  double initial_fluid_volume = 0.0;
  double fluid_volume = 0.0;
  double fluid_net_outflow = 0.0;
  // The size of the terms whose difference is the scheme's kinetic energy, 1/2 M (v^n . v^n +
  // (dt/2)^2 a^n . a^n): the scale of its round-off. Where every energy is still round-off (the
  // step in which a load starts: v^n = dt/2 a^n, so the kinetic energy is a difference of two equal
  // numbers), this keeps the balance error and the energy check relative to a real energy.
  double kinetic_terms = 0.0;
  // Kinetic + stored energy.
  double total() const { return kinetic + rotational_kinetic + elastic + stabilization + fluid_stored; }
  // What the balance accounts for: total plus the energy already dissipated.
  double accounted() const {
    return total() + plastic_dissipation + fracture_dissipation + flow_dissipation + flow_splitting;
  }
  // (fluid volume now - at the start + net outflow) / the start's (the pore volume the fluid
  // filled): the fluid mass balance (pore fluid only), round-off.
  double fluid_mass_balance() const {
    return initial_fluid_volume > 0.0 ? (fluid_volume - initial_fluid_volume + fluid_net_outflow) / initial_fluid_volume
                                      : 0.0;
  }
};

// Where the per-step guard found non-finite values (ExplicitDynamics::first_non_finite).
struct NonFinitePoint {
  std::size_t point = 0;   // the lowest index holding a non-finite value (global id when distributed)
  std::string field;       // "displacement", "velocity", "rotation" or "rotation_rate"
  std::size_t points = 0;  // how many points hold one
};

class ExplicitDynamics {
 public:
  // `gravity` is used when the model's effects include gravity. The model and the boundary
  // conditions must outlive this object.
  ExplicitDynamics(Model& model, const BoundaryConditions& conditions, double time_step,
                   std::array<double, 3> gravity = {0.0, 0.0, 0.0});

  // Time of step k = end * k / steps (the time step must be end / steps): the run then ends
  // exactly at `end`, not at a rounded multiple of the step.
  void set_clock(double end, std::int64_t steps) {
    clock_end_ = end;
    clock_steps_ = steps;
  }

  // Pore fluid: when the flow updates run against the mechanical step (Model::fluid; default: one
  // update of dt per step). Call it before initialize().
  void set_flow_schedule(const FlowSchedule& schedule) { flow_ = schedule; }
  const FlowSchedule& flow_schedule() const { return flow_; }

  // Mass-proportional damping coefficient c [1/s] (numerics.damping; 0 = none). Call it before
  // initialize(): damping needs the start-of-step state of every point.
  void set_damping(double c);

  // Prescribes the state at t = 0 and computes the forces and energies there.
  void initialize();
  // One step; energies are evaluated at the new time when `with_energy`.
  void step(bool with_energy) {
    step(with_energy, [](PointData&, std::int64_t) {});
  }
  // The same, calling after_forces(points, step) between the step's force evaluation and its second
  // half kick, with `step` counted from 1: the run driver applies its test hooks there
  // (solver/test_hooks.hpp).
  template <class AfterForces>
  void step(bool with_energy, AfterForces&& after_forces) {
    advance_to_forces(with_energy);
    after_forces(model_.points, steps_ + 1);
    complete_step(with_energy);
  }

  // Pore fluid: what went through fluid boundary condition k (scene order; zero for the others):
  // the volume so far [m^3] (out of a drained boundary, into a fed one) and the rate of the last
  // flow update [m^3/s] (0 before the first).
  struct FluidBoundaryFlow {
    double rate = 0.0, volume = 0.0;
  };
  FluidBoundaryFlow fluid_boundary_flow(std::size_t k) const;
  // True when the conditions hold a drained or fed boundary (then Carried::fluid_boundary_flows is
  // filled).
  bool has_fluid_boundaries() const { return !conditions_.drained().empty() || !conditions_.fed().empty(); }

  double time() const { return time_; }
  std::int64_t steps() const { return steps_; }
  double time_step() const { return dt_; }
  // Energies at the last evaluation with energy; external work is accumulated every step.
  const EnergyState& energy() const { return energy_; }
  double initial_total_energy() const { return initial_total_; }
  // (total + dissipated - initial - external work) / max(|external work|, |total + dissipated|,
  // total, initial, kinetic_terms, |each dissipation|, tiny)
  double balance_error() const;
  // False once a non-finite displacement, velocity or rotation has appeared (on any process of a
  // distributed run: all agree at the same step).
  bool finite() const { return finite_; }
  // The points holding non-finite values now (a full scan: call it when finite() turned false).
  // The lowest body point whose pore pressure is not finite (the unsaturated retention inverse found no
  // pressure for its fluid content), if any.
  std::optional<std::size_t> first_unrecovered_pressure() const;
  // In a distributed run every process gets the same answer, with the point's global id.
  std::optional<NonFinitePoint> first_non_finite() const;

  Model& model() { return model_; }
  const Model& model() const { return model_; }

  // What the integrator carries from one step to the next besides the model's arrays (the
  // forces of the last evaluation are the model's): a checkpoint stores it, a restart puts it
  // back (solver/checkpoint.hpp). The start-of-step copies (force_prev_, displacement_prev_, ...)
  // are rebuilt by every step and are not part of it.
  struct Carried {
    double time = 0.0;
    std::int64_t steps = 0;
    EnergyState energy;
    double initial_total = 0.0;
    // Pore fluid with fluid boundary conditions: per scene condition the volume through it so far,
    // then per condition the rate of the last flow update (fluid_boundary_flow); else empty.
    std::vector<double> fluid_boundary_flows;
  };
  Carried carried() const;
  // The external force density of the last evaluation (the first half kick of the next step uses
  // it), D per tracked point (see tracked_ below): every other point has none.
  const std::vector<double>& body_force() const { return body_force_; }
  // The points of body_force's rows, in row order: all owned points when every point is tracked
  // (gravity, damping), else the points with a prescribed component or a surface load.
  bool tracks_all_points() const { return track_all_; }
  const std::vector<std::int32_t>& tracked_points() const { return tracked_; }
  // After initialize(): continues from a checkpointed state (body_force must have the run's size).
  void restore(const Carried& carried, const std::vector<double>& body_force);

 private:
  // The constants of one step's kicks (no allocation: a step computes them on the stack).
  struct StepConstants {
    int D = 0, R = 0;
    double inv_rho = 0.0, inv_inertia = 0.0, rho = 0.0, inertia = 0.0;
    double half = 0.0, dt = 0.0, c_damp = 0.0;
    bool threaded = false;
  };
  StepConstants step_constants() const;
  // The damage terms of a step's energy bookkeeping (breakage_energy).
  struct BreakageEnergy {
    double kick = 0.0, work = 0.0;
  };
  // The first half of a step: first half kick, drift, prescribed motion, force evaluation.
  void advance_to_forces(bool with_energy);
  // The rest: the breaks' energy bookkeeping, second half kick, work, non-finite guard, energies.
  void complete_step(bool with_energy);
  void first_half_kick_and_drift(const StepConstants& sc);
  BreakageEnergy breakage_energy(const StepConstants& sc) const;
  bool second_half_kick(const StepConstants& sc);
  int second_half_kick_untracked(const StepConstants& sc, double damp_factor, std::size_t i);
  int second_half_kick_tracked(const StepConstants& sc, double damp_factor, std::size_t i, std::size_t t);
  void book_step_energy(const BreakageEnergy& breakage);
  // Pore fluid: whether flow updates are due after step steps_ (flow_), and those updates, their
  // dissipation booked, the drained layers' pressure prescribed first and the volumes through the
  // fluid boundaries booked.
  bool flow_due() const;
  void advance_flow();
  // One flow update of length h with the fluid boundaries at time_; the volumes through them added
  // to boundary_volume_ (book_boundary_volumes: the drains' outflow and the sources' inflow over h).
  void flow_update_with_boundaries(double h);
  void book_boundary_volumes(double h);
  // advance: the force evaluation of a step (advances the plastic state by dt).
  void compute_loads_and_forces(bool with_energy, bool advance);
  void evaluate_energy();
  std::optional<NonFinitePoint> first_non_finite_of_all(const std::optional<NonFinitePoint>& mine) const;
  // The scheme's translational and rotational kinetic energies and the size of their terms
  // (evaluate_energy), summed in chunks fixed by the point count.
  std::array<double, 3> kinetic_sums() const;
  // Chooses the tracked points and sizes the per-tracked-point arrays.
  void lay_out_tracked_points();
  std::size_t tracked_count() const;
  // The row of point i among the tracked points, -1 if it is not tracked.
  std::ptrdiff_t tracked_row(std::size_t i) const;
  // Calls visit(i, row) for every owned point i, row = tracked_row(i), in contiguous ranges of
  // points per thread (threaded: in parallel); returns the OR of what visit returns.
  template <class Visit>
  int for_each_point(bool threaded, Visit&& visit) const;
  // The same for the points lo .. hi-1, on the calling thread, in index order.
  template <class Visit>
  int for_each_point_in(std::size_t lo, std::size_t hi, Visit&& visit) const;

  Model& model_;
  const BoundaryConditions& conditions_;
  double dt_;
  double damping_ = 0.0;
  FlowSchedule flow_;
  double clock_end_ = 0.0;
  std::int64_t clock_steps_ = 0;
  std::array<double, 3> gravity_;
  bool use_gravity_;
  double time_ = 0.0;
  std::int64_t steps_ = 0;
  bool finite_ = true;
  // The points whose start-of-step state a step still needs after its force evaluation: those with
  // a prescribed component (the reaction's work takes the force and the displacement at both ends
  // of the step) and those with a body force (its work takes the body force and the displacement at
  // both ends): with gravity or damping every point, otherwise the fictitious layers and the loaded
  // surfaces. Every other point has a zero external work increment (exactly: +0), so leaving it
  // out of the work sum gives the same bits, and the start-of-step copies of the state, 5 to 8
  // values per point, are kept for the few points that need them.
  bool track_all_ = true;
  std::vector<std::int32_t> tracked_;    // sorted point indices (empty when track_all_)
  std::vector<std::int32_t> load_rows_;  // the tracked row of each loaded point (surfaces in order)
  // Per tracked point:
  std::vector<double> body_force_;  // external force density b (D)
  std::vector<double> body_force_prev_;
  std::vector<double> force_prev_, moment_prev_;           // D, R
  std::vector<double> displacement_prev_, rotation_prev_;  // D, R
  std::vector<double> work_increment_;                     // summed exactly (book_step_energy)
  EnergyState energy_;
  double initial_total_ = 0.0;
  // Pore fluid boundaries: per scene condition, the volume through it so far and the last rate;
  // the boundaries of the flow updates (its source list reused from update to update).
  std::vector<double> boundary_volume_, boundary_rate_, boundary_volume_start_;
  FlowBoundaries flow_boundaries_;
  std::vector<double> pressure_before_flow_;  // the pressures a batch of flow updates starts from
  FlowSuperStepWork super_step_work_;         // the RKL2 super step's arrays (FlowSchedule::stages > 1)
};

}  // namespace mppm::solver
