// A distributed run's damage state in a checkpoint (distributed_bond_state.hpp).
#include "solver/distributed_bond_state.hpp"

#include <algorithm>
#include <bit>
#include <numeric>
#include <span>
#include <tuple>

#include "common/input_error.hpp"

namespace mppm::solver {

namespace {

template <class T>
std::int64_t as_integer(T v) {
  if constexpr (std::is_same_v<T, double>)
    return std::bit_cast<std::int64_t>(v);
  else
    return static_cast<std::int64_t>(v);
}

template <class T>
T from_integer(std::int64_t v) {
  if constexpr (std::is_same_v<T, double>)
    return std::bit_cast<double>(v);
  else
    return static_cast<T>(v);
}

// Every owned point's values (`values(i, out)` appends point i's), of every process, in global-id
// order. Each point travels as its global id, its count of values and the values as integers.
template <class T, class Values>
std::vector<T> gather_by_global_id(const PointData& p, const ProcessGroup& group, Values&& values) {
  std::vector<std::int64_t> mine, point;
  for (std::size_t i = 0; i < p.owned; ++i) {
    point.clear();
    values(i, point);
    mine.push_back(p.global_id[i]);
    mine.push_back(static_cast<std::int64_t>(point.size()));
    mine.insert(mine.end(), point.begin(), point.end());
  }
  const std::vector<std::vector<std::int64_t>> all = group.gather(std::span<const std::int64_t>(mine));
  std::vector<std::tuple<std::int64_t, std::size_t, std::size_t>> where;  // global id, process, position
  for (std::size_t r = 0; r < all.size(); ++r)
    for (std::size_t m = 0; m + 1 < all[r].size(); m += 2 + static_cast<std::size_t>(all[r][m + 1]))
      where.emplace_back(all[r][m], r, m);
  std::sort(where.begin(), where.end());
  std::vector<T> out;
  for (const auto& [id, r, m] : where) {
    const auto n = static_cast<std::size_t>(all[r][m + 1]);
    for (std::size_t k = 0; k < n; ++k) out.push_back(from_integer<T>(all[r][m + 2 + k]));
  }
  return out;
}

// The first entry of each owned point's rows in the one-process array whose point g has
// `count(i)` entries: the sums of the counts of the points before it in global-id order.
template <class Count>
std::vector<std::size_t> whole_offsets(const PointData& p, const ProcessGroup& group, Count&& count) {
  std::vector<std::int64_t> mine;
  for (std::size_t i = 0; i < p.owned; ++i) {
    mine.push_back(p.global_id[i]);
    mine.push_back(count(i));
  }
  std::vector<std::pair<std::int64_t, std::int64_t>> all;
  for (const std::vector<std::int64_t>& from : group.gather(std::span<const std::int64_t>(mine)))
    for (std::size_t m = 0; m + 1 < from.size(); m += 2) all.emplace_back(from[m], from[m + 1]);
  std::sort(all.begin(), all.end());
  std::vector<std::size_t> start(all.size() + 1, 0);
  for (std::size_t k = 0; k < all.size(); ++k) start[k + 1] = start[k] + static_cast<std::size_t>(all[k].second);
  std::vector<std::size_t> offset(p.owned + 1);
  for (std::size_t i = 0; i < p.owned; ++i) {
    const auto it = std::lower_bound(all.begin(), all.end(), std::pair{p.global_id[i], std::int64_t{0}});
    offset[i] = start[static_cast<std::size_t>(it - all.begin())];
  }
  offset[p.owned] = start.back();  // the whole array's length
  return offset;
}

}  // namespace

std::vector<std::int32_t> gathered_bond_neighbors(const PointData& p, const BondFamilies& f,
                                                  const ProcessGroup& group) {
  return gather_by_global_id<std::int32_t>(p, group, [&](std::size_t i, std::vector<std::int64_t>& out) {
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const auto id = static_cast<std::int32_t>(p.global_id[f.neighbor_of(b)]);
      out.push_back(f.acting(b) ? id : (id | BondFamilies::kBrokenBit));
    }
  });
}

std::vector<double> gathered_bond_work(const PointData& p, const BondFamilies& f, const ProcessGroup& group) {
  return gather_by_global_id<double>(p, group, [&](std::size_t i, std::vector<std::int64_t>& out) {
    for (std::int64_t k = f.pair_offset[i]; k < f.pair_offset[i + 1]; ++k)
      out.push_back(as_integer(f.work[static_cast<std::size_t>(k)]));
  });
}

template <class T>
std::vector<T> gathered_point_values(const PointData& p, std::span<const T> values, const ProcessGroup& group) {
  const std::size_t width = values.size() / p.total();
  return gather_by_global_id<T>(p, group, [&](std::size_t i, std::vector<std::int64_t>& out) {
    for (std::size_t c = 0; c < width; ++c) out.push_back(as_integer(values[i * width + c]));
  });
}
template std::vector<std::uint8_t> gathered_point_values(const PointData&, std::span<const std::uint8_t>,
                                                         const ProcessGroup&);
template std::vector<std::int32_t> gathered_point_values(const PointData&, std::span<const std::int32_t>,
                                                         const ProcessGroup&);

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
