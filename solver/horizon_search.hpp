// Which points lie within the horizon of a point: a uniform cell grid of the horizon's size over
// the points' positions, searched in the 3^D cells around a point. One test decides it everywhere
// (here and on a lattice's sites, lattice_sites.hpp; neighbour_search.hpp chooses), so that the
// families and the ghosts a process needs from the others find the same points to the last bit.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mppm::solver {

// Positions of `count` points, `dimension` coordinates each.
struct PointPositions {
  int dimension = 2;
  const double* position = nullptr;
  std::size_t count = 0;
};

// The distance within which two points are bonded: the horizon and a tolerance of 1e-9 spacings,
// which keeps the lattice points that lie on the horizon's sphere in the family whatever the
// rounding of their coordinates.
inline double bond_reach(double horizon, double spacing) { return horizon + 1e-9 * spacing; }

struct CellGrid {
  int dimension = 2;
  std::array<double, 3> low{0, 0, 0};
  double size = 1.0;
  std::array<std::int64_t, 3> cells{1, 1, 1};
  std::vector<std::int64_t> start;   // cell -> first entry in `points`
  std::vector<std::int32_t> points;  // point indices sorted by cell

  std::array<std::int64_t, 3> cell_of(const double* x) const {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int a = 0; a < dimension; ++a)
      c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x[a] - low[a]) / size)), 0, cells[a] - 1);
    return c;
  }
  std::int64_t linear(const std::array<std::int64_t, 3>& c) const { return (c[2] * cells[1] + c[1]) * cells[0] + c[0]; }
};

// The grid of cells of edge `size` (at least the search reach) over all the points, or of a
// larger edge where those would number more than 8 per point (plus 1024).
CellGrid make_grid(const PointPositions& points, double size);

// Visits the points j != i with |x_j - x_i| <= sqrt(reach2), in any order: visit(j, xi) with
// xi = x_j - x_i, wrapped to the minimum image along the axes with a period (then without a grid:
// grid == nullptr searches every point).
template <class Visit>
void for_each_in_horizon(const PointPositions& points, const CellGrid* grid, const std::array<double, 3>& period,
                         std::size_t i, double reach2, Visit&& visit) {
  const int D = points.dimension;
  const double* x = points.position;
  const double* xi_pos = &x[i * D];
  double xi[3];
  auto consider = [&](std::size_t j) {
    if (j == i) return;
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      double d = x[j * D + a] - xi_pos[a];
      if (period[a] > 0.0) d -= period[a] * std::nearbyint(d / period[a]);
      xi[a] = d;
      r2 += d * d;
    }
    if (r2 <= reach2) visit(j, xi);
  };
  if (!grid) {
    for (std::size_t j = 0; j < points.count; ++j) consider(j);
    return;
  }
  const auto c = grid->cell_of(xi_pos);
  std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int a = 0; a < D; ++a) {
    lo[a] = std::max<std::int64_t>(0, c[a] - 1);
    hi[a] = std::min<std::int64_t>(grid->cells[a] - 1, c[a] + 1);
  }
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t xc = lo[0]; xc <= hi[0]; ++xc) {
        const std::int64_t cell = grid->linear({xc, y, z});
        for (std::int64_t k = grid->start[cell]; k < grid->start[cell + 1]; ++k)
          consider(static_cast<std::size_t>(grid->points[k]));
      }
}

// Whether some point j of `points`, gridded in `grid` (cells of at least sqrt(below2)), lies at a
// squared distance |x - x_j|^2 below `below2` from x, which need not be one of them nor lie in the
// grid's box (its cell is clamped to the box, and the grid's points within reach of it lie in the
// 3^D cells around that one). The squared distance is summed over the axes in order.
inline bool any_point_nearer(const PointPositions& points, const CellGrid& grid, const double* x, double below2) {
  const int D = points.dimension;
  const auto c = grid.cell_of(x);
  std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int a = 0; a < D; ++a) {
    lo[a] = std::max<std::int64_t>(0, c[a] - 1);
    hi[a] = std::min<std::int64_t>(grid.cells[a] - 1, c[a] + 1);
  }
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t xc = lo[0]; xc <= hi[0]; ++xc) {
        const std::int64_t cell = grid.linear({xc, y, z});
        for (std::int64_t k = grid.start[cell]; k < grid.start[cell + 1]; ++k) {
          const double* xj = &points.position[static_cast<std::size_t>(grid.points[k]) * D];
          double r2 = 0.0;
          for (int a = 0; a < D; ++a) r2 += (x[a] - xj[a]) * (x[a] - xj[a]);
          if (r2 < below2) return true;
        }
      }
  return false;
}

}  // namespace mppm::solver
