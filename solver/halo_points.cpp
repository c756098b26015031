// The ghosts of a part (halo_points.hpp).
#include "solver/halo_points.hpp"

#include <stdexcept>

namespace mppm::solver {

std::vector<std::size_t> halo_points(const PointPositions& points, std::span<const std::int32_t> part_of,
                                     std::int32_t part, double reach, double spacing) {
  if (part_of.size() != points.count) throw std::invalid_argument("halo_points: one part per point expected");
  const NeighbourSearch search(points, reach, spacing);
  std::vector<char> ghost(points.count, 0);
  for (std::size_t i = 0; i < points.count; ++i) {
    if (part_of[i] != part) continue;
    search.for_each(i, [&](std::size_t j, const double*) {
      if (part_of[j] != part) ghost[j] = 1;
    });
  }
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < points.count; ++j)
    if (ghost[j]) out.push_back(j);
  return out;
}

}  // namespace mppm::solver
