// Pre-cracks (docs/theory.md section 8): the set of lattice bonds that cross a pre-crack, as found by
// common/precrack_crossing (CGAL exact predicates, binned index), equals an independent
// brute-force count in integer lattice units (exact, no CGAL), in 2-D (the crack-branching
// plate's notch) and 3-D (a rectangular crack in a box); plus the touching rules by hand.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "common/precrack_crossing.hpp"
#include "test_preprocess_support.hpp"

using namespace mppm;
using mppm::test::inline_scene;

TEST(PrecrackCrossing, HandCases2d) {
  const std::vector<double> crack = {0, 0, 0, 1, 0, 0};  // segment (0,0)-(1,0)
  EXPECT_TRUE(bond_crosses_precrack({0.5, -1, 0}, {0.5, 1, 0}, 2, crack));
  EXPECT_FALSE(bond_crosses_precrack({1.5, -1, 0}, {1.5, 1, 0}, 2, crack));                  // beyond the tip
  EXPECT_TRUE(bond_crosses_precrack({1, -1, 0}, {1, 1, 0}, 2, crack));                       // through the tip
  EXPECT_FALSE(bond_crosses_precrack({0.2, 0.1, 0}, {0.8, 0.1, 0}, 2, crack));               // parallel
  EXPECT_TRUE(bond_crosses_precrack({0.5, 0, 0}, {0.5, 1, 0}, 2, crack));                    // end point on it
  EXPECT_TRUE(bond_crosses_precrack({-1, -1, 0}, {2, 2, 0}, 2, crack));                      // oblique at (0,0)
  EXPECT_FALSE(bond_crosses_precrack({-1, -0.5, 0}, {0.9, 1.5, 0}, 2, {0, 0, 0, 0, 0, 0}));  // degenerate crack
}

TEST(PrecrackCrossing, HandCases3d) {
  const std::vector<double> crack = {0, 0, 0, 1, 0, 0, 0, 1, 0};  // triangle in z = 0
  EXPECT_TRUE(bond_crosses_precrack({0.2, 0.2, -1}, {0.2, 0.2, 1}, 3, crack));
  EXPECT_FALSE(bond_crosses_precrack({0.6, 0.6, -1}, {0.6, 0.6, 1}, 3, crack));  // beyond hypotenuse
  EXPECT_TRUE(bond_crosses_precrack({0.5, 0.5, -1}, {0.5, 0.5, 1}, 3, crack));   // on the hypotenuse
  EXPECT_FALSE(bond_crosses_precrack({0.2, 0.2, 0.1}, {0.3, 0.2, 0.1}, 3, crack));
  EXPECT_TRUE(bond_crosses_precrack({-0.5, 0.2, -0.5}, {0.5, 0.2, 0.5}, 3, crack));
  PrecrackIndex index(3, crack, 0.3);
  EXPECT_TRUE(index.crosses({0.2, 0.2, -1}, {0.2, 0.2, 1}));
  EXPECT_FALSE(index.crosses({0.6, 0.6, -1}, {0.6, 0.6, 1}));
  EXPECT_TRUE(index.crosses({0.5, 0.5, -1}, {0.5, 0.5, 1}));
}

// The per-point pre-test never hides a crossing: every bond that crosses (of length up to the
// reach) starts at a point the test keeps, in 2-D and 3-D; and a point farther than the reach from
// the pre-crack's bounding box is skipped.
TEST(PrecrackCrossing, PointTestKeepsEveryPointWhoseBondsCanCross) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 3.0), unit(-1.0, 1.0);
  const double reach = 0.3;
  for (const int dimension : {2, 3}) {
    const std::vector<double> crack =
        dimension == 2 ? std::vector<double>{0, 0, 0, 1, 0, 0} : std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0};
    const PrecrackIndex index(dimension, crack, reach);
    int crossing = 0;
    for (int n = 0; n < 200000; ++n) {
      Point3 a{coordinate(random) / 2, coordinate(random) / 2, dimension == 3 ? coordinate(random) / 2 : 0.0};
      Point3 step{unit(random), unit(random), dimension == 3 ? unit(random) : 0.0};
      const double length = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
      if (length > 1.0 || length == 0.0) continue;
      const Point3 b{a[0] + reach * step[0], a[1] + reach * step[1], a[2] + reach * step[2]};
      if (!index.crosses(a, b)) continue;
      ++crossing;
      ASSERT_TRUE(index.may_cross_within(a, reach)) << "dimension " << dimension << " at " << a[0] << " " << a[1];
    }
    EXPECT_GT(crossing, 100) << "dimension " << dimension;  // the property was put to the test (2-D 2000+, 3-D 400+)
    EXPECT_FALSE(index.may_cross_within({0.5, -0.31, 0}, reach));
    EXPECT_FALSE(index.may_cross_within({1.31, 0, 0}, reach));
    EXPECT_TRUE(index.may_cross_within({0.5, -0.29, 0}, reach));
    if (dimension == 3) {
      EXPECT_FALSE(index.may_cross_within({0.2, 0.2, 0.31}, reach));
    }
  }
}

