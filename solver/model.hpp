// The discrete model as built for a run: points, bonds (pre-crack cuts applied), constants,
// shape tensors, and the chosen kernel instantiation. Tests build it from an in-memory cloud.
#pragma once
#include <cstddef>
#include <memory>
#include <optional>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/bond_breakage.hpp"
#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/crack_area.hpp"
#include "solver/crack_arrivals.hpp"
#include "solver/internal_forces.hpp"
#include "solver/local_points.hpp"
#include "solver/phase_timer.hpp"
#include "solver/plasticity/viscoplastic_model.hpp"
#include "solver/point_data.hpp"
#include "solver/pore_fluid.hpp"
#include "solver/step_advance.hpp"

namespace mppm::solver {

struct ModelOptions {
  CosseratConstants constants;
  EffectSet effects;
  double horizon = 0.0;
  double spacing = 0.0;
  std::array<double, 3> period{0.0, 0.0, 0.0};  // verification lattices only
  double no_fail_depth = 0.0;  // damage: bonds of points this close to a boundary condition never break
  // Regions of the effects (material.damage.region, material.viscoplasticity.region): a box,
  // [[x0, y0, z0], [x1, y1, z1]] in metres; none: the whole body.
  std::optional<std::array<std::array<double, 3>, 2>> damage_region, plastic_region;
  // Required with the viscoplasticity effect (make_viscoplastic_model of the scene's material).
  std::shared_ptr<const plasticity::ViscoplasticModel> viscoplastic_model;
  // Required with the pore_fluid effect (fluid_constants of the scene), and the pressure at t = 0.
  std::optional<FluidConstants> fluid;
  double initial_pressure = 0.0;
  std::optional<double> free_surface;  // hydrostatic start (PoreFluidParameters::free_surface)
  // Pore fluid: the drained layers and the fluid's own boundary ids (BoundaryConditions::fluid_layout);
  // empty: every face impermeable.
  FluidBoundaryLayout fluid_boundaries;
};

struct Model {
  CosseratConstants constants;
  EffectSet effects;
  double horizon = 0.0;  // delta [m]
  PointData points;
  BondFamilies bonds;
  InternalForceFunctions kernel;
  std::shared_ptr<const plasticity::ViscoplasticModel> viscoplastic_model;  // with the effect
  std::optional<FluidConstants> fluid;                                      // with pore_fluid
  // Pore fluid: the bonds of body points to drained layers (solver/fluid_boundaries.hpp), and the
  // points of the inert drained layers (out of the mechanics: no bonds, detached, held still by the
  // boundary conditions; not counted in detached_points).
  DrainBonds drains;
  std::size_t inert_points = 0;
  // Bond entries the pre-crack cuts removed (each pair at both of its points; a distributed run's
  // process counts those of its owned points, so that the processes' counts add up).
  std::size_t precrack_cut_entries = 0;
  // Damage in 3-D: the bonds the pre-crack cuts removed, for the crack area (crack_area.hpp).
  PrecrackCutBonds precrack_cuts;
  std::size_t detached_points = 0;
  std::size_t broken_bonds = 0;              // pairs broken by damage so far (pre-crack cuts not included)
  double last_fracture_dissipation = 0.0;    // [J] released by the breaks of the last advance
  bool last_breakage_anywhere = false;       // bonds broke in the last advance (on any process)
  std::size_t unstable_detached_points = 0;  // of detached_points: detached for the time step's sake
  std::size_t energy_detached_points = 0;    // of detached_points: losing bonds raised their energy
  BreakageWorkspace breakage_workspace;
  // Damage: when each point reached the crack path (crack_path.csv); started by
  // ExplicitDynamics::initialize, advanced by advance_internal_forces.
  CrackArrivals crack_arrivals;
  // Damage: a body point whose stiffness block exceeds this is detached (point_stability.hpp);
  // 0 = no such check. Set by set_breakage_time_step.
  double block_eigenvalue_limit = 0.0;

