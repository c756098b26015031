// Point-to-facet closest points (see facet_distance.hpp).
#include "preprocess/facet_distance.hpp"

#include <algorithm>

namespace mppm::pre {
namespace {
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 axpy(const Vec3& a, double s, const Vec3& d) { return {a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]}; }
}  // namespace

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = sub(b, a);
  const double length2 = dot(ab, ab);
  if (length2 == 0.0) return a;
  const double t = std::clamp(dot(sub(p, a), ab) / length2, 0.0, 1.0);
  return axpy(a, t, ab);
}

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return axpy(a, d1 / (d1 - d3), ab);
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return axpy(a, d2 / (d2 - d6), ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return axpy(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b));
  const double denominator = va + vb + vc;
  if (denominator == 0.0) return closest_point_on_segment(p, a, b);  // degenerate triangle
  const double v = vb / denominator, w = vc / denominator;
  return axpy(axpy(a, v, ab), w, ac);
}

Vec3 closest_point_on_facet(const FacetMesh& mesh, std::size_t f, const Vec3& p) {
  if (mesh.dimension == 2) return closest_point_on_segment(p, mesh.vertex(f, 0), mesh.vertex(f, 1));
  return closest_point_on_triangle(p, mesh.vertex(f, 0), mesh.vertex(f, 1), mesh.vertex(f, 2));
}

}  // namespace mppm::pre