namespace {

enum class Truth { apart, crosses, on_crack_edge };

// Does the bond p-q (integer lattice units) cross the plane `axis` = level inside the closed
// rectangle [lo, hi] of the other axes? Exact in 64-bit integers. A bond whose crossing point
// lies exactly on the rectangle's edge (e.g. through the crack tip) is a tie of the ideal
// geometry: in metres the lattice and crack coordinates carry round-off, so the preprocessor's
// exact predicates may decide it either way. Those are reported apart and not compared.
Truth crosses_axis_rectangle(const std::array<long, 3>& p, const std::array<long, 3>& q, int axis, long level,
                             const std::array<long, 3>& lo, const std::array<long, 3>& hi, int dimension) {
  const long dp = p[axis] - level, dq = q[axis] - level;
  if (dp == 0 || dq == 0 || (dp > 0) == (dq > 0)) return Truth::apart;  // no point on the crack plane here
  const long den = dp - dq;
  bool on_edge = false;
  for (int a = 0; a < dimension; ++a) {
    if (a == axis) continue;
    // Crossing point c = p + t (q - p), t = dp / (dp - dq): compare c[a] * den with the bounds.
    const long num = p[a] * den + dp * (q[a] - p[a]);
    const long low = lo[a] * den, high = hi[a] * den;
    const bool below = den > 0 ? num < low : num > low;
    const bool above = den > 0 ? num > high : num < high;
    if (below || above) return Truth::apart;
    on_edge = on_edge || num == low || num == high;
  }
  return on_edge ? Truth::on_crack_edge : Truth::crosses;
}

}  // namespace