  int dimension() const { return points.dimension; }
  bool micropolar() const { return effects.micropolar; }

  // Force and moment per unit volume of every owned point; energies too if asked. The plastic
  // state (if any) is frozen: stress = elastic law of (strain - plastic strain).
  void compute_internal_forces(bool with_energy = false) {
    (with_energy ? kernel.forces_and_energy : kernel.forces)(points, bonds, constants, nullptr);
  }
  // The kernel the start-up estimates apply as the linear operator K v (critical_time_step.cpp):
  // the one without the history effects while the state holds no history (no broken bond, no
  // plastic strain; on every process), the same operator at fewer instructions per bond; else the
  // model's own (kernel.forces).
  InternalForceFunction linear_operator_kernel() const;
  // A broken bond, or a plastic strain or wryness that is not zero, among this process's owned points.
  bool holds_history() const;
  // The same at the end of a time step of length dt, with the history advanced from the start of
  // the step: the viscoplastic state by the return map (points.plastic_dissipation set), and with
  // damage the bond work, the bonds that reach the critical work broken (points.bonds_broken and
  // last_fracture_dissipation set) and the shape tensors of their points refreshed for the next step;
  // the points the breaks put on the crack path arrive at `end_time`, the step's end (crack_arrivals).
  // Call it once per step, after the previous evaluation (the step's start); without these
  // effects it is compute_internal_forces.
  void advance_internal_forces(double dt, double end_time, bool with_energy);
  // Damage: the largest time step a damage run may use, given the start-up critical step: lopsided
  // families left by breaks raise the highest frequency (point_stability.hpp), so it is
  // min(critical, 2 / sqrt(damaged_frequency_ratio x largest point block)); without damage, critical.
  double damage_critical_step(double critical_step) const;
  // The same with this process's largest body point block already known (stiffest_points).
  double damage_critical_step(double critical_step, double largest_point_block) const;
  // Damage: points whose bonds broke stay stable at the time step dt (point_stability.hpp): a body
  // point whose block exceeds (2 / dt)^2 / damaged_frequency_ratio is detached. Call it once the
  // step is chosen; no-op without damage.
  void set_breakage_time_step(double dt);
};

// The options a scene asks for: constants, effects, horizon, spacing, the no-fail depth and the
// effects' regions, and the viscoplastic model by name from the registry (an InputError naming the
// key for bad parameters). Periodic lattices set `period` themselves.
ModelOptions model_options(const Scene& scene);

// Builds families (the inert drained layers' bonds taken out), cuts bonds across the cloud's
// pre-cracks, computes shape tensors, and with the pore fluid the drain bonds. With `phases`,
// each of these is marked there as a start-up phase ("point data", "bond families", "pre-crack
// cuts", "damage set-up", "shape tensors").
Model build_model(const PointCloud& cloud, const ModelOptions& options, PhaseTimer* phases = nullptr);
// The same, taking over or releasing the cloud's per-point arrays (make_point_data): what is left
// of it after the call is its pre-cracks and boundaries.
Model build_model(PointCloud&& cloud, const ModelOptions& options, PhaseTimer* phases = nullptr);

// A distributed run's model on one process (docs/theory.md section 13): the local points of the
// whole cloud (local_points.hpp), the ghosts' values from `ghosts` (their shape-tensor terms fetched
// here), the global sums over `processes`; both must outlive the model. Damage, viscoplasticity
// and the pore fluid do not run across processes yet: std::invalid_argument names them.
Model build_local_model(const PointCloud& cloud, const LocalPoints& local, const GhostExchange& ghosts,
                        const ProcessGroup& processes, const ModelOptions& options, PhaseTimer* phases = nullptr);

// Totals of the per-point energies of the last evaluation with energies [J], summed exactly
// (exact_point_sums.hpp: the same result for any thread count).
StoredEnergy internal_energy(const Model& model);

}  // namespace mppm::solver
