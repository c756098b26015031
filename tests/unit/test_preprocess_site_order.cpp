// The points file's numbering: the Z-order curve through the lattice's sites, checked against an
// independent key (the coordinates' bits interleaved, z highest), on whole grids (every aligned
// block of sites is one run of the numbering), on grids with empty sites, and on the points
// file of a body with boundary layers (each region in Z-order, the body first).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "preprocess/site_order.hpp"
#include "test_preprocess_support.hpp"

using namespace mppm;
using namespace mppm::pre;
using Site = std::array<std::int64_t, 3>;

namespace {

// The Morton key: bit b of x, y, z at bits 3b, 3b + 1, 3b + 2 (42 bits per axis fit in 128 bits).
__extension__ using Key = unsigned __int128;
Key interleaved_key(const Site& s) {
  Key key = 0;
  for (int b = 0; b < 42; ++b)
    for (int a = 0; a < 3; ++a) key |= static_cast<Key>((static_cast<std::uint64_t>(s[a]) >> b) & 1u) << (3 * b + a);
  return key;
}

LatticeGrid grid_of(int dimension, Site count) {
  LatticeGrid grid;
  grid.dimension = dimension;
  grid.spacing = 1.0;
  grid.count = count;
  return grid;
}

std::vector<std::uint8_t> all_sites(const LatticeGrid& grid) {
  return std::vector<std::uint8_t>(static_cast<std::size_t>(grid.size()), 1);
}

}  // namespace

TEST(SiteOrder, EveryAlignedBlockOfAWholeGridIsOneRun) {
  for (const int dimension : {2, 3}) {
    const LatticeGrid grid = grid_of(dimension, dimension == 2 ? Site{16, 16, 1} : Site{8, 8, 8});
    const auto order = sites_in_z_order(grid, all_sites(grid));
    ASSERT_EQ(order.size(), static_cast<std::size_t>(grid.size()));
    // The first 2^d sites are the block at the origin, x fastest (as in lattice order).
    EXPECT_EQ(grid.site(order[1]), (Site{1, 0, 0}));
    EXPECT_EQ(grid.site(order[2]), (Site{0, 1, 0}));
    for (std::int64_t edge = 2; edge <= 8; edge *= 2) {
      const std::int64_t block = dimension == 2 ? edge * edge : edge * edge * edge;
      for (std::size_t first = 0; first < order.size(); first += static_cast<std::size_t>(block)) {
        const Site corner = grid.site(order[first]);
        for (std::size_t s = first; s < first + static_cast<std::size_t>(block); ++s) {
          const Site at = grid.site(order[s]);
          for (int a = 0; a < dimension; ++a) {
            ASSERT_EQ(corner[a] % edge, 0) << "block " << edge << " starts off its alignment";
            ASSERT_EQ(at[a] / edge, corner[a] / edge) << "site " << s << " left its block of " << edge;
          }
        }
      }
    }
  }
}

TEST(SiteOrder, ListsExactlyTheOccupiedSitesInKeyOrder) {
  // Grids of any shape: edges not powers of two, one far longer than the others, 2-D and 3-D.
  for (const auto& [dimension, count] : {std::pair{3, Site{7, 5, 6}}, std::pair{3, Site{37, 3, 2}},
                                         std::pair{2, Site{13, 70, 1}}, std::pair{3, Site{1, 1, 9}}}) {
    const LatticeGrid grid = grid_of(dimension, count);
    std::vector<std::uint8_t> occupied(static_cast<std::size_t>(grid.size()));
    std::mt19937 random(3);
    for (auto& o : occupied) o = random() % 3 != 0;
    const auto order = sites_in_z_order(grid, occupied);
    std::vector<std::int64_t> expected;
    for (std::int64_t g = 0; g < grid.size(); ++g)
      if (occupied[static_cast<std::size_t>(g)]) expected.push_back(g);
    std::sort(expected.begin(), expected.end(), [&](std::int64_t a, std::int64_t b) {
      return interleaved_key(grid.site(a)) < interleaved_key(grid.site(b));
    });
    EXPECT_EQ(order, expected) << "grid " << count[0] << " x " << count[1] << " x " << count[2];
  }
}

TEST(SiteOrder, ThePointsFileNumbersEachRegionAlongTheCurveBodyFirst) {
  // A box with a velocity condition on one face: a layer of fictitious points outside it.
  const auto result = preprocess(mppm::test::inline_scene(3, "../geometry/box.geo", "mm", "0.5 mm", 3.0,
                                                          "  - {boundary: xmin, type: velocity, value: [0, 0, 0]}\n"));
  const PointCloud& cloud = result.cloud;
  ASSERT_GT(mppm::test::count_region(cloud, 1), 0);
  // The lattice's site (0, 0, 0): the body's lowest cell centre on each axis (the box's cells from
  // 0.25 mm), less the padding that holds the layers on every side, ceil(horizon / dx) + 1 = 4 cells.
  const std::vector<double>* axes[3] = {&cloud.x, &cloud.y, &cloud.z};
  double low[3];
  for (int a = 0; a < 3; ++a) {
    double body_low = 1.0;
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (cloud.region[i] == 0) body_low = std::min(body_low, (*axes[a])[i]);
    ASSERT_NEAR(body_low, 0.25e-3, 1e-12);
    low[a] = body_low - 4 * cloud.spacing;
  }
  const auto site = [&](std::size_t i) {
    return Site{mppm::test::lattice_index(cloud.x[i], low[0], cloud.spacing),
                mppm::test::lattice_index(cloud.y[i], low[1], cloud.spacing),
                mppm::test::lattice_index(cloud.z[i], low[2], cloud.spacing)};
  };
  for (std::size_t i = 1; i < cloud.size(); ++i) {
    ASSERT_LE(cloud.region[i - 1], cloud.region[i]) << "the regions are not contiguous blocks, body first";
    if (cloud.region[i - 1] == cloud.region[i]) {
      ASSERT_LT(interleaved_key(site(i - 1)), interleaved_key(site(i))) << "point " << i << " is off the Z-order curve";
    }
  }
}
