// Per-point storage of the solver: one array per field (structure of arrays), owned points
// first and ghost points (copies of other processes' points) after them, so that a
// distributed decomposition can be added without touching the kernels: kernels loop over owned
// points and read neighbours by local index, owned or ghost; with ghosts, their kinematic state
// and pass-1 tensors come from a halo exchange between passes. A single process owns every
// point and the local index is the index in the points file; a decomposition adds the points'
// global ids with the ghosts (8 B per point that a single process does not need).
// Small tensors of one point are contiguous (row-major) inside their field's array: the force
// pass gathers them per neighbour, and one cache line then holds a neighbour's whole tensor.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/ghost_exchange.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

struct PointData {
  int dimension = 2;
  int rotation_components = 0;  // 1 (2-D) or 3 (3-D) with micropolar, 0 without
  std::size_t owned = 0;        // points this process integrates
  std::size_t ghost = 0;        // read-only copies after the owned ones
  std::size_t total() const { return owned + ghost; }
  // Distributed runs: each local point's index in the points file (its global id; owned points and
  // ghosts each in ascending order), and where the ghosts' values come from. A single process
  // leaves both empty: there the local index is the global id.
  std::vector<std::int64_t> global_id;
  // Local point i's index in the points file, on one process or many.
  std::int64_t global_index(std::size_t i) const {
    return global_id.empty() ? static_cast<std::int64_t>(i) : global_id[i];
  }
  const GhostExchange* ghost_source = nullptr;
  // The processes whose points make up the model, for the global sums (null: this one alone).
  const ProcessGroup* processes = nullptr;

  std::vector<double> position;  // reference, D per point
  std::vector<double> volume;
  std::vector<std::int32_t> region;
  std::vector<std::int32_t> boundary_id;

  // Kinematic state. Rotation arrays stay empty when micropolar is off.
  std::vector<double> displacement, velocity;  // D per point
  std::vector<double> rotation, spin;          // R per point
  // Internal force and moment per unit volume (owned points).
  std::vector<double> force;   // D per point
  std::vector<double> moment;  // R per point

  // Shape tensors (constant while bonds do not change).
  // K^-1 and G_s (C : K^-1) (zero for detached points), symmetric: D (D + 1) / 2 per point, the
  // upper triangle row by row (solver/symmetric_tensor.hpp).
  std::vector<double> shape_inverse;
  std::vector<double> stabilization_ck;
  std::vector<double> stabilization_rot;  // G_s B_w tr(K^-1) / d (micropolar)
  std::vector<std::uint8_t> detached;

  // Products of the strain pass, read by the force pass for i and its neighbours. eps and kap are
  // stored by rows, A and Q by columns (A_00 A_10 A_20 A_01 ...): pass 2's bond products use A and
  // Q column by column (bond_products.hpp).
  std::vector<double> strain;         // eps, D*D
  std::vector<double> force_tensor;   // A = sigma K^-1 - G_s (C:K^-1) eps, D*D
  std::vector<double> wryness;        // kap, R*D
  std::vector<double> moment_tensor;  // Q = m K^-1 - g kap, R*D

  // Viscoplastic state (allocated only when the effect is on): the state after the last step.
  // The plastic strain is the full 3 x 3 tensor (row-major) in 2-D too: plane-strain flow has
  // an out-of-plane part eps_vp,zz (dilatancy, deviatoric flow), hence sigma_zz and its energy.
  std::vector<double> plastic_strain;             // eps_vp, 9 per point
  std::vector<double> plastic_wryness;            // kap_vp, R*D (micropolar)
  std::vector<double> equivalent_plastic_strain;  // ebar
  std::vector<double> plastic_dissipation;        // [J] of the last step (trapezoid rule)
  std::vector<std::uint8_t> plastic_active;       // 1 inside material.viscoplasticity.region

