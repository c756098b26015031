// What a run will cost, before it runs (mppm-solve --estimate, mppm-preprocess --estimate): its
// points and bonds, its time step and number of steps, the predicted wall time (common/run_cost_model.hpp)
// and peak memory (common/memory_estimate.hpp). The time step is the scene's given step, or the
// automatic one from the critical step of a small block of the scene's lattice, material and effects
// (a few hundred to a few thousand points, free faces and corners included: a fraction of a
// second), so the run itself is not started. A given step above the sample's critical step is
// refused as the run would refuse it.
#pragma once
#include <cstdint>
#include <string>

#include "common/point_cloud.hpp"
#include "common/run_cost_model.hpp"
#include "common/scene.hpp"

namespace mppm::solver {

struct RunEstimate {
  std::uint64_t points = 0, bonds = 0;
  bool bonds_counted = false;  // counted from the families, else the lattice estimate
  double critical_step = 0.0;  // of the sample block [s]
  double time_step = 0.0;      // given, or safety x critical (the damage bound included)
  bool step_given = false;
  std::int64_t steps = 0;
  std::int64_t snapshots = 0;
  int threads = 1;
  RunCostEstimate cost;
  std::uint64_t memory_bytes = 0;
};

// `bonds` 0: estimated from the lattice (common/memory_estimate.hpp estimated_bond_entries).
RunEstimate estimate_run(const Scene& scene, const PointCloud& cloud, std::uint64_t bonds, int threads);

// The lines mppm-solve / mppm-preprocess print.
std::string format_run_estimate(const Scene& scene, const RunEstimate& estimate);

}  // namespace mppm::solver
