// Distance test against the boundary points through a bucket grid (cell = margin).
#include "postprocess/boundary_layer_mask.hpp"

#include <cstddef>

#include "postprocess/point_grid.hpp"

namespace mppm::post {

std::vector<char> points_away_from_boundaries(const std::vector<double>& x, const std::vector<double>& y,
                                              const std::vector<double>& z, const std::vector<int>& region,
                                              const std::vector<int>& boundary_id, double margin) {
  const std::size_t n = x.size();
  std::vector<std::size_t> boundary;
  for (std::size_t i = 0; i < n; ++i)
    if (region[i] != 0 || boundary_id[i] != 0) boundary.push_back(i);
  std::vector<char> away(n, 0);
  if (!(margin > 0)) {
    for (std::size_t i = 0; i < n; ++i) away[i] = region[i] == 0 && boundary_id[i] == 0;
    return away;
  }
  PointGrid grid(x, y, z, boundary, margin);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (region[i] != 0 || boundary_id[i] != 0) continue;
    bool near = false;
    grid.for_each_within(x[i], y[i], z[i], margin, [&](std::size_t) { near = true; });
    away[i] = near ? 0 : 1;
  }
  return away;
}

}  // namespace mppm::post
