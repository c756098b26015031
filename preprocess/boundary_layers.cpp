// Layer assignment by scattering each selected facet onto the lattice points of its bounding box
// grown by the layer depth (see boundary_layers.hpp).
#include "preprocess/boundary_layers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "preprocess/facet_distance.hpp"

namespace mppm::pre {
namespace {

// Lattice index ranges of the facet's bounding box grown by `reach`; false if empty.
bool lattice_range_near_facet(const LatticeGrid& grid, const FacetMesh& boundary, std::size_t f, double reach,
                              std::array<std::int64_t, 3>& first, std::array<std::int64_t, 3>& last) {
  const int d = grid.dimension;
  first = {0, 0, 0};
  last = {0, 0, 0};
  for (int a = 0; a < d; ++a) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (int c = 0; c < d; ++c) {
      lo = std::min(lo, boundary.vertex(f, c)[a]);
      hi = std::max(hi, boundary.vertex(f, c)[a]);
    }
    first[a] =
        std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil((lo - reach - grid.origin[a]) / grid.spacing)));
    last[a] = std::min<std::int64_t>(
        grid.count[a] - 1, static_cast<std::int64_t>(std::floor((hi + reach - grid.origin[a]) / grid.spacing)));
    if (first[a] > last[a]) return false;
  }
  return true;
}

}  // namespace

LayerTags assign_layers(const LatticeGrid& grid, const std::vector<std::uint8_t>& inside, const FacetMesh& boundary,
                        const std::vector<LayerRequest>& requests, bool inside_side) {
  const auto n = static_cast<std::size_t>(grid.size());
  LayerTags tags;
  tags.boundary.assign(n, 0);
  tags.facet.assign(n, -1);
  tags.distance.assign(n, std::numeric_limits<double>::infinity());
  // Lattice points exactly at the depth belong to the layer (like family members exactly on
  // the horizon sphere, docs/theory.md section 1).
  const double slack = 1e-9 * grid.spacing;
  const int d = grid.dimension;
  for (const LayerRequest& request : requests) {
    const double reach = request.depth + slack;
    for (std::size_t f : request.facets) {
      std::array<std::int64_t, 3> first{0, 0, 0}, last{0, 0, 0};
      if (!lattice_range_near_facet(grid, boundary, f, reach, first, last)) continue;
      for (std::int64_t k = first[2]; k <= last[2]; ++k)
        for (std::int64_t j = first[1]; j <= last[1]; ++j)
          for (std::int64_t i = first[0]; i <= last[0]; ++i) {
            const auto index = static_cast<std::size_t>(grid.index(i, j, k));
            if ((inside[index] != 0) != inside_side) continue;
            const Vec3 p{grid.coordinate(0, i), grid.coordinate(1, j), d == 2 ? 0.0 : grid.coordinate(2, k)};
            const double dist = distance(p, closest_point_on_facet(boundary, f, p));
            if (dist <= reach && dist < tags.distance[index]) {
              tags.distance[index] = dist;
              tags.boundary[index] = request.boundary;
              tags.facet[index] = static_cast<std::int32_t>(f);
            }
          }
    }
  }
  return tags;
}

void drop_points_nearer_to_other_facets(LayerTags& tags, const LatticeGrid& grid, const FacetMesh& boundary,
                                        double reach) {
  const double slack = 1e-9 * grid.spacing;
  const int d = grid.dimension;
  std::vector<std::uint8_t> drop(tags.boundary.size(), 0);
  for (std::size_t f = 0; f < boundary.facet_count(); ++f) {
    std::array<std::int64_t, 3> first{}, last{};
    if (!lattice_range_near_facet(grid, boundary, f, reach + slack, first, last)) continue;
    for (std::int64_t k = first[2]; k <= last[2]; ++k)
      for (std::int64_t j = first[1]; j <= last[1]; ++j)
        for (std::int64_t i = first[0]; i <= last[0]; ++i) {
          const auto index = static_cast<std::size_t>(grid.index(i, j, k));
          if (tags.boundary[index] == 0 || drop[index]) continue;
          const Vec3 p{grid.coordinate(0, i), grid.coordinate(1, j), d == 2 ? 0.0 : grid.coordinate(2, k)};
          if (distance(p, closest_point_on_facet(boundary, f, p)) < tags.distance[index] - slack) drop[index] = 1;
        }
  }
  for (std::size_t index = 0; index < drop.size(); ++index)
    if (drop[index]) {
      tags.boundary[index] = 0;
      tags.facet[index] = -1;
      tags.distance[index] = std::numeric_limits<double>::infinity();
    }
}

}  // namespace mppm::pre
