// The crack-arrival table (crack_arrivals.hpp).
#include "solver/crack_arrivals.hpp"

#include <algorithm>
#include <bit>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/crack_path.hpp"
#include "common/input_error.hpp"
#include "solver/bond_breakage.hpp"

namespace mppm::solver {

void CrackArrivals::arrive(const PointData& p, std::size_t i, double time) {
  arrived_[i] = 1;
  points_.push_back(static_cast<std::uint64_t>(p.global_index(i)));
  times_.push_back(time);
}

void CrackArrivals::start(const PointData& p, const BondFamilies& f, double time) {
  arrived_.assign(p.owned, 0);
  points_.clear();
  times_.clear();
  reported_ = 0;
  for (std::size_t i = 0; i < p.owned; ++i)
    if (point_damage(p, f, i) >= kCrackDamageThreshold) arrive(p, i, time);
}

void CrackArrivals::update(const PointData& p, const BondFamilies& f, const std::vector<std::size_t>& changed,
                           double time) {
  for (const std::size_t i : changed)
    if (i < arrived_.size() && !arrived_[i] && point_damage(p, f, i) >= kCrackDamageThreshold) arrive(p, i, time);
}

std::vector<CrackArrivals::Row> CrackArrivals::merged_rows(const PointData& p, const ProcessGroup& group,
                                                           std::size_t first) const {
  // Each row travels as 5 integers (the point, and the time and position's bits).
  const auto D = static_cast<std::size_t>(p.dimension);
  std::vector<std::int64_t> mine;
  for (std::size_t k = first; k < points_.size(); ++k) {
    const std::optional<std::size_t> i = owned_index(p, points_[k]);
    if (!i) throw std::logic_error("CrackArrivals: point " + std::to_string(points_[k]) + " is not owned here");
    std::array<double, 3> x{0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < D; ++c) x[c] = p.position[*i * D + c];
    mine.push_back(static_cast<std::int64_t>(points_[k]));
    mine.push_back(std::bit_cast<std::int64_t>(times_[k]));
    for (const double v : x) mine.push_back(std::bit_cast<std::int64_t>(v));
  }
  std::vector<Row> rows;
  for (const std::vector<std::int64_t>& from : group.gather(mine))
    for (std::size_t m = 0; m + 4 < from.size(); m += 5)
      rows.push_back({static_cast<std::uint64_t>(from[m]),
                      std::bit_cast<double>(from[m + 1]),
                      {std::bit_cast<double>(from[m + 2]), std::bit_cast<double>(from[m + 3]),
                       std::bit_cast<double>(from[m + 4])}});
  // Each process's rows are in arrival order already; merged, arrival order is time, then point.
  if (group.distributed())
    std::sort(rows.begin(), rows.end(),
              [](const Row& a, const Row& b) { return a.time != b.time ? a.time < b.time : a.point < b.point; });
  return rows;
}

std::vector<CrackArrivals::Row> CrackArrivals::take_new_rows(const PointData& p, const ProcessGroup& group) {
  std::vector<Row> rows = merged_rows(p, group, reported_);
  reported_ = points_.size();
  return rows;
}

CrackArrivals::Table CrackArrivals::whole_table(const PointData& p, const ProcessGroup& group) const {
  Table table;
  for (const Row& row : merged_rows(p, group, 0)) {
    table.points.push_back(row.point);
    table.times.push_back(row.time);
  }
  return table;
}

void CrackArrivals::restore(std::vector<std::uint64_t> points, std::vector<double> times, const PointData& p,
                            std::size_t point_count, const std::string& file) {
  auto refuse = [&](const std::string& what) {
    throw InputError(file + ": corrupted checkpoint (the crack-arrival table " + what + ")");
  };
  if (points.size() != times.size())
    refuse("has " + std::to_string(points.size()) + " points but " + std::to_string(times.size()) + " times");
  std::vector<std::uint8_t> arrived(point_count, 0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k] >= point_count)
      refuse("names point " + std::to_string(points[k]) + " of " + std::to_string(point_count));
    if (arrived[points[k]]) refuse("lists point " + std::to_string(points[k]) + " twice");
    if (k > 0 && !(times[k] >= times[k - 1])) refuse("is not in time order");
    arrived[points[k]] = 1;
  }
  reported_ = 0;
  if (p.global_id.empty()) {
    arrived_ = std::move(arrived);
    points_ = std::move(points);
    times_ = std::move(times);
    return;
  }
  // A distributed run's process keeps its own points' arrivals (in the table's order).
  arrived_.assign(p.owned, 0);
  points_.clear();
  times_.clear();
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::optional<std::size_t> i = owned_index(p, points[k]);
    if (!i) continue;
    arrived_[*i] = 1;
    points_.push_back(points[k]);
    times_.push_back(times[k]);
  }
}

}  // namespace mppm::solver
