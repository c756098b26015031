// Energy-based bond breakage (docs/theory.md section 7): the critical bond work calibrated from G_cr, the
// no-fail zone, the damage field, and the bookkeeping after a step in which bonds broke. The
// work of each bond is accumulated by the force kernel (internal_force_kernel.hpp), which is
// where the pair force is at hand; the kernel only counts the bonds that reached the critical
// work (points.bonds_broken). update_after_breakage, which Model::advance_internal_forces calls
// right after that evaluation, breaks them, at both ends in the same step.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/internal_forces.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// w_cr [J/m^6] such that breaking every bond across a plane costs G_cr per unit area of it, for a
// constant critical work. "continuum" (docs/theory.md section 7): 3-D 4 G_cr / (pi delta^4); 2-D
// 3 G_cr / (2 t delta^3), t the thickness of the plane-strain slice (the point volumes dx^2 t
// carry it). "lattice" (default): the same statement for the bonds of the lattice itself, whose
// crossing sum differs from the continuum one by -21 % to +17 % at the usual horizon factors
// (2-D 2.05: 0.87, 3.05: 0.95; 3-D 2.05: 0.79, 2.55: 1.17, 3.05: 1.03), which would otherwise be
// a calibration error of the same size (tests/verification/test_solver_crack_energy.cpp).
// "dissipation": the lattice value divided by the released fraction rho of a running crack
// (solver/damage_calibration.hpp), which depends on the horizon factor and G_s
// (`stabilization`); std::invalid_argument outside the measured ranges.
double critical_bond_work(const DamageParameters& damage, int dimension, double spacing, double horizon_factor,
                          double thickness, double stabilization);
double continuum_critical_bond_work(int dimension, double critical_energy_release_rate, double horizon,
                                    double thickness);
// sum of b over the lattice offsets (a, b[, c]) with b > 0 within the horizon factor: the bonds
// crossing a plane between two rows, per lattice cell of that plane, in units of V^2 / cell.
double lattice_crossing_sum(int dimension, double horizon_factor);

// Marks as no-fail (points.no_fail = 1) every point closer than `depth` to a point of a boundary
// condition (a kinematic layer point or a loaded body point: boundary_id > 0), the boundary points
// themselves included when depth > 0. A bond with a no-fail end never breaks. The boundary ids in
// `ignored` (the pore fluid's own boundaries: FluidBoundaryLayout::fluid_only_ids) make no zone.
// Every local point is marked, ghosts included. A distributed run passes the whole cloud
// (`whole`): the zone's depth can exceed the ghosts' reach, so the boundary points come from it.
void mark_no_fail_zone(PointData& points, double depth, const std::vector<std::int32_t>& ignored = {},
                       const PointCloud* whole = nullptr);

// sum_j V_j over each point's whole list (broken bonds included), in list order.
std::vector<double> family_volumes(const PointData& points, const BondFamilies& bonds);
// Keeps in points.precut_* the family volumes `before` of the points whose lists the pre-crack cuts
// changed (call it after the cuts), so that the notch shows as damage from the start.
void record_precut_family_volumes(PointData& points, const BondFamilies& bonds, const std::vector<double>& before);
// The family volume of point i before the pre-crack cuts.
double family_volume_of(const PointData& points, const BondFamilies& bonds, std::size_t i);

// D_i = 1 - sum_j b_ij V_j / family volume_i (0 for a point without a family).
double point_damage(const PointData& points, const BondFamilies& bonds, std::size_t i);
std::vector<double> damage_field(const PointData& points, const BondFamilies& bonds);

// After a force evaluation in which bonds reached their critical work (counted by the kernel in
// points.bonds_broken at their lower end): breaks them for good, recomputes the shape tensors of
// the points that lost bonds and the step's forces without them; a point left with a singular one
// is detached and its remaining bonds break (it moves ballistically). The energy the breaks
// release is measured, not assumed: the stored energy of the affected points before minus after,
// at the same configuration (so the energy balance closes; the bond work W_ij is the breakage
// criterion, not the measure of what a break dissipates). A point whose stored energy would rise
// by losing bonds, by more than c.detach_energy_rise or at all when it is overloaded
// (c.overload_factor; both from the scene's numerics block), is detached (see the .cpp for why). A body point whose
// stiffness block exceeds `block_eigenvalue_limit` (point_stability.hpp; 0: no such check) is
// detached as well: its lopsided family would make the run's time step unstable. Returns the pairs
// broken in that evaluation (cascade included), the points newly detached (of them for stability)
// and the released energy [J]. In a distributed run it is a collective call (docs/theory.md
// section 13) with the same result as one process: the counts are this process's shares (a pair
// counted at its end earlier in the global order, a point by its owner), summed over the
// processes by the caller; the released energy is the whole model's.
struct BreakageUpdate {
  bool broke = false;  // bonds broke anywhere in the model (then the workspace's lists are this update's)
  std::size_t broken_pairs = 0;
  std::size_t newly_detached = 0;
  std::size_t unstable_detached = 0;  // of them, for the time step's sake
  std::size_t energy_detached = 0;    // of them, because losing bonds raised their stored energy
  double released_energy = 0.0;       // stored energy released by the breaks [J]
};

// The energy it takes to break every bond of point i at the critical bond work, the point's half
// share of each pair: 1/2 w_cr V_i sum_j V_j over its family, broken bonds included [J]. Summed
// over the points it is the critical work of all the pairs.
double family_breaking_energy(const PointData& points, const BondFamilies& bonds, const CosseratConstants& c,
                              std::size_t i);

// Scratch arrays kept from one step to the next (no allocation in the time loop once warm).
struct BreakageWorkspace {
  std::vector<std::int64_t> affected_index;  // per point: index into affected, -1 if not met
  // Bond entries breaking in this update, with their points.
  std::vector<std::pair<std::size_t, std::int64_t>> breaking;
  // A distributed run: bonds broken here whose other end is a ghost, for its owner; ghost flags
  // (a per-point field for the exchange, and its ghost rows); the owned points with a bond to
  // each ghost (CSR by ghost, with the bond entry), indexed once.
  std::vector<PointNote> notes;
  std::vector<double> flag_values;
  std::vector<std::uint8_t> ghost_flag;
  std::vector<std::size_t> ghost_neighbour_offset, ghost_neighbour;
  std::vector<std::int64_t> ghost_neighbour_bond;
  void index_ghost_neighbours(const PointData& points, const BondFamilies& bonds);
  std::vector<std::size_t> affected, changed, next, detach, candidates;
  // After an update that broke bonds: the points whose lists lost bonds in it, sorted (the only
  // points whose damage changed). Stale after an update that broke none.
  std::vector<std::size_t> sorted;
  std::vector<double> energy_before;
  std::vector<double> candidate_eigenvalue;  // the stability check's blocks, evaluated in parallel
  std::vector<std::uint8_t> was_detached;
};
BreakageUpdate update_after_breakage(PointData& points, BondFamilies& bonds, const CosseratConstants& c,
                                     const InternalForceFunctions& kernel, double block_eigenvalue_limit,
                                     BreakageWorkspace& workspace);

}  // namespace mppm::solver
