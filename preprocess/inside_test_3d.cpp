// 3-D inside test: lattice lines along x against the boundary triangles (see inside_test.hpp).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

#include "preprocess/inside_test.hpp"

namespace mppm::pre {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;  // (y, z) of a projected vertex
using Point3 = Kernel::Point_3;

// Sign of orient2d(u, v, q + (eps, eps^2)) when orient2d(u, v, q) == 0 and u != v:
// the eps term -(v_z - u_z) dominates, the eps^2 term (v_y - u_y) breaks the remaining tie.
bool perturbed_left(const Point2& u, const Point2& v) {
  if (v.y() != u.y()) return v.y() < u.y();
  return v.x() > u.x();
}

enum class LineHit { none, crosses, touches };

// Does the line through q (along x) cross the triangle once moved by (eps, eps^2)? If not,
// does the unmoved line still touch the closed projected triangle (a lattice point on the line
// may then lie on the facet)?
LineHit line_hits_triangle(const Point2& a, const Point2& b, const Point2& c, const Point2& q) {
  const CGAL::Orientation area = CGAL::orientation(a, b, c);
  if (area == CGAL::COLLINEAR) {  // facet parallel to x: only touching is possible
    const Kernel::Segment_2 edges[3] = {{a, b}, {b, c}, {c, a}};
    for (const auto& e : edges)
      if (!e.is_degenerate() && e.has_on(q)) return LineHit::touches;
    return LineHit::none;
  }
  const Point2* ccw[3] = {&a, area == CGAL::LEFT_TURN ? &b : &c, area == CGAL::LEFT_TURN ? &c : &b};
  bool perturbed_inside = true;
  for (int e = 0; e < 3; ++e) {
    const Point2& u = *ccw[e];
    const Point2& v = *ccw[(e + 1) % 3];
    const CGAL::Orientation o = CGAL::orientation(u, v, q);
    if (o == CGAL::RIGHT_TURN) return LineHit::none;
    if (o == CGAL::COLLINEAR && !perturbed_left(u, v)) perturbed_inside = false;
  }
  if (perturbed_inside) return LineHit::crosses;
  return LineHit::touches;  // on an edge or vertex of the closed projection
}

}  // namespace

std::vector<std::uint8_t> classify_inside_3d(const LatticeGrid& grid, const FacetMesh& boundary) {
  const std::int64_t nx = grid.count[0], ny = grid.count[1], nz = grid.count[2];
  const std::int64_t lines = ny * nz;
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(grid.size()), 0);

  // Scatter every triangle to the lattice lines its projection may contain (one line of slack
  // each side); the exact test decides. Two passes (count, fill) in triangle order, so the
  // per-line lists are the same for any thread count.
  struct Hit {
    std::int64_t line;
    std::int32_t facet;
    bool crosses;
  };
  std::vector<Hit> hits;
  for (std::size_t t = 0; t < boundary.facet_count(); ++t) {
    const Vec3 &a = boundary.vertex(t, 0), &b = boundary.vertex(t, 1), &c = boundary.vertex(t, 2);
    const auto range = [&](int axis, std::int64_t n) {
      const double lo = (std::min({a[axis], b[axis], c[axis]}) - grid.origin[axis]) / grid.spacing;
      const double hi = (std::max({a[axis], b[axis], c[axis]}) - grid.origin[axis]) / grid.spacing;
      return std::pair<std::int64_t, std::int64_t>{
          std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(lo)) - 1),
          std::min<std::int64_t>(n - 1, static_cast<std::int64_t>(std::floor(hi)) + 1)};
    };
    const auto [j0, j1] = range(1, ny);
    const auto [k0, k1] = range(2, nz);
    const Point2 pa(a[1], a[2]), pb(b[1], b[2]), pc(c[1], c[2]);
    for (std::int64_t k = k0; k <= k1; ++k)
      for (std::int64_t j = j0; j <= j1; ++j) {
        const Point2 q(grid.coordinate(1, j), grid.coordinate(2, k));
        const LineHit hit = line_hits_triangle(pa, pb, pc, q);
        if (hit != LineHit::none) hits.push_back({k * ny + j, static_cast<std::int32_t>(t), hit == LineHit::crosses});
      }
  }
  std::stable_sort(hits.begin(), hits.end(), [](const Hit& l, const Hit& r) { return l.line < r.line; });
  std::vector<std::int64_t> line_start(static_cast<std::size_t>(lines) + 1, 0);
  for (const Hit& h : hits) ++line_start[static_cast<std::size_t>(h.line) + 1];
  for (std::int64_t l = 0; l < lines; ++l) line_start[l + 1] += line_start[l];

#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t line = 0; line < lines; ++line) {
    if (line_start[line] == line_start[line + 1]) continue;
    const std::int64_t j = line % ny, k = line / ny;
    const double y = grid.coordinate(1, j), z = grid.coordinate(2, k);
    for (std::int64_t i = 0; i < nx; ++i) {
      const double x = grid.coordinate(0, i);
      const Point3 p(x, y, z);
      bool on_boundary = false;
      int after = 0;
      for (std::int64_t h = line_start[line]; h < line_start[line + 1] && !on_boundary; ++h) {
        const Hit& hit = hits[static_cast<std::size_t>(h)];
        const Vec3 &a = boundary.vertex(hit.facet, 0), &b = boundary.vertex(hit.facet, 1),
                   &c = boundary.vertex(hit.facet, 2);
        const double xmin = std::min({a[0], b[0], c[0]}), xmax = std::max({a[0], b[0], c[0]});
        if (hit.crosses) {
          if (x < xmin) {
            ++after;
          } else if (x <= xmax) {
            // Side of p against the facet plane, exactly; the projected orientation tells which
            // side is "before the crossing" along +x.
            const Point3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]), pc(c[0], c[1], c[2]);
            const CGAL::Orientation side = CGAL::orientation(pa, pb, pc, p);
            const CGAL::Orientation facing =
                CGAL::orientation(Point2(a[1], a[2]), Point2(b[1], b[2]), Point2(c[1], c[2]));
            if (side == CGAL::COPLANAR)
              on_boundary = true;
            else if (side != facing)
              ++after;  // sign(n . (p - a)) = sign(n_x (x - x_cross)): p before the crossing
          }
        } else if (x >= xmin && x <= xmax) {
          const Kernel::Triangle_3 facet(Point3(a[0], a[1], a[2]), Point3(b[0], b[1], b[2]), Point3(c[0], c[1], c[2]));
          if (!facet.is_degenerate() && facet.has_on(p)) on_boundary = true;
        }
      }
      inside[static_cast<std::size_t>(grid.index(i, j, k))] = on_boundary || (after % 2 == 1);
    }
  }
  return inside;
}

}  // namespace mppm::pre
