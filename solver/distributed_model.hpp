// A distributed run's model on this process, with what it rests on (docs/theory.md section 13): the
// partition of the whole cloud, this process's local points, and the halo exchange its ghosts come
// from (held here, at a fixed address, for the model's points to point at).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "solver/halo_exchange.hpp"
#include "solver/local_points.hpp"
#include "solver/model.hpp"
#include "solver/partition_summary.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

struct DistributedModel {
  std::vector<std::int32_t> part;  // of every point of the cloud
  LocalPoints local;
  std::unique_ptr<HaloExchange> halo;
  Model model;
};

// Collective: every process of `group` calls it with the same cloud and options. The group must
// outlive the model (its sums go through it).
DistributedModel build_distributed_model(const PointCloud& cloud, const ModelOptions& options,
                                         const ProcessGroup& group);

// Collective: the summary of this run's partition, the same on every process.
PartitionSummary summarize_partition(const Model& model, const ProcessGroup& group);

}  // namespace mppm::solver
