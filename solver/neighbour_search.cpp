// The search for the points within the reach (neighbour_search.hpp).
#include "solver/neighbour_search.hpp"

namespace mppm::solver {

NeighbourSearch::NeighbourSearch(const PointPositions& points, double reach, double spacing,
                                 const std::array<double, 3>& period)
    : points_(points),
      reach2_(reach * reach),
      period_(period),
      periodic_(period[0] > 0.0 || period[1] > 0.0 || period[2] > 0.0) {
  if (!periodic_) lattice_ = lattice_sites(points, spacing, reach);
  if (!periodic_ && !lattice_) grid_ = make_grid(points, reach);
}

std::vector<std::int64_t> bond_counts(const PointPositions& points, double reach, double spacing) {
  const NeighbourSearch search(points, reach, spacing);
  std::vector<std::int64_t> count(points.count, 0);
  const auto n = static_cast<std::int64_t>(points.count);
#pragma omp parallel for schedule(static)
  for (std::int64_t s = 0; s < n; ++s)
    search.for_each(static_cast<std::size_t>(s),
                    [&](std::size_t, const double*) { ++count[static_cast<std::size_t>(s)]; });
  return count;
}

}  // namespace mppm::solver
