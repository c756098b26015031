// A distributed run's model on this process (distributed_model.hpp).
#include "solver/distributed_model.hpp"

#include <algorithm>
#include <numeric>

#include "solver/horizon_search.hpp"

namespace mppm::solver {

namespace {

// The return map's cost per point and step in bond entries' (docs/theory.md section 13), from the
// plate lattice of workflows/benchmarks/results.md on one thread (elastic trial states): a point
// inside material.viscoplasticity.region about 37 (251 ns against 6.9 ns per bond entry), one
// outside about 10 (69 ns: the viscoplastic kernel's own bookkeeping).
constexpr std::int64_t kReturnMapWeight = 37, kOutsideRegionWeight = 10;

// Every point's weight beyond its bonds: none without viscoplasticity.
std::vector<std::int64_t> return_map_weights(const PointPositions& x, const ModelOptions& o) {
  if (!o.effects.viscoplasticity) return {};
  std::vector<std::int64_t> weight(x.count, kReturnMapWeight);
  if (!o.plastic_region) return weight;
  const auto D = static_cast<std::size_t>(x.dimension);
  for (std::size_t i = 0; i < x.count; ++i)
    if (!inside_box(x.position + i * D, x.dimension, *o.plastic_region)) weight[i] = kOutsideRegionWeight;
  return weight;
}

}  // namespace

DistributedModel build_distributed_model(const PointCloud& cloud, const ModelOptions& options,
                                         const ProcessGroup& group) {
  const double reach = bond_reach(options.horizon, options.spacing);
  DistributedModel d;
  const std::vector<double> x = cloud_positions(cloud);
  const PointPositions positions{cloud.dimension, x.data(), cloud.size()};
  d.part = partition_cloud(positions, reach, options.spacing, group.size(), return_map_weights(positions, options));
  d.local = local_points(positions, d.part, group.rank(), reach, options.spacing);
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
