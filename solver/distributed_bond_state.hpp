// The bond state of a distributed damage run in a checkpoint (docs/theory.md section 13): the bonds'
// broken marks and the pairs' work, in the one-process layout (points in global-id order, each
// point's bonds in its list's order). Written as rows, a chunk at a time, through the first
// process's gathered writer (distributed_snapshot.hpp), so no process holds a whole bond array; read
// whole on a restart (the memory limit docs/theory.md states).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/distributed_snapshot.hpp"
#include "solver/point_data.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

// The rows of the two bond arrays: one per bond entry (bond_neighbor: the neighbour's global id,
// with BondFamilies::kBrokenBit when the bond is broken) and one per pair (bond_work: W_ij, at the
// pair's end earlier in the global order). A process's rows are its owned points' entries, which
// its local order keeps in global-id order. The first process finds a row's owner from each point's
// first rows (16 bytes per point, there only). Keep the object alive while the rows are written.
class BondRows {
 public:
  // Collective. `part_of`: the process of every point of the whole cloud.
  BondRows(const PointData& points, const BondFamilies& bonds, std::span<const std::int32_t> part_of,
           const ProcessGroup& group);
  GatheredRowSet entries() const;  // the field "bond_neighbor"
  GatheredRowSet pairs() const;    // the field "bond_work"
  // The whole model's rows (on the first process).
  std::uint64_t entry_count() const { return first_entry_.empty() ? 0 : first_entry_.back(); }
  std::uint64_t pair_count() const { return first_pair_.empty() ? 0 : first_pair_.back(); }

 private:
  const PointData& points_;
  const BondFamilies& bonds_;
  std::span<const std::int32_t> part_of_;
  std::vector<std::int64_t> entry_ids_, pair_ids_;       // the global row of each local row
  std::vector<std::uint64_t> first_entry_, first_pair_;  // first process: each point's first row, and the count
};

// Collective. The restore: this process's bonds broken where `neighbors` (the one-process lists)
// marks them, and its pairs' work from `work`. Throws InputError naming `file` when the lists are
// not those of this model.
void restore_own_bonds(const std::vector<std::int32_t>& neighbors, const std::vector<double>& work, PointData& points,
                       BondFamilies& bonds, const ProcessGroup& group, const std::string& file);

}  // namespace mppm::solver
