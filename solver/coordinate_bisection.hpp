// The static partition of a distributed run (docs/theory.md section 13): weighted recursive
// coordinate bisection of the reference lattice. Each cut splits a set of points across the longest
// side of its bounding box where the weights on either side stand in the ratio of the parts each
// side gets; points are ordered along the axis by coordinate, ties by global id, so the partition
// depends on the points alone: not on their order in memory, the thread count or the process that
// computes it.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace mppm::solver {

struct PartitionPoints {
  int dimension = 2;
  std::span<const double> position;         // dimension per point
  std::span<const std::int64_t> weight;     // cost of each point (> 0): its bonds, plus its return map's
  std::span<const std::int64_t> global_id;  // unique
};

// The part (0 .. parts-1) of each point. Every part gets at least one point; throws
// std::invalid_argument when there are fewer points than parts or the spans disagree.
std::vector<std::int32_t> coordinate_bisection(const PartitionPoints& points, int parts);

}  // namespace mppm::solver