TEST(PrecrackCrossing, PlateNotchBondsEqualBruteForce) {
  const pre::PreprocessResult result =
      pre::preprocess(inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.5 mm", 4.05, "", "[notch]"));
  const PointCloud& cloud = result.cloud;
  ASSERT_GT(cloud.precrack_element_count(), 0u);
  const PrecrackIndex index(2, cloud.precrack_vertices, cloud.horizon);
  // Integer units of dx/2 = 0.25 mm: points at odd coordinates, the notch at y = 80, x in [0, 200].
  const double unit = 0.25e-3;
  std::vector<std::array<long, 3>> lattice(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    lattice[i] = {std::lround(cloud.x[i] / unit), std::lround(cloud.y[i] / unit), 0};
  const long reach = 2 * 4;  // 4 spacings, in units
  const double limit = 4.05 * 2;
  long expected = 0, found = 0, mismatches = 0, brute_checked = 0, ties = 0;
  // Neighbour search by lattice index (the plate is a full 200 x 80 grid).
  std::vector<std::int64_t> at(200 * 80, -1);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    at[(lattice[i][1] - 1) / 2 * 200 + (lattice[i][0] - 1) / 2] = static_cast<std::int64_t>(i);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (long dj = -reach; dj <= reach; dj += 2)
      for (long di = -reach; di <= reach; di += 2) {
        if ((di == 0 && dj == 0) || std::hypot(double(di), double(dj)) > limit + 1e-9) continue;
        const long x = lattice[i][0] + di, y = lattice[i][1] + dj;
        if (x < 1 || x > 399 || y < 1 || y > 159) continue;
        const auto j = static_cast<std::size_t>(at[(y - 1) / 2 * 200 + (x - 1) / 2]);
        const Truth exact = crosses_axis_rectangle(lattice[i], lattice[j], 1, 80, {0, 0, 0}, {200, 0, 0}, 2);
        if (exact == Truth::on_crack_edge) {
          ++ties;
          continue;
        }
        const bool truth = exact == Truth::crosses;
        const Point3 a{cloud.x[i], cloud.y[i], 0}, b{cloud.x[j], cloud.y[j], 0};
        const bool indexed = index.crosses(a, b);
        expected += truth;
        found += indexed;
        mismatches += truth != indexed;
        if (std::abs(y - 80) <= reach + 2 && x <= 200 + reach + 2) {  // near the notch: brute force too
          ++brute_checked;
          mismatches += truth != bond_crosses_precrack(a, b, 2, cloud.precrack_vertices);
        }
      }
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(found, expected);
  EXPECT_GT(expected, 1000);  // ~ (notch length / dx) x (bonds across a line per column)
  EXPECT_GT(brute_checked, expected);
  EXPECT_LT(ties, expected / 50);  // only the bonds through the tip itself
}

TEST(PrecrackCrossing, BoxCrackBondsEqualBruteForce) {
  const pre::PreprocessResult result =
      pre::preprocess(inline_scene(3, "../geometry/box_with_crack.geo", "mm", "0.5 mm", 2.05, "", "[crack]"));
  const PointCloud& cloud = result.cloud;
  ASSERT_EQ(cloud.size(), 20u * 12u * 8u);
  const PrecrackIndex index(3, cloud.precrack_vertices, cloud.horizon);
  const double unit = 0.25e-3;  // points at odd units; the crack at z = 8, x in [0, 20], y in [0, 24]
  long expected = 0, mismatches = 0, ties = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (std::size_t j = 0; j < cloud.size(); ++j) {
      if (i == j) continue;
      const std::array<long, 3> p{std::lround(cloud.x[i] / unit), std::lround(cloud.y[i] / unit),
                                  std::lround(cloud.z[i] / unit)};
      const std::array<long, 3> q{std::lround(cloud.x[j] / unit), std::lround(cloud.y[j] / unit),
                                  std::lround(cloud.z[j] / unit)};
      const long dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
      if (dx * dx + dy * dy + dz * dz > 4.1 * 4.1 + 1e-9) continue;  // horizon 2.05 dx = 4.1 units
      const Truth exact = crosses_axis_rectangle(p, q, 2, 8, {0, 0, 0}, {20, 24, 0}, 3);
      if (exact == Truth::on_crack_edge) {
        ++ties;
        continue;
      }
      const bool truth = exact == Truth::crosses;
      expected += truth;
      mismatches += truth != index.crosses({cloud.x[i], cloud.y[i], cloud.z[i]}, {cloud.x[j], cloud.y[j], cloud.z[j]});
    }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(expected, 0);
  EXPECT_LT(ties, expected / 10);  // the bonds through the crack front x = 5 mm
}

TEST(PrecrackCrossing, BoxAndEntitySelectionsOfTheNotchAgree) {
  const auto by_name =
      pre::preprocess(inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.5 mm", 4.05, "", "[notch]"))
          .cloud;
  const auto by_entity = pre::preprocess(inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.5 mm", 4.05,
                                                      "", "[{entities: [5]}]"))
                             .cloud;
  // The box also holds part of the left edge, but a box selects pre-cracks only among curves
  // that are not on the body boundary.
  const auto by_box = pre::preprocess(inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.5 mm", 4.05, "",
                                                   "[{box: [[-1 mm, 19 mm, -1 mm], [51 mm, 21 mm, 1 mm]]}]"))
                          .cloud;
  EXPECT_EQ(by_entity.precrack_vertices, by_name.precrack_vertices);
  EXPECT_EQ(by_box.precrack_vertices, by_name.precrack_vertices);
}

TEST(PrecrackCrossing, LatticePointsOnAPrecrackAreReported) {
  // 40 mm / 41 rows puts the middle row on the notch (y = 20 mm); 0.5 mm puts it between rows.
  const auto on = pre::preprocess(
      inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.975609756097561 mm", 3.0, "", "[notch]"));
  ASSERT_EQ(on.report.warnings.size(), 1u);
  EXPECT_NE(on.report.warnings[0].find("lie exactly on a pre-crack"), std::string::npos);
  const auto between =
      pre::preprocess(inline_scene(2, "../../../geometry/branching_plate.geo", "m", "0.5 mm", 3.0, "", "[notch]"));
  EXPECT_TRUE(between.report.warnings.empty());
}
