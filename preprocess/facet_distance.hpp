// Closest point of a segment or triangle to a point (Ericson, Real-Time Collision Detection,
// 5.1.2 and 5.1.5). Used for "within the horizon of that boundary" and "nearest boundary wins":
// plain floating point is enough here, the decisions that must be exact are in inside_test.
#pragma once
#include <cmath>

#include "preprocess/geometry_model.hpp"

namespace mppm::pre {

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b);
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Closest point on facet `f` of `mesh` (segment or triangle by mesh.dimension).
Vec3 closest_point_on_facet(const FacetMesh& mesh, std::size_t f, const Vec3& p);

inline double distance(const Vec3& p, const Vec3& q) {
  const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace mppm::pre
