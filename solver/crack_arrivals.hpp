// When each point reached the crack path (damage >= kCrackDamageThreshold, common/crack_path.hpp):
// the contents of the run directory's crack_path.csv (docs/stages.md). Damage only grows (a bond
// breaks for good, docs/theory.md section 7), so the crack path at time t is exactly the points
// that arrived at or before t: the table resolves the crack in time to the step, where the
// snapshots' damage fields resolve it to output.interval.
// Only a point whose list lost bonds can change its damage, so a step looks at the points the
// breakage update changed (bond_breakage.hpp), serially and in index order: the same for any
// thread count. A run without damage has none of this (empty arrays).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

class CrackArrivals {
 public:
  // Every point already on the crack path (the pre-crack cuts) arrives at `time`, the run's start.
  void start(const PointData& points, const BondFamilies& bonds, double time);
  // After a breakage update at the end of a step (`time`): the points of `changed` (sorted) whose
  // damage reached the threshold arrive then.
  void update(const PointData& points, const BondFamilies& bonds, const std::vector<std::size_t>& changed, double time);

  // The arrivals so far, in arrival order (time, then point index), by index in the points file
  // (global id: a distributed run's process holds its own points' arrivals).
  const std::vector<std::uint64_t>& points() const { return points_; }
  const std::vector<double>& times() const { return times_; }
  std::size_t size() const { return points_.size(); }

  // The arrivals since the last call (the first: all of them), of every process, in arrival order
  // with their reference positions (z = 0 in 2-D): the rows crack_path.csv adds. Collective in a
  // distributed run; every process gets them all.
  struct Row {
    std::uint64_t point = 0;
    double time = 0.0;
    std::array<double, 3> position{0.0, 0.0, 0.0};
  };
  std::vector<Row> take_new_rows(const PointData& points, const ProcessGroup& group);

  // Every process's arrivals, merged in arrival order (collective; one process: its own).
  struct Table {
    std::vector<std::uint64_t> points;
    std::vector<double> times;
  };
  Table whole_table(const PointData& points, const ProcessGroup& group) const;

  // A restart (solver/checkpoint.hpp): the arrivals of the checkpoint for a model of `point_count`
  // points (of this process's points in a distributed run: `points_data`). Throws InputError naming `file` when they
  // are not a valid table (a point out of range or listed twice, lengths that differ, times out of order).
  void restore(std::vector<std::uint64_t> points, std::vector<double> times, const PointData& points_data,
               std::size_t point_count, const std::string& file);

 private:
  void arrive(const PointData& points, std::size_t i, double time);
  // The arrivals from the `first` on, of every process, merged in arrival order (collective).
  std::vector<Row> merged_rows(const PointData& points, const ProcessGroup& group, std::size_t first) const;
  std::vector<std::uint8_t> arrived_;  // per owned point (local index): 1 once on the crack path
  std::vector<std::uint64_t> points_;
  std::vector<double> times_;
  std::size_t reported_ = 0;  // arrivals already handed out by take_new_rows
};

}  // namespace mppm::solver
