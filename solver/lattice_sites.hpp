// Points that lie on one regular lattice, found by index arithmetic instead of a cell search: the
// preprocessor's lattices (docs/theory.md section 1), whose families are then visited as offsets
// from a point's site. for_each_on_lattice visits exactly the points for_each_in_horizon visits
// (horizon_search.hpp): it applies the same test to the same coordinates, only to fewer candidates.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "solver/horizon_search.hpp"

namespace mppm::solver {

struct LatticeSites {
  int dimension = 2;
  double spacing = 1.0;
  std::array<double, 3> low{0, 0, 0};          // the site (0, 0, 0)
  std::array<std::int64_t, 3> sites{1, 1, 1};  // along each axis
  std::vector<std::int32_t> point_at;          // site -> point index, -1 where there is none
  std::vector<std::array<int, 3>> candidates;  // offsets that can hold a point within the reach

  std::array<std::int64_t, 3> site_of(const double* x) const {
    std::array<std::int64_t, 3> k{0, 0, 0};
    for (int a = 0; a < dimension; ++a) k[a] = std::llround((x[a] - low[a]) / spacing);
    return k;
  }
};

// The site map of `points` if every point lies within a hundredth of a spacing of a site of one
// lattice of that spacing, no two on one site, and the lattice's box holds at most 16 sites per
// point (a sparse body is searched by cells instead); the candidate offsets reach `reach`.
std::optional<LatticeSites> lattice_sites(const PointPositions& points, double spacing, double reach);

// for_each_in_horizon without periods, over the candidate offsets of point i's site: the visits
// are those of the cell search (the test and xi are computed as there), in another order.
template <class Visit>
void for_each_on_lattice(const PointPositions& points, const LatticeSites& lattice, std::size_t i, double reach2,
                         Visit&& visit) {
  const int D = points.dimension;
  const double* x = points.position;
  const double* xi_pos = &x[i * D];
  const auto k = lattice.site_of(xi_pos);
  double xi[3];
  for (const auto& o : lattice.candidates) {
    std::int64_t site = 0;
    bool inside = true;
    for (int a = D - 1; a >= 0; --a) {
      const std::int64_t c = k[a] + o[a];
      inside = inside && c >= 0 && c < lattice.sites[a];
      site = site * lattice.sites[a] + c;
    }
    if (!inside) continue;
    const std::int32_t j = lattice.point_at[static_cast<std::size_t>(site)];
    if (j < 0) continue;
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      const double d = x[static_cast<std::size_t>(j) * D + a] - xi_pos[a];
      xi[a] = d;
      r2 += d * d;
    }
    if (r2 <= reach2) visit(static_cast<std::size_t>(j), xi);
  }
}

}  // namespace mppm::solver
