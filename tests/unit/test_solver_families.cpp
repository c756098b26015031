// Families and bond storage (docs/theory.md section 1): the cell-list search finds exactly the points
// within the horizon (tolerance 1e-9 dx), every bond is stored from both ends, and bonds across
// a pre-crack are cut from both ends before the first step.
#include <gtest/gtest.h>

#include <set>

#include "common/precrack_crossing.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

constexpr double kDx = 1e-3;

std::set<std::pair<int, int>> bond_set(const Model& m) {
  std::set<std::pair<int, int>> bonds;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    for (std::int64_t b = m.bonds.offset[i]; b < m.bonds.offset[i + 1]; ++b)
      bonds.insert({static_cast<int>(i), m.bonds.neighbor[b]});
  return bonds;
}

TEST(SolverFamilies, CellListFindsExactlyThePointsWithinTheHorizonFromBothEnds) {
  for (int d : {2, 3}) {
    const double factor = d == 2 ? 4.05 : 2.0;  // 2.0: lattice points exactly on the sphere must be in
    const std::array<int, 3> n = d == 2 ? std::array<int, 3>{23, 17, 1} : std::array<int, 3>{9, 8, 7};
    const Model m = make_model(make_lattice(d, n, kDx), make_scene(d, true, kDx, factor));
    // Brute force reference with the same tolerance.
    const double reach = factor * kDx + 1e-9 * kDx;
    std::set<std::pair<int, int>> expected;
    for (std::size_t i = 0; i < m.points.owned; ++i)
      for (std::size_t j = 0; j < m.points.owned; ++j) {
        if (i == j) continue;
        double r2 = 0.0;
        for (int a = 0; a < d; ++a) {
          const double x = m.points.position[j * d + a] - m.points.position[i * d + a];
          r2 += x * x;
        }
        if (r2 <= reach * reach) expected.insert({static_cast<int>(i), static_cast<int>(j)});
      }
    const auto found = bond_set(m);
    EXPECT_EQ(found, expected) << "d=" << d;
    for (const auto& [i, j] : found) EXPECT_TRUE(found.count({j, i})) << "bond " << i << "-" << j << " stored once";
    // xi = x_j - x_i (computed from the positions, not stored: no periodicity), neighbours sorted.
    EXPECT_TRUE(m.bonds.xi.empty());
    for (std::size_t i = 0; i < m.points.owned; ++i)
      for (std::int64_t b = m.bonds.offset[i]; b < m.bonds.offset[i + 1]; ++b) {
        if (b > m.bonds.offset[i]) {
          EXPECT_LT(m.bonds.neighbor[b - 1], m.bonds.neighbor[b]);
        }
        const auto j = static_cast<std::size_t>(m.bonds.neighbor[b]);
        double xi[3];
        bond_vector(m.bonds, m.points, i, b, xi);
        for (int a = 0; a < d; ++a) EXPECT_EQ(xi[a], m.points.position[j * d + a] - m.points.position[i * d + a]);
      }
  }
  // Interior point of the 2-D lattice with factor 4.05: the number of lattice points in a disc
  // of radius 4.05 (Gauss circle count 49, minus the point itself).
  const Model m = make_model(make_lattice(2, {23, 17, 1}, kDx), make_scene(2, true, kDx, 4.05));
  const std::size_t centre = 8 * 23 + 11;
  EXPECT_EQ(m.bonds.offset[centre + 1] - m.bonds.offset[centre], 48);
}

TEST(SolverFamilies, PrecrackCutsBondsCrossingItFromBothEnds) {
  // A 2-D notch from the left edge to the middle, between two lattice rows.
  PointCloud cloud = make_lattice(2, {20, 12, 1}, kDx);
  cloud.precrack_vertices = {-kDx, 6 * kDx, 0.0, 10 * kDx, 6 * kDx, 0.0};
  const Scene scene = make_scene(2, true, kDx, 3.05);
  const Model whole = make_model(make_lattice(2, {20, 12, 1}, kDx), scene);
  const Model cut = make_model(cloud, scene);
  const auto before = bond_set(whole);
  const auto after = bond_set(cut);
  std::size_t crossing = 0;
  for (const auto& [i, j] : before) {
    const Point3 a{cloud.x[i], cloud.y[i], 0.0}, b{cloud.x[j], cloud.y[j], 0.0};
    const bool crosses = bond_crosses_precrack(a, b, 2, cloud.precrack_vertices);
    crossing += crosses;
    EXPECT_EQ(after.count({i, j}), crosses ? 0u : 1u) << i << "-" << j;
  }
  EXPECT_GT(crossing, 0u);
  EXPECT_EQ(cut.precrack_cut_entries, crossing);
  for (const auto& [i, j] : after) EXPECT_TRUE(after.count({j, i}));
  EXPECT_EQ(cut.detached_points, 0u);
  // No interaction crosses the notch: moving a point just below it leaves every point above it
  // and more than two horizons from the tip (no path around the tip) exactly unloaded.
  Model loaded = make_model(cloud, scene);
  const std::size_t below = 5 * 20 + 2;  // column 2, row 5 (y = 5.5 dx), the notch is at y = 6 dx
  loaded.points.displacement[below * 2 + 1] = -1e-6;
  loaded.compute_internal_forces();
  EXPECT_NE(loaded.points.force[below * 2 + 1], 0.0);
  int checked = 0;
  for (std::size_t i = 0; i < loaded.points.owned; ++i) {
    if (cloud.y[i] < 6 * kDx || cloud.x[i] > 10 * kDx - 2 * 3.05 * kDx) continue;
    EXPECT_EQ(loaded.points.force[i * 2], 0.0) << i;
    EXPECT_EQ(loaded.points.force[i * 2 + 1], 0.0) << i;
    EXPECT_EQ(loaded.points.moment[i], 0.0) << i;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

}  // namespace
}  // namespace mppm::solver
