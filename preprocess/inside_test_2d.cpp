// 2-D inside test: rows of the lattice against the boundary segments (see inside_test.hpp).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

#include "preprocess/inside_test.hpp"

namespace mppm::pre {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
}  // namespace

std::vector<std::uint8_t> classify_inside(const LatticeGrid& grid, const FacetMesh& boundary) {
  return grid.dimension == 2 ? classify_inside_2d(grid, boundary) : classify_inside_3d(grid, boundary);
}

std::vector<std::uint8_t> classify_inside_2d(const LatticeGrid& grid, const FacetMesh& boundary) {
  const std::int64_t nx = grid.count[0], ny = grid.count[1];
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(grid.size()), 0);

  // Bucket the segments by the rows their closed y range may touch (one row of slack on each
  // side against round-off in the row index; the exact tests below decide).
  std::vector<std::int64_t> row_start(static_cast<std::size_t>(ny) + 1, 0);
  std::vector<std::pair<std::int64_t, std::int64_t>> rows_of(boundary.facet_count());
  for (std::size_t s = 0; s < boundary.facet_count(); ++s) {
    const double y0 = boundary.vertex(s, 0)[1], y1 = boundary.vertex(s, 1)[1];
    const double lo = (std::min(y0, y1) - grid.origin[1]) / grid.spacing;
    const double hi = (std::max(y0, y1) - grid.origin[1]) / grid.spacing;
    const std::int64_t first = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(lo)) - 1);
    const std::int64_t last = std::min<std::int64_t>(ny - 1, static_cast<std::int64_t>(std::floor(hi)) + 1);
    rows_of[s] = {first, last};
    for (std::int64_t j = first; j <= last; ++j) ++row_start[static_cast<std::size_t>(j) + 1];
  }
  for (std::int64_t j = 0; j < ny; ++j) row_start[j + 1] += row_start[j];
  std::vector<std::int64_t> fill(row_start.begin(), row_start.end() - 1);
  std::vector<std::int64_t> row_segments(static_cast<std::size_t>(row_start[ny]));
  for (std::size_t s = 0; s < boundary.facet_count(); ++s)
    for (std::int64_t j = rows_of[s].first; j <= rows_of[s].second; ++j)
      row_segments[static_cast<std::size_t>(fill[j]++)] = static_cast<std::int64_t>(s);

#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t j = 0; j < ny; ++j) {
    const double y = grid.coordinate(1, j);
    struct Crossing {
      Point2 low, high;  // segment oriented upwards
      double xmin, xmax;
    };
    std::vector<Crossing> crossings;
    std::vector<std::pair<Point2, Point2>> touching;  // end point on the row, or along it
    for (std::int64_t r = row_start[j]; r < row_start[j + 1]; ++r) {
      const auto s = static_cast<std::size_t>(row_segments[r]);
      const Vec3 &a = boundary.vertex(s, 0), &b = boundary.vertex(s, 1);
      const Point2 pa(a[0], a[1]), pb(b[0], b[1]);
      if ((a[1] > y) != (b[1] > y)) {  // crosses the row moved up by eps
        crossings.push_back({a[1] < b[1] ? pa : pb, a[1] < b[1] ? pb : pa, std::min(a[0], b[0]), std::max(a[0], b[0])});
      } else if (std::min(a[1], b[1]) <= y && y <= std::max(a[1], b[1])) {
        touching.push_back({pa, pb});
      }
    }
    for (std::int64_t i = 0; i < nx; ++i) {
      const double x = grid.coordinate(0, i);
      const Point2 p(x, y);
      bool on_boundary = false;
      int after = 0;
      for (const Crossing& c : crossings) {
        if (x < c.xmin) {
          ++after;
        } else if (x <= c.xmax) {
          const CGAL::Orientation o = CGAL::orientation(c.low, c.high, p);
          if (o == CGAL::LEFT_TURN) ++after;  // p left of an upward segment: crossing is beyond p
          if (o == CGAL::COLLINEAR) on_boundary = true;
        }
      }
      for (const auto& [a, b] : touching)
        if (!on_boundary && x >= std::min(a.x(), b.x()) && x <= std::max(a.x(), b.x()))
          on_boundary = CGAL::collinear(a, b, p);
      inside[static_cast<std::size_t>(grid.index(i, j, 0))] = on_boundary || (after % 2 == 1);
    }
  }
  return inside;
}

}  // namespace mppm::pre
