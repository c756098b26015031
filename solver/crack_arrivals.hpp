// When each point reached the crack path (damage >= kCrackDamageThreshold, common/crack_path.hpp):
// the contents of the run directory's crack_path.csv (docs/stages.md). Damage only grows (a bond
// breaks for good, docs/theory.md section 7), so the crack path at time t is exactly the points
// that arrived at or before t: the table resolves the crack in time to the step, where the
// snapshots' damage fields resolve it to output.interval.
// Only a point whose list lost bonds can change its damage, so a step looks at the points the
// breakage update changed (bond_breakage.hpp), serially and in index order: the same for any
// thread count. A run without damage has none of this (empty arrays).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

class CrackArrivals {
 public:
  // Every point already on the crack path (the pre-crack cuts) arrives at `time`, the run's start.
  void start(const PointData& points, const BondFamilies& bonds, double time);
  // After a breakage update at the end of a step (`time`): the points of `changed` (sorted) whose
  // damage reached the threshold arrive then.
  void update(const PointData& points, const BondFamilies& bonds, const std::vector<std::size_t>& changed, double time);

  // The arrivals so far, in arrival order (time, then point index).
  const std::vector<std::uint64_t>& points() const { return points_; }
  const std::vector<double>& times() const { return times_; }
  std::size_t size() const { return points_.size(); }

  // A restart (solver/checkpoint.hpp): the arrivals of the checkpoint for a model of `point_count`
  // points. Throws InputError naming `file` when they are not a valid table (a point out of range
  // or listed twice, lengths that differ, times out of order).
  void restore(std::vector<std::uint64_t> points, std::vector<double> times, std::size_t point_count,
               const std::string& file);

 private:
  void arrive(std::size_t i, double time);
  std::vector<std::uint8_t> arrived_;  // per point: 1 once on the crack path
  std::vector<std::uint64_t> points_;
  std::vector<double> times_;
};

}  // namespace mppm::solver
