// The damage state of a distributed run in a checkpoint (docs/theory.md section 13): the arrays that
// are not rows of doubles per point (the bonds' broken marks and work, the per-point flags), in the
// one-process layout, points in global-id order. Every process gets them whole (a damage run's
// checkpoint puts every bond's state in one file, which each process holds while writing and
// reading it: the memory limit docs/theory.md states).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

// Collective. The neighbour lists of the one-process model: each bond's neighbour by global id,
// with BondFamilies::kBrokenBit when it is broken.
std::vector<std::int32_t> gathered_bond_neighbors(const PointData& points, const BondFamilies& bonds,
                                                  const ProcessGroup& group);
// Collective. The pairs' work W_ij, each at its end earlier in the global order.
std::vector<double> gathered_bond_work(const PointData& points, const BondFamilies& bonds, const ProcessGroup& group);
// Collective. A per-point array (the same number of values per local point) of the owned points.
template <class T>
std::vector<T> gathered_point_values(const PointData& points, std::span<const T> values, const ProcessGroup& group);

// Collective. The restore: this process's bonds broken where `neighbors` (the one-process lists)
// marks them, and its pairs' work from `work`. Throws InputError naming `file` when the lists are
// not those of this model.
void restore_own_bonds(const std::vector<std::int32_t>& neighbors, const std::vector<double>& work, PointData& points,
                       BondFamilies& bonds, const ProcessGroup& group, const std::string& file);

}  // namespace mppm::solver
