// A distributed run's damage state in a checkpoint (distributed_bond_state.hpp).
#include "solver/distributed_bond_state.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>
#include <utility>

#include "common/input_error.hpp"

namespace mppm::solver {

namespace {

// Each point's first bond entry and first pair in the one-process arrays (bond_neighbor, bond_work):
// the sums of the counts of the points before it in global-id order, for every point of the whole
// cloud (global ids are 0 .. n-1), and each array's length last. One gather of (global id, entries,
// pairs) per owned point, on every process.
struct FirstRows {
  std::vector<std::uint64_t> entry, pair;
};

std::int64_t entries_of(const BondFamilies& f, std::size_t i) { return f.offset[i + 1] - f.offset[i]; }
std::int64_t pairs_of(const BondFamilies& f, std::size_t i) { return f.pair_offset[i + 1] - f.pair_offset[i]; }

FirstRows first_rows(const PointData& p, const BondFamilies& f, const ProcessGroup& group) {
  std::vector<std::int64_t> mine;
  for (std::size_t i = 0; i < p.owned; ++i) {
    mine.push_back(p.global_id[i]);
    mine.push_back(entries_of(f, i));
    mine.push_back(pairs_of(f, i));
  }
  std::vector<std::array<std::int64_t, 3>> all;
  for (const std::vector<std::int64_t>& from : group.gather(std::span<const std::int64_t>(mine)))
    for (std::size_t m = 0; m + 2 < from.size(); m += 3) all.push_back({from[m], from[m + 1], from[m + 2]});
  std::sort(all.begin(), all.end());
  FirstRows first{std::vector<std::uint64_t>(all.size() + 1, 0), std::vector<std::uint64_t>(all.size() + 1, 0)};
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k][0] != static_cast<std::int64_t>(k))
      throw std::logic_error("bond rows: the processes' points are not the global ids 0 .. n-1");
    first.entry[k + 1] = first.entry[k] + static_cast<std::uint64_t>(all[k][1]);
    first.pair[k + 1] = first.pair[k] + static_cast<std::uint64_t>(all[k][2]);
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

}  // namespace

BondRows::BondRows(const PointData& p, const BondFamilies& f, std::span<const std::int32_t> part_of,
                   const ProcessGroup& group)
    : points_(p), bonds_(f), part_of_(part_of) {
  FirstRows first = first_rows(p, f, group);
  entry_ids_ = own_row_ids(p, first.entry, [&](std::size_t i) { return entries_of(f, i); });
  pair_ids_ = own_row_ids(p, first.pair, [&](std::size_t i) { return pairs_of(f, i); });
  first_entry_ = std::move(first.entry);
  first_pair_ = std::move(first.pair);
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
  const FirstRows first = first_rows(p, f, group);
  bool same = first.entry.back() == neighbors.size() && first.pair.back() == work.size();
  for (std::size_t i = 0; same && i < p.owned; ++i) {
    const auto g = static_cast<std::size_t>(p.global_id[i]);
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const std::int32_t saved = neighbors[first.entry[g] + static_cast<std::size_t>(b - f.offset[i])];
      same = same && static_cast<std::int64_t>(BondFamilies::index_of(saved)) == p.global_id[f.neighbor_of(b)];
      if (same && saved < 0) f.break_bond(b);
    }
    for (std::int64_t k = f.pair_offset[i]; k < f.pair_offset[i + 1]; ++k)
      f.work[static_cast<std::size_t>(k)] = work[first.pair[g] + static_cast<std::size_t>(k - f.pair_offset[i])];
  }
  if (group.any(!same))
    throw InputError(file + ": the checkpoint's bonds are not those of these points (corrupted checkpoint?)");
}

}  // namespace mppm::solver
