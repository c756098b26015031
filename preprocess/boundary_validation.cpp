// Closedness, self-intersection and orientation of the body boundary (see boundary_validation.hpp).
#include "preprocess/boundary_validation.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/input_error.hpp"

namespace mppm::pre {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

std::string where(const Vec3& p, int dimension) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p[0] << ", " << p[1];
  if (dimension == 3) s << ", " << p[2];
  s << ") m";
  return s.str();
}

void drop_degenerate_facets(FacetMesh& mesh) {
  FacetMesh kept;
  kept.dimension = mesh.dimension;
  kept.vertices = std::move(mesh.vertices);
  for (std::size_t f = 0; f < mesh.facet_count(); ++f) {
    const std::int64_t* c = &mesh.facets[f * mesh.dimension];
    const bool repeated = mesh.dimension == 2 ? c[0] == c[1] : (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]);
    if (!repeated) kept.add_facet(c, mesh.entity[f]);
  }
  mesh = std::move(kept);
}

// Boundary curves must not cross (a figure-eight or overlapping surfaces would make "inside"
// meaningless). Sweep in x with exact segment tests; neighbours along a loop share a vertex
// and are skipped.
void reject_crossing_segments(const FacetMesh& mesh, const std::string& file) {
  using Point2 = Kernel::Point_2;
  const std::size_t n = mesh.facet_count();
  std::vector<std::size_t> order(n);
  for (std::size_t s = 0; s < n; ++s) order[s] = s;
  auto xmin = [&](std::size_t s) { return std::min(mesh.vertex(s, 0)[0], mesh.vertex(s, 1)[0]); };
  auto xmax = [&](std::size_t s) { return std::max(mesh.vertex(s, 0)[0], mesh.vertex(s, 1)[0]); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return xmin(a) < xmin(b); });
  for (std::size_t oi = 0; oi < n; ++oi) {
    const std::size_t a = order[oi];
    const double a_xmax = xmax(a);
    const Vec3 &a0 = mesh.vertex(a, 0), &a1 = mesh.vertex(a, 1);
    const double a_ylo = std::min(a0[1], a1[1]), a_yhi = std::max(a0[1], a1[1]);
    for (std::size_t oj = oi + 1; oj < n && xmin(order[oj]) <= a_xmax; ++oj) {
      const std::size_t b = order[oj];
      const Vec3 &b0 = mesh.vertex(b, 0), &b1 = mesh.vertex(b, 1);
      if (std::max(b0[1], b1[1]) < a_ylo || std::min(b0[1], b1[1]) > a_yhi) continue;
      const std::int64_t *ca = &mesh.facets[2 * a], *cb = &mesh.facets[2 * b];
      if (ca[0] == cb[0] || ca[0] == cb[1] || ca[1] == cb[0] || ca[1] == cb[1]) continue;
      if (CGAL::do_intersect(Kernel::Segment_2(Point2(a0[0], a0[1]), Point2(a1[0], a1[1])),
                             Kernel::Segment_2(Point2(b0[0], b0[1]), Point2(b1[0], b1[1]))))
        throw InputError(file + ": boundary curves of the body cross each other near " + where(a0, 2) +
                         " (expected a body bounded by closed, non-crossing curves)");
    }
  }
}

