// Energy-based bond breakage (SPEC section 7): the critical bond work calibrated from G_cr, the
// no-fail zone, the damage field, and the bookkeeping after a step in which bonds broke. The
// work of each bond is accumulated by the force kernel (internal_force_kernel.hpp), which is
// where the pair force is at hand; a bond breaks there, at both ends in the same step.
#pragma once
#include <cstddef>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// w_cr [J/m^6] such that breaking every bond across a plane costs G_cr per unit area of it for
// a constant critical work: 3-D 4 G_cr / (pi delta^4); 2-D 3 G_cr / (2 t delta^3), t the
// thickness of the plane-strain slice (the point volumes dx^2 t carry it).
double critical_bond_work(int dimension, double critical_energy_release_rate, double horizon, double thickness);

// Marks as no-fail (points.no_fail = 1) every point closer than `depth` to a point of a boundary
// condition (a kinematic layer point or a loaded body point: boundary_id > 0), the boundary points
// themselves included when depth > 0. A bond with a no-fail end never breaks.
void mark_no_fail_zone(PointData& points, double depth);

// sum_j V_j over each point's current family, stored as points.family_volume: call it before
// the pre-crack cuts, so that the notch shows as damage from the start.
void record_family_volume(PointData& points, const BondFamilies& bonds);

// D_i = 1 - sum_j b_ij V_j / family_volume_i (0 for a point without a family).
std::vector<double> damage_field(const PointData& points, const BondFamilies& bonds);

// After a force evaluation that broke bonds: recomputes the shape tensors of the points that lost
// bonds; a point left with a singular one is detached and its remaining bonds break (it moves
// ballistically). Returns the pairs broken in that evaluation and the points newly detached.
struct BreakageUpdate {
  std::size_t broken_pairs = 0;
  std::size_t newly_detached = 0;
};
BreakageUpdate update_after_breakage(PointData& points, BondFamilies& bonds, const CosseratConstants& c);

}  // namespace mppm::solver
