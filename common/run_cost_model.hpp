// How long a run will take, before it runs: wall time = start-up + steps x bond entries x the cost
// of one bond update for the dimension and the effect set, over the threads. The costs are
// measured on the development machine (common/run_cost_model.cpp says where); on another machine
// the prediction scales with its speed. mppm-solve --estimate and mppm-preprocess --estimate
// print it (docs/stages.md); workflows/accuracy-cost/README.md reports how close it comes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mppm {

struct RunCostInput {
  int dimension = 2;
  std::vector<std::string> effects;  // scene effect names
  std::uint64_t points = 0;
  std::uint64_t bonds = 0;  // bond entries (each bond at both of its points)
  std::int64_t steps = 0;
  int threads = 1;
  std::int64_t snapshots = 0;                   // written by the run, the first and last included
  std::uint64_t snapshot_values_per_point = 0;  // the components of its output fields
  // Pore fluid: the flow-rate evaluations per step (explicit substeps or RKL2 stages; 1 / N for an
  // update every N steps).
  double flow_evaluations_per_step = 0.0;
};

struct RunCostEstimate {
  double seconds_per_bond_update = 0.0;  // one thread
  double thread_speed_up = 1.0;          // of `threads` over one
  double seconds_per_step = 0.0;
  double start_up_seconds = 0.0;  // loading, reading, families, critical step, first snapshot
  double snapshot_seconds = 0.0;  // of one snapshot (its fields computed, checksummed and written)
  double loop_seconds = 0.0;      // the steps and the snapshots
  double total_seconds = 0.0;
};

RunCostEstimate estimate_run_cost(const RunCostInput& input);

}  // namespace mppm
