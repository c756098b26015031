// Boundary layers and loaded points (docs/theory.md section 8): kinematic layers lie outside the body,
// reach at least the horizon, carry the right region, and are complete (every lattice point
// outside the body within the horizon of the boundary, nearest boundary winning, is there);
// traction/pressure tags lie inside within the traction depth with the outward normal; box and
// entity-tag selections pick the same facets as the physical group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "common/input_error.hpp"
#include "test_preprocess_support.hpp"

using namespace mppm;
using mppm::test::count_region;
using mppm::test::inline_scene;

namespace {

constexpr double kDx = 0.5e-3, kL = 0.1, kH = 0.04, kFactor = 4.05;
constexpr double kHorizon = kFactor * kDx;

double distance_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay;
  const double t = std::clamp(((px - ax) * ux + (py - ay) * uy) / (ux * ux + uy * uy), 0.0, 1.0);
  return std::hypot(px - ax - t * ux, py - ay - t * uy);
}

// The plate with: 1 top velocity, 2 left displacement, 3 bottom traction, 4 right pressure.
Scene plate_scene(const std::string& top_selector = "boundary: top", const std::string& bottom_extra = "") {
  return inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.5 mm", kFactor,
                      "  - {" + top_selector +
                          ", type: velocity, value: [0, 1 m/s]}\n"
                          "  - {boundary: left, type: displacement, value: [0, 0]}\n"
                          "  - {boundary: bottom, type: traction, value: [0, -8 MPa]" +
                          bottom_extra +
                          "}\n"
                          "  - {boundary: right, type: pressure, value: 1 MPa}\n",
                      "[]", "2 mm");
}

}  // namespace

TEST(PreprocessLayers, KinematicLayersAreOutsideCompleteAndNearestWins) {
  const PointCloud cloud = pre::preprocess(plate_scene()).cloud;
  ASSERT_EQ(cloud.boundaries.size(), 4u);
  EXPECT_EQ(count_region(cloud, 0), 200 * 80);
  // Reference: every lattice position (cell centres extended beyond the plate) outside the plate
  // within the horizon of the top or the left edge; the nearer edge wins, ties to the earlier.
  std::map<std::pair<long, long>, int> expected;
  for (long i = -12; i < 212; ++i)
    for (long j = -12; j < 92; ++j) {
      const double x = (i + 0.5) * kDx, y = (j + 0.5) * kDx;
      if (x > 0 && x < kL && y > 0 && y < kH) continue;  // inside the body
      const double top = distance_to_segment(x, y, 0, kH, kL, kH);
      const double left = distance_to_segment(x, y, 0, 0, 0, kH);
      const double bottom = distance_to_segment(x, y, 0, 0, kL, 0);
      const double right = distance_to_segment(x, y, kL, 0, kL, kH);
      const double reach = kHorizon + 1e-9 * kDx;
      if (std::min(top, left) > reach) continue;
      // Not wrapped around a corner into the space beside a traction edge (ties stay).
      if (std::min(bottom, right) < std::min(top, left) - 1e-9 * kDx) continue;
      expected[{i, j}] = top <= left ? 1 : 2;
    }
  std::map<std::pair<long, long>, int> actual;
  double top_depth = 0.0, left_depth = 0.0;
  for (std::size_t p = 0; p < cloud.size(); ++p) {
    if (cloud.region[p] == 0) continue;
    ASSERT_TRUE(cloud.region[p] == 1 || cloud.region[p] == 2) << "layer of a traction boundary";
    ASSERT_EQ(cloud.boundary_id[p], cloud.region[p]);
    ASSERT_FALSE(cloud.x[p] > 0 && cloud.x[p] < kL && cloud.y[p] > 0 && cloud.y[p] < kH)
        << "layer point inside the body";
    actual[{std::lround(cloud.x[p] / kDx - 0.5), std::lround(cloud.y[p] / kDx - 0.5)}] = cloud.region[p];
    if (cloud.region[p] == 1) top_depth = std::max(top_depth, cloud.y[p] - kH);
    if (cloud.region[p] == 2) left_depth = std::max(left_depth, -cloud.x[p]);
  }
  EXPECT_EQ(actual, expected);
  // Depth >= horizon in lattice terms: the outermost layer row is the last lattice row within
  // the horizon, i.e. less than one spacing short of it (rows at dx/2, 3dx/2, ...).
  EXPECT_GT(top_depth + kDx, kHorizon);
  EXPECT_LE(top_depth, kHorizon);
  EXPECT_GT(left_depth + kDx, kHorizon);
  // And what the depth is for: every family member (|xi| <= horizon) of every body point that
  // falls outside the body across the top edge is a layer point of the top.
  long checked = 0;
  const long reach = static_cast<long>(std::floor(kFactor));
  for (std::size_t p = 0; p < cloud.size(); ++p) {
    if (cloud.region[p] != 0 || cloud.y[p] < kH - kHorizon || cloud.x[p] < kHorizon) continue;
    const long i = std::lround(cloud.x[p] / kDx - 0.5), j = std::lround(cloud.y[p] / kDx - 0.5);
    for (long di = -reach; di <= reach; ++di)
      for (long dj = 1; dj <= reach; ++dj) {
        if (std::hypot(double(di), double(dj)) > kFactor + 1e-9 || j + dj < 80) continue;
        ASSERT_EQ(actual.count({i + di, j + dj}), 1u);
        ++checked;
      }
  }
  EXPECT_GT(checked, 0);
  EXPECT_DOUBLE_EQ(cloud.boundaries[0].area, kL * 2e-3);  // length x thickness
  EXPECT_EQ(cloud.boundaries[0].type, "velocity");
  EXPECT_EQ(cloud.boundaries[0].name, "top");
}