  // Damage state (allocated only when the effect is on, docs/theory.md section 7).
  // The family volume sum_j V_j before the pre-crack cuts of the points that lost bonds to them
  // (sorted by point); any other point's is the sum over its whole list, broken bonds included
  // (family_volume_of in bond_breakage.hpp), so that the points away from a pre-crack, nearly
  // all of them, store none.
  std::vector<std::size_t> precut_points;
  std::vector<double> precut_family_volume;
  std::vector<std::uint8_t> no_fail;  // 1: the bonds of this point never break
  // The bonds that reached the critical work in the last advancing force evaluation, counted at
  // their lower-index end (pass 2 of the force kernel); update_after_breakage breaks them.
  std::vector<std::int32_t> bonds_broken;
  // The state of the previous force evaluation, for the trapezoid rule on the bond work (the
  // pair force of a bond is rebuilt from these per-point arrays instead of being stored per bond):
  // its displacement and rotation, and the sums A + A_prev and Q + Q_prev of this evaluation's
  // tensors and the previous one's (written by pass 1 of an advancing evaluation just before it
  // overwrites A and Q; the bond work needs only the sums, and one array each instead of the
  // previous tensors saves a load and an addition per tensor entry and bond).
  std::vector<double> previous_displacement, previous_rotation;
  std::vector<double> force_tensor_sum, moment_tensor_sum;
  // The points whose force the last breakage refresh changed (sorted), with their force and moment
  // before it: the integrator books the kick and the layers' reaction work with them
  // (ExplicitDynamics::step). Cleared at every advance.
  std::vector<std::size_t> refreshed_points;
  std::vector<double> force_before_refresh, moment_before_refresh;

  // Pore fluid (allocated only when the effect is on, docs/theory.md section 12), per point; zero on
  // the fictitious layers. The pressure p (compression positive) of the last force evaluation or
  // flow update, p = M (zeta - n0 - b tr eps); the change of the fluid content zeta (fluid volume
  // per reference volume) from the porosity n0, the state the flow advances (stored as the change:
  // zeta itself would resolve p only to M ulp(n0), 6e-8 Pa at M = 2 GPa); the rate d zeta / dt of
  // the last flow update.
  std::vector<double> pore_pressure, fluid_content_change, fluid_rate;
  // Unsaturated pore fluid only (a retention curve; allocated by start_fluid): the stored fluid
  // energy per point [J], the work the fluid received since the start (solver/unsaturated_coupling.hpp),
  // and the relative permeability k_r(p) of every point, layers included, refreshed by each flow-rate evaluation.
  std::vector<double> fluid_energy, relative_permeability;

  // The stabilization energy per point [J], V 1/2 sum_j V_j (z_u.T^s + z_w.M^s), filled when a force
  // evaluation is asked for energies (the bond loop that gives it is the force pass's). The elastic
  // energies are computed from the stored strain and wryness when they are summed
  // (kernel::elastic_energy_of_point), not stored.
  std::vector<double> stabilization_energy;
};

// The cloud's positions, D per point (the form the solver, the horizon search and the partition read).
std::vector<double> cloud_positions(const PointCloud& cloud);

// The local index of the point with index `point` in the points file when this process owns it:
// `point` itself on one process; found among the owned points' global ids (ascending) in a
// distributed run; none when another process owns it.
std::optional<std::size_t> owned_index(const PointData& p, std::size_t point);

// Whether the point at `x` (`dimension` coordinates) lies in `box` (corners [lo, hi], bounds included):
// the scene's material.damage.region and material.viscoplasticity.region.
bool inside_box(const double* x, int dimension, const std::array<std::array<double, 3>, 2>& box);

// Copies positions, volumes, regions of the cloud; allocates the state for the dimension and
// the effects (an effect that is off allocates nothing). Every point is owned (single process).
PointData make_point_data(const PointCloud& cloud, const EffectSet& effects);
// The same, taking over the cloud's volumes, regions and boundary ids instead of copying them and
// releasing its coordinates and normals (its pre-cracks and boundaries stay), so that the points
// are not held twice.
PointData make_point_data(PointCloud&& cloud, const EffectSet& effects);

}  // namespace mppm::solver
