// Boundary validation and orientation: after validate_and_orient_boundary every facet normal
// points out of the body (outer loops and holes in 2-D, outer shells and cavities in 3-D);
// open, branching, crossing and self-intersecting boundaries are rejected with the file name.
#include <gtest/gtest.h>

#include <cmath>

#include "common/input_error.hpp"
#include "preprocess/boundary_validation.hpp"

using namespace mppm;
using namespace mppm::pre;

namespace {

FacetMesh loops_2d(const std::vector<std::vector<std::array<double, 2>>>& loops) {
  FacetMesh mesh;
  mesh.dimension = 2;
  for (const auto& loop : loops) {
    const auto first = static_cast<std::int64_t>(mesh.vertices.size());
    for (const auto& p : loop) mesh.vertices.push_back({p[0], p[1], 0.0});
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::int64_t c[2] = {first + static_cast<std::int64_t>(i),
                                 first + static_cast<std::int64_t>((i + 1) % loop.size())};
      mesh.add_facet(c, 1);
    }
  }
  return mesh;
}

// Closed triangulated cube surface [o, o + s]^3 with the given face winding (+1 outward).
void add_cube(FacetMesh& mesh, double o, double s, bool inward) {
  const auto base = static_cast<std::int64_t>(mesh.vertices.size());
  for (int k = 0; k < 8; ++k)
    mesh.vertices.push_back({o + s * (k & 1), o + s * ((k >> 1) & 1), o + s * ((k >> 2) & 1)});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    std::int64_t t1[3] = {base + q[0], base + q[1], base + q[2]}, t2[3] = {base + q[0], base + q[2], base + q[3]};
    if (inward) {
      std::swap(t1[1], t1[2]);
      std::swap(t2[1], t2[2]);
    }
    mesh.add_facet(t1, 1);
    mesh.add_facet(t2, 1);
  }
}

Vec3 centroid(const FacetMesh& mesh, std::size_t f) {
  Vec3 c{};
  for (int k = 0; k < mesh.dimension; ++k)
    for (int a = 0; a < 3; ++a) c[a] += mesh.vertex(f, k)[a] / mesh.dimension;
  return c;
}

void expect_input_error(FacetMesh mesh, const std::string& fragment) {
  try {
    validate_and_orient_boundary(mesh, "shape.geo");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shape.geo"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(PreprocessBoundary, TwoDimensionalNormalsPointOutOfTheBody) {
  // Outer square given clockwise, hole given counter-clockwise: both must be flipped.
  FacetMesh mesh = loops_2d({{{0, 0}, {0, 4}, {4, 4}, {4, 0}}, {{1, 1}, {3, 1}, {3, 3}, {1, 3}}});
  validate_and_orient_boundary(mesh, "shape.geo");
  for (std::size_t f = 0; f < mesh.facet_count(); ++f) {
    const Vec3 n = facet_normal(mesh, f), c = centroid(mesh, f);
    const bool hole = c[0] > 0.5 && c[0] < 3.5 && c[1] > 0.5 && c[1] < 3.5;
    // Outward of the body: away from the square's centre on the outer loop, towards it on the hole.
    const double radial = n[0] * (c[0] - 2) + n[1] * (c[1] - 2);
    EXPECT_EQ(radial > 0, !hole) << "facet " << f;
    EXPECT_NEAR(std::hypot(n[0], n[1]), 1.0, 1e-15);
  }
}

TEST(PreprocessBoundary, ThreeDimensionalNormalsPointOutOfTheBodyAroundACavity) {
  FacetMesh mesh;
  mesh.dimension = 3;
  add_cube(mesh, 0.0, 4.0, true);   // outer shell wound inwards
  add_cube(mesh, 1.0, 2.0, false);  // cavity wound "outwards" of itself, i.e. into the body
  validate_and_orient_boundary(mesh, "shape.geo");
  for (std::size_t f = 0; f < mesh.facet_count(); ++f) {
    const Vec3 n = facet_normal(mesh, f), c = centroid(mesh, f);
    const bool cavity = f >= 12;
    const double radial = n[0] * (c[0] - 2) + n[1] * (c[1] - 2) + n[2] * (c[2] - 2);
    EXPECT_EQ(radial > 0, !cavity) << "facet " << f;
  }
}

TEST(PreprocessBoundary, BadBoundariesAreRejected) {
  expect_input_error(loops_2d({{{0, 0}, {2, 2}, {2, 0}, {0, 2}}}), "cross");  // bow tie
  FacetMesh open = loops_2d({{{0, 0}, {1, 0}, {1, 1}}});
  open.facets.resize(4);  // drop the closing segment
  open.entity.resize(2);
  expect_input_error(open, "not closed");
  FacetMesh cube;
  cube.dimension = 3;
  add_cube(cube, 0.0, 1.0, false);
  FacetMesh open_cube = cube;
  open_cube.facets.resize(open_cube.facets.size() - 6);
  open_cube.entity.resize(open_cube.entity.size() - 2);
  expect_input_error(open_cube, "not closed");
  FacetMesh overlapping = cube;
  add_cube(overlapping, 0.5, 1.0, false);
  expect_input_error(overlapping, "intersects itself");
}
