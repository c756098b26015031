// 3-D crack metrics (postprocess/crack_area_metrics.hpp) on synthetic crack_area fields of a
// 40 x 20 x 10 mm block (dx 1 mm): a planar crack normal to z whose front runs along x, each
// point of the two rows next to it holding half the area of its lattice cell's face (so that the
// field sums to the cracked area exactly, as the solver's estimator does within about 1 %:
// tests/unit/test_solver_crack_area.cpp); a penny that grows; stray broken bonds; no pre-crack.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "postprocess/crack_area_metrics.hpp"

namespace {

using mppm::post::CrackAreaMetrics;
using mppm::post::measure_crack_area;

constexpr double kDx = 1e-3;
constexpr double kCell = kDx * kDx;
constexpr int kNx = 40, kNy = 20, kNz = 10;
// Sums of a few thousand values: rounding to 1e-12 of the block's section.
constexpr double kAreaTolerance = 1e-12 * kNx * kNy * kCell;

struct Block {
  std::vector<double> x, y, z;
  std::vector<char> include;
  Block() {
    for (int k = 0; k < kNz; ++k)
      for (int j = 0; j < kNy; ++j)
        for (int i = 0; i < kNx; ++i) {
          x.push_back((i + 0.5) * kDx);
          y.push_back((j + 0.5) * kDx);
          z.push_back((k + 0.5) * kDx);
          include.push_back(1);
        }
  }
  std::size_t size() const { return x.size(); }
  // The crack in the plane z = 5 mm over the points `cracked(x, y)`: the rows z = 4.5 and 5.5 mm
  // hold dx^2 / 2 each there.
  template <class Inside>
  std::vector<double> crack(Inside cracked) const {
    std::vector<double> area(size(), 0.0);
    for (std::size_t i = 0; i < size(); ++i)
      if (std::abs(z[i] - 5 * kDx) < kDx && cracked(x[i], y[i])) area[i] = 0.5 * kCell;
    return area;
  }
  // A crack through the whole width from x = 0 to `front` (between columns).
  std::vector<double> edge_crack(double front) const {
    return crack([front](double px, double) { return px < front; });
  }
  CrackAreaMetrics measure(const std::vector<double>& times, const std::vector<std::vector<double>>& fields) const {
    return measure_crack_area(x, y, z, include, times, fields, kDx);
  }
};

TEST(PostCrackArea, EdgeCrackGrowingAlongX) {
  const Block b;
  // The pre-crack reaches x = 5 mm; the crack front then advances 2 mm per microsecond to 25 mm.
  std::vector<double> times;
  std::vector<std::vector<double>> fields;
  for (int k = 0; k <= 10; ++k) {
    times.push_back(k * 1e-6);
    fields.push_back(b.edge_crack((5 + 2 * k) * kDx));
  }
  const CrackAreaMetrics m = b.measure(times, fields);
  const double width = kNy * kDx;
  EXPECT_NEAR(m.precrack_area_m2, 5 * kDx * width, kAreaTolerance);
  EXPECT_NEAR(m.area_m2, 20 * kDx * width, kAreaTolerance);
  // New area 2 mm x 20 mm = 40 dx^2 at 1 us: at or above one cell's face.
  ASSERT_TRUE(m.start_time_s);
  EXPECT_DOUBLE_EQ(*m.start_time_s, 1e-6);
  // The last crack points are at x = 24.5 mm, the pre-crack's last at 4.5 mm, on the same rows.
  ASSERT_TRUE(m.front_advance_m);
  EXPECT_NEAR(*m.front_advance_m, 20 * kDx, 1e-12);
  EXPECT_DOUBLE_EQ(*m.front_advance_time_s, 10e-6);
  ASSERT_EQ(m.frames.size(), times.size());
  for (std::size_t k = 0; k < m.frames.size(); ++k) {
    EXPECT_NEAR(m.frames[k].new_area, 2.0 * k * kDx * width, kAreaTolerance) << k;
    ASSERT_TRUE(m.frames[k].front_advance) << k;
    EXPECT_NEAR(*m.frames[k].front_advance, 2.0 * k * kDx, 1e-12) << k;
  }
  EXPECT_TRUE(m.notes.empty());
}

TEST(PostCrackArea, StartNeedsOneCellOfNewArea) {
  const Block b;
  const auto pre = b.edge_crack(5 * kDx);
  // 1 us: stray broken bonds (0.1 dx^2 at each of 8 points far from the crack): no crack point, and
  // 0.8 dx^2 of area in all: not yet a crack. 2 us: a 1 x 2 mm patch ahead of the front grows it by
  // 2 dx^2.
  auto stray = pre;
  for (int k = 0; k < 8; ++k) stray[static_cast<std::size_t>(k * kNx * kNy + 35 + 15 * kNx)] = 0.1 * kCell;
  auto grown = b.crack([](double px, double py) { return px < 5 * kDx || (px < 6 * kDx && py < 2 * kDx); });
  for (int k = 0; k < 8; ++k) grown[static_cast<std::size_t>(k * kNx * kNy + 35 + 15 * kNx)] = 0.1 * kCell;
  const CrackAreaMetrics m = b.measure({0.0, 1e-6, 2e-6}, {pre, stray, grown});
  EXPECT_NEAR(m.frames[1].new_area, 0.8 * kCell, kAreaTolerance);
  EXPECT_DOUBLE_EQ(*m.frames[1].front_advance, 0.0);
  ASSERT_TRUE(m.start_time_s);
  EXPECT_DOUBLE_EQ(*m.start_time_s, 2e-6);
  EXPECT_NEAR(*m.front_advance_m, kDx, 1e-12);  // x = 5.5 mm from the pre-crack's 4.5 mm
}

TEST(PostCrackArea, PennyGrowingRadially) {
  const Block b;
  const double cx = 20 * kDx, cy = 10 * kDx;
  auto penny = [&](double radius) {
    return b.crack([=](double px, double py) { return std::hypot(px - cx, py - cy) < radius; });
  };
  const CrackAreaMetrics m = b.measure({0.0, 1e-6, 2e-6}, {penny(3 * kDx), penny(6 * kDx), penny(9 * kDx)});
  // The lattice's disc areas differ from pi r^2 by the cells on the rim; the front from the
  // pre-crack is 6 mm within one dx (the outermost points of both are up to dx inside their circles).
  EXPECT_NEAR(m.area_m2 + m.precrack_area_m2, std::acos(-1.0) * 81 * kCell, 0.1 * std::acos(-1.0) * 81 * kCell);
  ASSERT_TRUE(m.front_advance_m);
  EXPECT_NEAR(*m.front_advance_m, 6 * kDx, kDx);
}

TEST(PostCrackArea, WithoutPrecrackTheFrontIsMeasuredFromWhereTheCrackAppeared) {
  const Block b;
  const std::vector<double> none(b.size(), 0.0);
  auto strip = [&](double from, double to) { return b.crack([=](double px, double) { return px > from && px < to; }); };
  const CrackAreaMetrics m =
      b.measure({0.0, 1e-6, 2e-6, 3e-6}, {none, strip(19 * kDx, 21 * kDx), strip(17 * kDx, 23 * kDx), none});
  EXPECT_EQ(m.precrack_area_m2, 0.0);
  EXPECT_DOUBLE_EQ(*m.start_time_s, 1e-6);
  EXPECT_FALSE(m.frames[0].front_advance);
  EXPECT_DOUBLE_EQ(*m.frames[1].front_advance, 0.0);
  EXPECT_NEAR(*m.frames[2].front_advance, 2 * kDx, 1e-12);
  // The furthest advance is kept when a later frame has less (a field that shrank).
  EXPECT_NEAR(*m.front_advance_m, 2 * kDx, 1e-12);
  EXPECT_DOUBLE_EQ(*m.front_advance_time_s, 2e-6);
  EXPECT_EQ(m.area_m2, 0.0);
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("no pre-crack"), std::string::npos) << m.notes[0];
}