void orient_2d(FacetMesh& mesh, const std::string& file) {
  const std::size_t n = mesh.facet_count();
  std::vector<std::vector<std::size_t>> incident(mesh.vertices.size());
  for (std::size_t s = 0; s < n; ++s)
    for (int c = 0; c < 2; ++c) incident[static_cast<std::size_t>(mesh.facets[2 * s + c])].push_back(s);
  for (std::size_t v = 0; v < incident.size(); ++v) {
    if (incident[v].empty() || incident[v].size() == 2) continue;
    throw InputError(file + ": the boundary of the body is " +
                     (incident[v].size() == 1 ? std::string("not closed (a curve ends at ")
                                              : std::string("not a simple curve (") +
                                                    std::to_string(incident[v].size()) + " boundary curves meet at ") +
                     where(mesh.vertices[v], 2) + ")");
  }
  // Walk the loops: make consecutive segments head to tail.
  std::vector<std::int32_t> loop_of(n, -1);
  std::vector<std::vector<std::size_t>> loops;
  for (std::size_t start = 0; start < n; ++start) {
    if (loop_of[start] >= 0) continue;
    const auto id = static_cast<std::int32_t>(loops.size());
    loops.emplace_back();
    std::size_t s = start;
    while (loop_of[s] < 0) {
      loop_of[s] = id;
      loops.back().push_back(s);
      const auto head = static_cast<std::size_t>(mesh.facets[2 * s + 1]);
      const std::size_t next = incident[head][0] == s ? incident[head][1] : incident[head][0];
      if (static_cast<std::size_t>(mesh.facets[2 * next]) != head)
        std::swap(mesh.facets[2 * next], mesh.facets[2 * next + 1]);
      s = next;
    }
  }
  using Point2 = Kernel::Point_2;
  auto point = [&](std::size_t s, int c) {
    const Vec3& p = mesh.vertices[static_cast<std::size_t>(mesh.facets[2 * s + c])];
    return Point2(p[0], p[1]);
  };
  for (std::size_t l = 0; l < loops.size(); ++l) {
    double twice_area = 0.0;
    for (std::size_t s : loops[l]) {
      const Point2 a = point(s, 0), b = point(s, 1);
      twice_area += a.x() * b.y() - b.x() * a.y();
    }
    // Nesting depth of the loop: how many other loops contain its first vertex (exact parity,
    // ray to +x, half-open rule on the row).
    const Point2 v = point(loops[l][0], 0);
    int depth = 0;
    for (std::size_t m = 0; m < loops.size(); ++m) {
      if (m == l) continue;
      int crossings = 0;
      for (std::size_t s : loops[m]) {
        Point2 a = point(s, 0), b = point(s, 1);
        if ((a.y() > v.y()) == (b.y() > v.y())) continue;
        if (a.y() > b.y()) std::swap(a, b);
        const CGAL::Orientation o = CGAL::orientation(a, b, v);
        if (o == CGAL::COLLINEAR)
          throw InputError(file + ": boundary curves of the body touch or cross near " + where({v.x(), v.y(), 0.0}, 2));
        if (o == CGAL::LEFT_TURN) ++crossings;
      }
      depth += crossings % 2;
    }
    const bool outer = depth % 2 == 0;
    if ((twice_area > 0) != outer)  // body must be on the left of every segment
      for (std::size_t s : loops[l]) std::swap(mesh.facets[2 * s], mesh.facets[2 * s + 1]);
  }
}

