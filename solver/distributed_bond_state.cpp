// A distributed run's damage state in a checkpoint (distributed_bond_state.hpp).
#include "solver/distributed_bond_state.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>

#include "common/input_error.hpp"

namespace mppm::solver {

namespace {

// Each point's first row in the one-process array whose point g has `count(i)` rows (owned point i
// of some process): the sums of the counts of the points before it in global-id order, for every
// point of the whole cloud (global ids are 0 .. n-1), and the whole array's length last.
template <class Count>
std::vector<std::uint64_t> first_rows(const PointData& p, const ProcessGroup& group, Count&& count) {
  std::vector<std::int64_t> mine;
  for (std::size_t i = 0; i < p.owned; ++i) {
    mine.push_back(p.global_id[i]);
    mine.push_back(count(i));
  }
  std::vector<std::pair<std::int64_t, std::int64_t>> all;
  for (const std::vector<std::int64_t>& from : group.gather(std::span<const std::int64_t>(mine)))
    for (std::size_t m = 0; m + 1 < from.size(); m += 2) all.emplace_back(from[m], from[m + 1]);
  std::sort(all.begin(), all.end());
  std::vector<std::uint64_t> first(all.size() + 1, 0);
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].first != static_cast<std::int64_t>(k))
      throw std::logic_error("bond rows: the processes' points are not the global ids 0 .. n-1");
    first[k + 1] = first[k] + static_cast<std::uint64_t>(all[k].second);
  }
  return first;
}

// The global row of every local row: owned point i's rows follow its first row.
template <class Count>
std::vector<std::int64_t> own_row_ids(const PointData& p, const std::vector<std::uint64_t>& first, Count&& count) {
  std::vector<std::int64_t> ids;
  for (std::size_t i = 0; i < p.owned; ++i) {
    const auto start = static_cast<std::int64_t>(first[static_cast<std::size_t>(p.global_id[i])]);
    for (std::int64_t k = 0; k < count(i); ++k) ids.push_back(start + k);
  }
  return ids;
}

// The rows' distribution: a row's owner is the owner of the point whose rows hold it. A chunk's rows
// are consecutive: the first row's point is found by bisection, the others by walking on.
DistributedRows rows_by_point(std::span<const std::int64_t> ids, const std::vector<std::uint64_t>& first,
                              std::span<const std::int32_t> part_of) {
  DistributedRows rows;
  rows.local_ids = ids;
  rows.owners = [&first, part_of](std::int64_t begin, std::int64_t end, std::int32_t* out) {
    auto point = std::upper_bound(first.begin(), first.end(), static_cast<std::uint64_t>(begin)) - first.begin() - 1;
    for (std::int64_t g = begin; g < end; ++g) {
      while (first[static_cast<std::size_t>(point) + 1] <= static_cast<std::uint64_t>(g)) ++point;
      out[g - begin] = part_of[static_cast<std::size_t>(point)];
    }
  };
  return rows;
}

// The first entry of each owned point's rows in the one-process array, and the array's length last.
template <class Count>
std::vector<std::size_t> whole_offsets(const PointData& p, const ProcessGroup& group, Count&& count) {
  const std::vector<std::uint64_t> first = first_rows(p, group, count);
  std::vector<std::size_t> offset(p.owned + 1);
  for (std::size_t i = 0; i < p.owned; ++i) offset[i] = first[static_cast<std::size_t>(p.global_id[i])];
  offset[p.owned] = first.back();
  return offset;
}

}  // namespace

BondRows::BondRows(const PointData& p, const BondFamilies& f, std::span<const std::int32_t> part_of,
                   const ProcessGroup& group)
    : points_(p), bonds_(f), part_of_(part_of) {
  auto entries = [&](std::size_t i) { return f.offset[i + 1] - f.offset[i]; };
  auto pairs = [&](std::size_t i) { return f.pair_offset[i + 1] - f.pair_offset[i]; };
  first_entry_ = first_rows(p, group, entries);
  first_pair_ = first_rows(p, group, pairs);
  entry_ids_ = own_row_ids(p, first_entry_, entries);
  pair_ids_ = own_row_ids(p, first_pair_, pairs);
  if (group.rank() != 0) {  // only the first process places rows
    first_entry_ = {};
    first_pair_ = {};
  }
}

// The local rows are the owned points' entries and pairs in the local arrays' order: the k-th local
// row is bond entry k, and pair k.
GatheredRowSet BondRows::entries() const {
  GatheredRowSet set;
  set.rows = rows_by_point(entry_ids_, first_entry_, part_of_);
  set.local.push_back({"bond_neighbor", 1, [this](std::uint64_t first, std::uint64_t n, double* out) {
                         for (std::uint64_t k = 0; k < n; ++k) {
                           const auto b = static_cast<std::int64_t>(first + k);
                           const auto id = static_cast<std::int32_t>(points_.global_id[bonds_.neighbor_of(b)]);
                           out[k] = bonds_.acting(b) ? id : (id | BondFamilies::kBrokenBit);
                         }
                       }});
  return set;
}

GatheredRowSet BondRows::pairs() const {
  GatheredRowSet set;
  set.rows = rows_by_point(pair_ids_, first_pair_, part_of_);
  set.local.push_back({"bond_work", 1, [this](std::uint64_t first, std::uint64_t n, double* out) {
                         std::copy_n(bonds_.work.data() + first, n, out);
                       }});
  return set;
}

void restore_own_bonds(const std::vector<std::int32_t>& neighbors, const std::vector<double>& work, PointData& p,
                       BondFamilies& f, const ProcessGroup& group, const std::string& file) {
  const std::vector<std::size_t> entry =
      whole_offsets(p, group, [&](std::size_t i) { return f.offset[i + 1] - f.offset[i]; });
  const std::vector<std::size_t> pair =
      whole_offsets(p, group, [&](std::size_t i) { return f.pair_offset[i + 1] - f.pair_offset[i]; });
  bool same = entry.back() == neighbors.size() && pair.back() == work.size();
  for (std::size_t i = 0; same && i < p.owned; ++i) {
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const std::int32_t saved = neighbors[entry[i] + static_cast<std::size_t>(b - f.offset[i])];
      same = same && static_cast<std::int64_t>(BondFamilies::index_of(saved)) == p.global_id[f.neighbor_of(b)];
      if (same && saved < 0) f.break_bond(b);
    }
    for (std::int64_t k = f.pair_offset[i]; k < f.pair_offset[i + 1]; ++k)
      f.work[static_cast<std::size_t>(k)] = work[pair[i] + static_cast<std::size_t>(k - f.pair_offset[i])];
  }
  if (group.any(!same))
    throw InputError(file + ": the checkpoint's bonds are not those of these points (corrupted checkpoint?)");
}

}  // namespace mppm::solver