TEST(PostCrackArea, NoCrackAndLayerPoints) {
  Block b;
  const std::vector<double> none(b.size(), 0.0);
  const CrackAreaMetrics quiet = b.measure({0.0, 1e-6}, {none, none});
  EXPECT_EQ(quiet.area_m2, 0.0);
  EXPECT_FALSE(quiet.start_time_s);
  EXPECT_FALSE(quiet.front_advance_m);
  // Crack area on points that are not body points (boundary layers) is left out.
  for (std::size_t i = 0; i < b.size(); ++i) b.include[i] = b.x[i] > 4 * kDx;
  const CrackAreaMetrics layers = b.measure({0.0, 1e-6}, {none, b.edge_crack(4 * kDx)});
  EXPECT_EQ(layers.area_m2, 0.0);
  EXPECT_FALSE(layers.start_time_s);
}

TEST(PostCrackArea, HistoryTable) {
  const Block b;
  const CrackAreaMetrics m = b.measure({0.0, 1e-6}, {b.crack([](double, double) { return false; }), b.edge_crack(kDx)});
  const std::string csv = mppm::post::crack_area_csv(m);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "time_s,crack_area_m2,total_crack_area_m2,crack_front_advance_m");
  // No crack in the first frame: no front advance yet; the crack appears at 1 us (20 dx^2).
  EXPECT_NE(csv.find("\n0,0,0,\n"), std::string::npos) << csv;
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  double time = 0, added = 0, total = 0, advance = -1;
  ASSERT_EQ(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf", &time, &added, &total, &advance), 4) << csv;
  EXPECT_EQ(time, 1e-6);
  EXPECT_NEAR(added, 20 * kCell, kAreaTolerance);
  EXPECT_EQ(total, added);
  EXPECT_EQ(advance, 0.0);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
}

}  // namespace
