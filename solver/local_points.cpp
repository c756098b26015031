// The points one process holds (local_points.hpp).
#include "solver/local_points.hpp"

#include <numeric>
#include <stdexcept>

#include "solver/coordinate_bisection.hpp"
#include "solver/halo_points.hpp"
#include "solver/neighbour_search.hpp"

namespace mppm::solver {

std::vector<std::int32_t> partition_cloud(const PointPositions& points, double reach, double spacing, int parts,
                                          std::span<const std::int64_t> extra_weight) {
  std::vector<std::int64_t> id(points.count);
  std::iota(id.begin(), id.end(), std::int64_t{0});
  const std::span<const double> x(points.position, points.count * static_cast<std::size_t>(points.dimension));
  std::vector<std::int64_t> weight = bond_counts(points, reach, spacing);
  if (!extra_weight.empty()) {
    if (extra_weight.size() != points.count)
      throw std::invalid_argument("partition_cloud: one extra weight per point expected");
    for (std::size_t i = 0; i < points.count; ++i) weight[i] += extra_weight[i];
  }
  return coordinate_bisection({points.dimension, x, weight, id}, parts);
}

LocalPoints local_points(const PointPositions& points, std::span<const std::int32_t> part_of, std::int32_t part,
                         double reach, double spacing) {
  if (part_of.size() != points.count) throw std::invalid_argument("local_points: one part per point expected");
  LocalPoints local;
  for (std::size_t i = 0; i < points.count; ++i)
    if (part_of[i] == part) local.global_id.push_back(static_cast<std::int64_t>(i));
  local.owned = local.global_id.size();
  for (const std::size_t j : halo_points(points, part_of, part, reach, spacing))
    local.global_id.push_back(static_cast<std::int64_t>(j));
  return local;
}

namespace {

template <class T>
std::vector<T> pick(const std::vector<T>& all, const std::vector<std::int64_t>& index) {
  if (all.empty()) return {};
  std::vector<T> out(index.size());
  for (std::size_t k = 0; k < index.size(); ++k) out[k] = all[static_cast<std::size_t>(index[k])];
  return out;
}

}  // namespace

PointCloud local_cloud(const PointCloud& cloud, const LocalPoints& local) {
  PointCloud c;
  c.dimension = cloud.dimension;
  c.spacing = cloud.spacing;
  c.horizon = cloud.horizon;
  c.thickness = cloud.thickness;
  c.boundaries = cloud.boundaries;
  c.precrack_vertices = cloud.precrack_vertices;
  const auto& id = local.global_id;
  c.x = pick(cloud.x, id);
  c.y = pick(cloud.y, id);
  c.z = pick(cloud.z, id);
  c.volume = pick(cloud.volume, id);
  c.region = pick(cloud.region, id);
  c.boundary_id = pick(cloud.boundary_id, id);
  c.normal_x = pick(cloud.normal_x, id);
  c.normal_y = pick(cloud.normal_y, id);
  c.normal_z = pick(cloud.normal_z, id);
  return c;
}

PointData make_local_point_data(const PointCloud& cloud, const LocalPoints& local, const EffectSet& effects) {
  PointData p = make_point_data(local_cloud(cloud, local), effects);
  p.owned = local.owned;
  p.ghost = local.global_id.size() - local.owned;
  p.global_id = local.global_id;
  return p;
}

}  // namespace mppm::solver