TEST(PreprocessLayers, TractionPointsAreInsideWithinDepthWithOutwardNormals) {
  const PointCloud cloud = pre::preprocess(plate_scene()).cloud;
  long bottom = 0, right = 0;
  for (std::size_t p = 0; p < cloud.size(); ++p) {
    if (cloud.region[p] != 0) continue;
    const double x = cloud.x[p], y = cloud.y[p];
    // Default traction depth dx: only the first row/column (at dx/2) is within it.
    const bool near_bottom = y <= kDx, near_right = kL - x <= kDx;
    if (cloud.boundary_id[p] == 3) {
      ++bottom;
      ASSERT_TRUE(near_bottom);
      ASSERT_EQ(cloud.normal_x[p], 0.0);
      ASSERT_DOUBLE_EQ(cloud.normal_y[p], -1.0);
    } else if (cloud.boundary_id[p] == 4) {
      ++right;
      ASSERT_TRUE(near_right);
      ASSERT_DOUBLE_EQ(cloud.normal_x[p], 1.0);
      ASSERT_EQ(cloud.normal_y[p], 0.0);
    } else {
      ASSERT_EQ(cloud.boundary_id[p], 0);
      ASSERT_FALSE(near_bottom || near_right) << "untagged point within the traction depth";
      ASSERT_EQ(cloud.normal_x[p], 0.0);
    }
  }
  // The corner point (99.75, 0.25) mm is equally near both: the earlier condition (bottom) wins.
  EXPECT_EQ(bottom, 200);
  EXPECT_EQ(right, 79);
  EXPECT_EQ(cloud.boundaries[2].point_count, 200);
  EXPECT_EQ(cloud.boundaries[3].point_count, 79);
  EXPECT_DOUBLE_EQ(cloud.boundaries[3].area, kH * 2e-3);
  // A deeper loaded layer (depth: 2 dx) takes two rows, except (99.75, 0.75) mm, which is
  // nearer to the right edge (0.25 mm) than to the bottom (0.75 mm): 2 x 200 - 1.
  const PointCloud deep = pre::preprocess(plate_scene("boundary: top", ", depth: 1 mm")).cloud;
  EXPECT_EQ(deep.boundaries[2].point_count, 399);
}

TEST(PreprocessLayers, BoxAndEntitySelectionsEqualThePhysicalGroup) {
  const PointCloud by_name = pre::preprocess(plate_scene()).cloud;
  // Line 3 of branching_plate.geo is the top edge; the box holds only that edge (facets entirely
  // inside the box are selected, so it must not hold the end facets of the side edges).
  const PointCloud by_entity = pre::preprocess(plate_scene("entities: [3]")).cloud;
  const PointCloud by_box =
      pre::preprocess(plate_scene("box: [[-1 mm, 39.95 mm, -1 mm], [101 mm, 40.05 mm, 1 mm]]")).cloud;
  for (const PointCloud* other : {&by_entity, &by_box}) {
    EXPECT_EQ(other->x, by_name.x);
    EXPECT_EQ(other->y, by_name.y);
    EXPECT_EQ(other->region, by_name.region);
    EXPECT_EQ(other->boundary_id, by_name.boundary_id);
    EXPECT_DOUBLE_EQ(other->boundaries[0].area, by_name.boundaries[0].area);
  }
}