void validate_and_orient_3d(FacetMesh& mesh, const std::string& file) {
  const std::size_t n = mesh.facet_count();
  // Closed and manifold: each undirected edge on exactly two triangles.
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  edges.reserve(3 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (int e = 0; e < 3; ++e) {
      const std::int64_t a = mesh.facets[3 * t + e], b = mesh.facets[3 * t + (e + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  std::size_t open = 0, nonmanifold = 0;
  std::pair<std::int64_t, std::int64_t> first_bad{-1, -1};
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) {
      (j - i == 1 ? open : nonmanifold) += 1;
      if (first_bad.first < 0) first_bad = edges[i];
    }
    i = j;
  }
  if (open || nonmanifold) {
    std::ostringstream s;
    s << file << ": the boundary surface of the body is "
      << (open ? "not closed (" + std::to_string(open) + " open edges"
               : "not manifold (" + std::to_string(nonmanifold) + " edges shared by more than two triangles")
      << ", e.g. near " << where(mesh.vertices[static_cast<std::size_t>(first_bad.first)], 3)
      << "); a 3-D body needs a closed, watertight surface";
    throw InputError(s.str());
  }

  // Only the vertices the facets use (the model's vertex list also holds pre-crack and other
  // entities' nodes; CGAL's orientation code must not see isolated vertices).
  std::vector<std::int64_t> compact(mesh.vertices.size(), -1);
  std::vector<Kernel::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons(n);
  for (std::size_t t = 0; t < n; ++t)
    for (int c = 0; c < 3; ++c) {
      const auto v = static_cast<std::size_t>(mesh.facets[3 * t + c]);
      if (compact[v] < 0) {
        compact[v] = static_cast<std::int64_t>(points.size());
        points.emplace_back(mesh.vertices[v][0], mesh.vertices[v][1], mesh.vertices[v][2]);
      }
      polygons[t].push_back(static_cast<std::size_t>(compact[v]));
    }
  namespace PMP = CGAL::Polygon_mesh_processing;
  PMP::orient_polygon_soup(points, polygons);  // may duplicate non-manifold vertices
  CGAL::Surface_mesh<Kernel::Point_3> surface;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, surface);
  if (surface.number_of_faces() != n || !CGAL::is_closed(surface))
    throw InputError(file +
                     ": the boundary surface of the body cannot be oriented consistently "
                     "(non-orientable or non-manifold surface)");
  if (PMP::does_self_intersect(surface))
    throw InputError(file +
                     ": the boundary surface of the body intersects itself (or has "
                     "degenerate triangles); a 3-D body needs a closed surface without "
                     "self-intersections");
  PMP::orient_to_bound_a_volume(surface);
  // Faces were created in polygon order: copy the final orientation back facet by facet.
  std::size_t t = 0;
  for (auto face : surface.faces()) {
    Vec3 corner[3];
    int k = 0;
    for (auto v : CGAL::vertices_around_face(surface.halfedge(face), surface)) {
      const auto& p = surface.point(v);
      if (k < 3) corner[k] = {p.x(), p.y(), p.z()};
      ++k;
    }
    std::int64_t* c = &mesh.facets[3 * t];
    const Vec3 &a = mesh.vertices[c[0]], &b = mesh.vertices[c[1]], &d = mesh.vertices[c[2]];
    const bool same = (corner[0] == a && corner[1] == b && corner[2] == d) ||
                      (corner[0] == b && corner[1] == d && corner[2] == a) ||
                      (corner[0] == d && corner[1] == a && corner[2] == b);
    const bool reversed = (corner[0] == a && corner[1] == d && corner[2] == b) ||
                          (corner[0] == d && corner[1] == b && corner[2] == a) ||
                          (corner[0] == b && corner[1] == a && corner[2] == d);
    if (k != 3 || (!same && !reversed)) throw std::logic_error("boundary orientation: CGAL reordered the faces");
    if (reversed) std::swap(c[1], c[2]);
    ++t;
  }
}

}  // namespace

void validate_and_orient_boundary(FacetMesh& boundary, const std::string& file) {
  drop_degenerate_facets(boundary);
  if (boundary.facet_count() == 0) throw InputError(file + ": the body has an empty boundary");
  if (boundary.dimension == 2) {
    reject_crossing_segments(boundary, file);
    orient_2d(boundary, file);
  } else
    validate_and_orient_3d(boundary, file);
}

Vec3 facet_normal(const FacetMesh& boundary, std::size_t facet) {
  const Vec3 &a = boundary.vertex(facet, 0), &b = boundary.vertex(facet, 1);
  Vec3 n{};
  if (boundary.dimension == 2) {
    n = {b[1] - a[1], -(b[0] - a[0]), 0.0};
  } else {
    const Vec3& c = boundary.vertex(facet, 2);
    const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  }
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (length > 0)
    for (double& c : n) c /= length;
  return n;
}

double facet_measure(const FacetMesh& boundary, std::size_t facet) {
  const Vec3 &a = boundary.vertex(facet, 0), &b = boundary.vertex(facet, 1);
  if (boundary.dimension == 2) return std::hypot(b[0] - a[0], b[1] - a[1]);
  const Vec3& c = boundary.vertex(facet, 2);
  const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const Vec3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace mppm::pre
