// How a distributed run's points and work are shared among its processes (run_info.json and
// log.txt; docs/theory.md section 13).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mppm::solver {

// Per process its owned points, ghosts and bonds, and the imbalance: the heaviest process's bonds
// over the mean (1 = even).
struct PartitionSummary {
  std::vector<std::int64_t> points, ghosts, bonds;
  double imbalance = 1.0;
};

// "2 processes: points 8000 / 8000, ghosts 320 / 320, bonds 372854 / 372854, imbalance 1.000"
std::string describe(const PartitionSummary& summary);

}  // namespace mppm::solver
