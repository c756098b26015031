// Stability of a point after its bonds changed (damage). Breaking bonds leaves lopsided families
// whose shape tensor K_i is nearly singular; K_i^-1 then amplifies the point's stiffness and the
// critical time step of the run falls below the step in use (measured: 0.8 -> 0.4 of the start-up
// critical step in a strip whose crack ran, and the run blew up). docs/theory.md section 2 detaches points
// whose K_i is singular; this module decides when K_i is too badly conditioned for the run's step.
//
// The measure is the largest eigenvalue of M_i^-1 H_i, H_i the block of the stiffness matrix of
// the point's own degrees of freedom (u_i, and w_i with micropolar): the Rayleigh quotient of any
// field that moves only point i, so a lower bound of omega_max^2 of the whole model. It is computed
// in closed form from the energy of such a field (the point's own energy and that of every point
// whose family holds it), in O(family) operations. omega_max^2 is kappa times the largest block
// value: kappa_0 = 1.4 on intact lattices, and up to 3.1 measured on damaged ones (crack faces,
// fragments: neighbouring lopsided families couple), where the critical step then falls to 0.45
// of the start-up one. So a point is detached when the damaged frequency ratio (numerics.
// damaged_frequency_ratio, default 3.5: the largest omega_max^2 / largest block value a damaged
// lattice is allowed, measured up to 3.1; CosseratConstants) times its block value
// exceeds (2 / dt)^2, which keeps omega_max dt <= 2 for kappa up to that ratio; and the time step
// of a damage run must leave every intact point inside that limit from the start:
// dt <= 2 / sqrt(ratio x max block value), about 0.6 of the start-up critical step
// (Model::damage_critical_step).
#pragma once
#include <cstddef>

#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// lambda_max(M_i^-1 H_i) [1/s^2] of point i with its bonds and shape tensors as they are; 0 for a
// detached point.
double point_block_eigenvalue(const PointData& points, const BondFamilies& bonds, const CosseratConstants& c,
                              std::size_t i);

// The same block H_i itself (D + R square, row-major; translation first), for the tests.
void point_stiffness_block(const PointData& points, const BondFamilies& bonds, const CosseratConstants& c,
                           std::size_t i, double* block);

// The largest block value over the body points (region 0) that are not detached.
double max_point_block_eigenvalue(const PointData& points, const BondFamilies& bonds, const CosseratConstants& c);

// A point of the largest block value (of several, the first) and that value (0: none).
struct StiffestPoint {
  std::size_t index = 0;
  double block_eigenvalue = 0.0;
};
// Over the body points (the damage step limit: only they lose bonds) and over all points, the
// fictitious layers' too (where the highest mode of the whole operator may live: the naming's
// patch, critical_time_step.cpp), from one pass over the points.
struct StiffestPoints {
  StiffestPoint body, any;
};
StiffestPoints stiffest_points(const PointData& points, const BondFamilies& bonds, const CosseratConstants& c);
// With micro-rotations, the stiffest points of the blocks' translational and rotational parts over
// all points (the largest eigenvalue of M^-1/2 H M^-1/2 restricted to each part): the centres of
// the patches that name a highest mode mixing both (critical_time_step.cpp). The values of the
// parts are Eigen's closed forms: a patch centre needs no more accuracy.
struct StiffestParts {
  StiffestPoint translational, rotational;
};
StiffestParts stiffest_parts(const PointData& points, const BondFamilies& bonds, const CosseratConstants& c);

}  // namespace mppm::solver
