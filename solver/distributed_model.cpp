// A distributed run's model on this process (distributed_model.hpp).
#include "solver/distributed_model.hpp"

#include "solver/horizon_search.hpp"

namespace mppm::solver {

DistributedModel build_distributed_model(const PointCloud& cloud, const ModelOptions& options,
                                         const ProcessGroup& group) {
  const double reach = bond_reach(options.horizon, options.spacing);
  DistributedModel d;
  d.part = partition_cloud(cloud, reach, group.size());
  d.local = local_points(cloud, d.part, group.rank(), reach);
  d.halo = std::make_unique<HaloExchange>(d.local, d.part);
  d.model = build_local_model(cloud, d.local, *d.halo, group, options);
  return d;
}

}  // namespace mppm::solver
