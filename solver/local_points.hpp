// The points one process of a distributed run holds (docs/theory.md section 13): the points of its
// part, then its ghosts (halo_points.hpp), each in ascending global id (the index in the points
// file), and their point data with the global ids.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/horizon_search.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// The part (process) of every point among `parts`: coordinate bisection weighted by each
// point's bonds within `reach` (bond_reach; `spacing` the lattice's, neighbour_search.hpp), plus its
// `extra_weight` when given (one per point: the return map's cost), ties by the index in the points
// file (coordinate_bisection.hpp).
std::vector<std::int32_t> partition_cloud(const PointPositions& points, double reach, double spacing, int parts,
                                          std::span<const std::int64_t> extra_weight = {});

struct LocalPoints {
  std::vector<std::int64_t> global_id;  // of each local point: owned, then ghosts
  std::size_t owned = 0;
};

// The local points of `part` among all the points' parts, with the ghosts within `reach` (bond_reach;
// `spacing` the lattice's, neighbour_search.hpp).
LocalPoints local_points(const PointPositions& points, std::span<const std::int32_t> part_of, std::int32_t part,
                         double reach, double spacing);

// The cloud of the local points, in their local order; its pre-cracks and boundary descriptions are
// the whole cloud's.
PointCloud local_cloud(const PointCloud& cloud, const LocalPoints& local);

// The point data of the local points: owned first, ghosts after, with their global ids.
PointData make_local_point_data(const PointCloud& cloud, const LocalPoints& local, const EffectSet& effects);

}  // namespace mppm::solver
