// Shape tensors K_i = sum_j b w (xi (x) xi) V_j, their inverses, the stabilization tensors built
// from them, and the detection of detached points (docs/theory.md sections 2-3).
#pragma once
#include <cstddef>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// A point is detached when fewer than d+1 bonds act on it or when the reciprocal condition
// number of K (smallest over largest eigenvalue) is below this.
inline constexpr double kDetachReciprocalCondition = 1e-6;

// Fills shape_inverse, stabilization_ck, stabilization_rot and detached for every owned point
// (K is never inverted when it is singular); returns the number of detached points.
std::size_t update_shape_tensors(PointData& points, const BondFamilies& bonds, const CosseratConstants& c);

// Recomputes stabilization_ck of every owned point from its K^-1 and the constants `c` (the
// same bits as update_shape_tensors), e.g. after a study that switched the stabilization off.
void update_stabilization_tensors(PointData& points, const CosseratConstants& c);

// Marks point i detached: its K^-1 and stabilization tensors are zero, so it carries no stress
// and moves ballistically (its bonds are the caller's business).
void detach_point(PointData& points, std::size_t i);

// The same for the listed points only (those whose bonds changed); a point may become detached,
// a detached one stays so.
void update_shape_tensors(PointData& points, const BondFamilies& bonds, const CosseratConstants& c,
                          const std::vector<std::size_t>& changed_points);

// A distributed run (a collective call; nothing without ghosts): the ghosts' G_s (C : K^-1) and
// G_s B_w tr(K^-1) / d from their owners, which pass 2 reads at the neighbours; `all` adds K^-1
// and the detached flag, which the damage effect's stability blocks read there.
void share_shape_terms(PointData& points, bool all);

}  // namespace mppm::solver
