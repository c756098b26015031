// Which points lie within the reach of a point: on the sites of the points' lattice when they lie
// on one (lattice_sites.hpp: a few dozen candidate offsets per point), else in the cell grid of
// horizon_search.hpp (with periods: every point, by minimum images). Both apply the same test to the
// same coordinates, so every user (the families, the partition's weights, a part's ghosts) finds the
// same points whichever way it searches.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "solver/horizon_search.hpp"
#include "solver/lattice_sites.hpp"

namespace mppm::solver {

class NeighbourSearch {
 public:
  // `spacing`: the lattice spacing the points may lie on (0: search by cells); `period`: see
  // FamilyOptions (bond_families.hpp).
  NeighbourSearch(const PointPositions& points, double reach, double spacing,
                  const std::array<double, 3>& period = {0.0, 0.0, 0.0});

  // visit(j, xi) for every point j != i within the reach, xi = x_j - x_i (minimum image), in an
  // order that depends on the search (callers sort what they keep).
  template <class Visit>
  void for_each(std::size_t i, Visit&& visit) const {
    if (lattice_)
      for_each_on_lattice(points_, *lattice_, i, reach2_, visit);
    else
      for_each_in_horizon(points_, periodic_ ? nullptr : &grid_, period_, i, reach2_, visit);
  }

  bool on_lattice() const { return lattice_.has_value(); }

 private:
  PointPositions points_;
  double reach2_;
  std::array<double, 3> period_;
  bool periodic_;
  std::optional<LatticeSites> lattice_;
  CellGrid grid_;
};

// The number of points within `reach` of each point (its bonds before any cut): the weights of
// the partition (coordinate_bisection.hpp).
std::vector<std::int64_t> bond_counts(const PointPositions& points, double reach, double spacing);

}  // namespace mppm::solver