TEST(PreprocessLayers, LayerInAHoleAndPressureOnACurvedBoundary) {
  const Scene scene = inline_scene(2, "../geometry/disc_with_hole.geo", "mm", "0.5 mm", 3.05,
                                   "  - {boundary: hole, type: velocity, value: [0, 0]}\n"
                                   "  - {boundary: outer, type: pressure, value: 1 MPa}\n");
  const PointCloud cloud = pre::preprocess(scene).cloud;
  const double horizon = 3.05 * 0.5;  // mm
  long layer = 0, loaded = 0;
  for (std::size_t p = 0; p < cloud.size(); ++p) {
    const double x = cloud.x[p] * 1e3, y = cloud.y[p] * 1e3;
    const double from_hole_centre = std::hypot(x - 3.0, y - 2.0), radius = std::hypot(x, y);
    if (cloud.region[p] == 1) {
      ++layer;
      // In the hole (facet sag < 1e-3 mm), within the horizon of its circle.
      ASSERT_LT(from_hole_centre, 8.0 + 1e-3);
      ASSERT_LE(8.0 - from_hole_centre, horizon + 1e-3);
    } else if (cloud.boundary_id[p] == 2) {
      ++loaded;
      ASSERT_LE(20.0 - radius, 0.5 + 1e-3);  // within dx of the outer circle
      // Outward normal of the circle, up to the facet's deviation (facets <= dx/4 on r = 20).
      const double nx = cloud.normal_x[p], ny = cloud.normal_y[p];
      ASSERT_NEAR(std::hypot(nx, ny), 1.0, 1e-12);
      ASSERT_GT((nx * x + ny * y) / radius, std::cos(0.02));
    }
  }
  // Every lattice point of the hole ring within the horizon: about the ring area / dx^2.
  const double ring = std::numbers::pi * (8.0 * 8.0 - (8.0 - horizon) * (8.0 - horizon)) / 0.25;
  EXPECT_NEAR(static_cast<double>(layer), ring, 0.05 * ring);
  const double rim = std::numbers::pi * (20.0 * 20.0 - 19.5 * 19.5) / 0.25;
  EXPECT_NEAR(static_cast<double>(loaded), rim, 0.1 * rim);
  EXPECT_NEAR(cloud.boundaries[1].area, 2 * std::numbers::pi * 20e-3 * 1e-3,
              1e-3 * 2 * std::numbers::pi * 20e-3 * 1e-3);
}

TEST(PreprocessLayers, ThreeDimensionalBoxLayersAndNormals) {
  const Scene scene = inline_scene(3, "../geometry/box.geo", "mm", "0.5 mm", 3.05,
                                   "  - {boundary: xmin, type: velocity, value: [0, 0, 0]}\n"
                                   "  - {boundary: zmax, type: traction, value: [0, 0, 1 MPa]}\n");
  const PointCloud cloud = pre::preprocess(scene).cloud;
  EXPECT_EQ(count_region(cloud, 0), 20 * 12 * 8);
  const double horizon = 3.05 * 0.5e-3;
  long layer = 0, loaded = 0;
  for (std::size_t p = 0; p < cloud.size(); ++p) {
    if (cloud.region[p] == 1) {
      ++layer;
      ASSERT_LT(cloud.x[p], 0.0);  // beside the face only, not wrapped around its edges
      // Distance to the face x = 0, 0 <= y <= 6, 0 <= z <= 4 mm.
      const double dy = std::max({0.0, -cloud.y[p], cloud.y[p] - 6e-3});
      const double dz = std::max({0.0, -cloud.z[p], cloud.z[p] - 4e-3});
      ASSERT_LE(std::sqrt(cloud.x[p] * cloud.x[p] + dy * dy + dz * dz), horizon * (1 + 1e-9));
    } else if (cloud.boundary_id[p] == 2) {
      ++loaded;
      ASSERT_NEAR(cloud.z[p], 3.75e-3, 1e-12);
      ASSERT_EQ(cloud.normal_z[p], 1.0);
    }
  }
  // Straight through the face: 3 rows (0.25, 0.75, 1.25 mm <= 1.525 mm) of 12 x 8, plus the
  // points around the face's edges and corners within the horizon.
  EXPECT_GT(layer, 3 * 12 * 8);
  EXPECT_EQ(loaded, 20 * 12);
  EXPECT_DOUBLE_EQ(cloud.boundaries[1].area, 10e-3 * 6e-3);
}

TEST(PreprocessLayers, UnknownGroupListsTheAvailableOnes) {
  try {
    pre::preprocess(plate_scene("boundary: lid"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("unknown physical group 'lid'"), std::string::npos) << message;
    EXPECT_NE(message.find("branching_plate.geo"), std::string::npos) << message;
    EXPECT_NE(message.find("'top' (curve)"), std::string::npos) << message;
  }
  try {  // a box that holds no boundary
    pre::preprocess(plate_scene("box: [[10 mm, 10 mm, -1 mm], [20 mm, 20 mm, 1 mm]]"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("selects no part of the body boundary"), std::string::npos) << e.what();
  }
}

TEST(PreprocessLayers, StepPartSelectedByBoxesMatchesTheGeoPartSelectedByGroups) {
  // geometry/notched_specimen_3d.step is the .geo part exported; STEP has no physical groups,
  // so its scene selects the end faces with boxes (in mm, converted by the scene parser).
  const auto geo = pre::preprocess(load_scene(mppm::test::scenes_dir() + "/pre_notched_3d.yaml")).cloud;
  const auto step = pre::preprocess(load_scene(mppm::test::scenes_dir() + "/pre_notched_3d_step.yaml")).cloud;
  for (int region : {0, 1}) EXPECT_EQ(count_region(step, region), count_region(geo, region)) << region;
  ASSERT_EQ(step.boundaries.size(), 2u);
  for (std::size_t b = 0; b < 2; ++b) {
    EXPECT_EQ(step.boundaries[b].point_count, geo.boundaries[b].point_count);
    EXPECT_NEAR(step.boundaries[b].area, geo.boundaries[b].area, 1e-12);
  }
  EXPECT_NEAR(geo.boundaries[0].area, 20e-3 * 10e-3, 1e-12);  // the left end face
}
