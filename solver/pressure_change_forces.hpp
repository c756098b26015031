// The forces of a pore-pressure change at a fixed skeleton (docs/theory.md section 12): after a batch
// of flow updates only the pressures changed, and the force state is linear in them, so the
// forces, moments and force tensors are corrected by the change instead of evaluated again. With
// A_i = sigma_i K_i^-1 - G_s (C:K_i^-1) eps_i and sigma_i = sigma'_i - b p_i 1, a change dp gives
// dA_i = -b dp_i K_i^-1, and with the kernel's sums (internal_force_kernel.hpp)
//   df_i = dA_i m_i + sum_j V_j dA_j xi,   m_i = sum_j V_j xi,
//   dl_i = sum_j V_j 1/2 xi x (dA_j xi)    (dA_i K_i is isotropic: no moment of its own),
// over the acting bonds. A bond loop with a scalar per neighbour: a fraction of a force evaluation.
// Unsaturated, the change is that of Bishop's pore stress S_r(p) p (solver/unsaturated_coupling.hpp).
#pragma once
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// Adds to points.force, points.moment and points.force_tensor the change that the pressures
// points.pore_pressure make against `pressure_before` (one per point) at the body points that are
// not detached (the layers carry no pressure in the force state; a detached point has none).
void add_pressure_change_forces(PointData& points, const BondFamilies& bonds, const CosseratConstants& constants,
                                const std::vector<double>& pressure_before);

}  // namespace mppm::solver
