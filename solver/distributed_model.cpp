// A distributed run's model on this process (distributed_model.hpp).
#include "solver/distributed_model.hpp"

#include <algorithm>
#include <numeric>

#include "solver/horizon_search.hpp"

namespace mppm::solver {

DistributedModel build_distributed_model(const PointCloud& cloud, const ModelOptions& options,
                                         const ProcessGroup& group) {
  const double reach = bond_reach(options.horizon, options.spacing);
  DistributedModel d;
  const std::vector<double> x = cloud_positions(cloud);
  const PointPositions positions{cloud.dimension, x.data(), cloud.size()};
  d.part = partition_cloud(positions, reach, group.size());
  d.local = local_points(positions, d.part, group.rank(), reach);
  d.halo = std::make_unique<HaloExchange>(d.local, d.part);
  d.model = build_local_model(cloud, d.local, *d.halo, group, options);
  return d;
}

PartitionSummary summarize_partition(const Model& model, const ProcessGroup& group) {
  PartitionSummary s;
  s.points = group.gather(static_cast<std::int64_t>(model.points.owned));
  s.ghosts = group.gather(static_cast<std::int64_t>(model.points.ghost));
  s.bonds = group.gather(static_cast<std::int64_t>(model.bonds.bond_count()));
  const std::int64_t total = std::accumulate(s.bonds.begin(), s.bonds.end(), std::int64_t{0});
  if (total > 0)
    s.imbalance = static_cast<double>(*std::max_element(s.bonds.begin(), s.bonds.end())) *
                  static_cast<double>(s.bonds.size()) / static_cast<double>(total);
  return s;
}

}  // namespace mppm::solver
