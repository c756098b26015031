// The cell grid of the horizon search (horizon_search.hpp).
#include "solver/horizon_search.hpp"

#include <cmath>
#include <numeric>

namespace mppm::solver {

CellGrid make_grid(const PointPositions& points, double size) {
  CellGrid g;
  const int D = points.dimension;
  const double* x = points.position;
  g.dimension = D;
  g.size = size;
  const std::size_t n = points.count;
  std::array<double, 3> high{0, 0, 0};
  for (int a = 0; a < D; ++a) {
    g.low[a] = n ? x[a] : 0.0;
    high[a] = g.low[a];
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a) {
      g.low[a] = std::min(g.low[a], x[i * D + a]);
      high[a] = std::max(high[a], x[i * D + a]);
    }
  // Cells larger than asked where cells of `size` would outnumber the points many times over (a
  // sparse cloud, or a small reach over a large box): any size of at least the reach finds the
  // same points, and the grid's memory stays of the order of the points'.
  const double most_cells = 8.0 * static_cast<double>(n) + 1024.0;
  for (;;) {
    double cells = 1.0;
    for (int a = 0; a < D; ++a) cells *= std::floor((high[a] - g.low[a]) / g.size) + 1.0;
    if (cells <= most_cells) break;
    g.size *= 2.0;
  }
  for (int a = 0; a < D; ++a)
    g.cells[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>((high[a] - g.low[a]) / g.size) + 1);
  const std::int64_t total = g.cells[0] * g.cells[1] * g.cells[2];
  std::vector<std::int64_t> cell_of_point(n);
  g.start.assign(static_cast<std::size_t>(total) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    cell_of_point[i] = g.linear(g.cell_of(&x[i * D]));
    ++g.start[cell_of_point[i] + 1];
  }
  std::partial_sum(g.start.begin(), g.start.end(), g.start.begin());
  g.points.resize(n);
  std::vector<std::int64_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) g.points[fill[cell_of_point[i]]++] = static_cast<std::int32_t>(i);
  return g;
}

}  // namespace mppm::solver
