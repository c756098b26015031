// The partition of a distributed run and the ghosts of its parts (solver/coordinate_bisection.hpp,
// solver/halo_points.hpp): balance, independence of the points' order, and ghost sets equal to a
// brute-force search and to the families' neighbours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/coordinate_bisection.hpp"
#include "solver/halo_points.hpp"
#include "solver/horizon_search.hpp"
#include "solver/local_points.hpp"

namespace {

using namespace mppm::solver;

// A lattice of unit spacing, nx x ny (x nz), points in row order, global ids 0 .. n-1.
struct Lattice {
  int dimension = 2;
  std::vector<double> position;
  std::vector<std::int64_t> id;
  std::vector<std::int64_t> weight;
  std::size_t size() const { return id.size(); }
  PointPositions positions() const { return {dimension, position.data(), size()}; }
  PartitionPoints partition_points() const { return {dimension, position, weight, id}; }
};

constexpr double kHorizon = 3.05;  // the cases' horizon factor, in spacings

// Brute force: the points within the bond reach of point i (the families' test, every pair).
bool within_reach(const Lattice& l, std::size_t i, std::size_t j, double reach) {
  double r2 = 0.0;
  for (int a = 0; a < l.dimension; ++a) {
    const double d = l.position[j * l.dimension + a] - l.position[i * l.dimension + a];
    r2 += d * d;
  }
  return i != j && r2 <= reach * reach;
}

Lattice make_lattice(int dimension, int nx, int ny, int nz = 1) {
  Lattice l;
  l.dimension = dimension;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        l.position.push_back(x);
        l.position.push_back(y);
        if (dimension == 3) l.position.push_back(z);
        l.id.push_back(static_cast<std::int64_t>(l.id.size()));
      }
  // Weight: the bonds of each point (fewer at the edges), as a run weighs its points.
  const double reach = bond_reach(kHorizon, 1.0);
  for (std::size_t i = 0; i < l.size(); ++i) {
    std::int64_t bonds = 0;
    for (std::size_t j = 0; j < l.size(); ++j) bonds += within_reach(l, i, j, reach) ? 1 : 0;
    l.weight.push_back(bonds);
  }
  return l;
}

std::vector<std::int32_t> part_by_id(const Lattice& l, const std::vector<std::int32_t>& part) {
  std::vector<std::int32_t> by_id(l.size());
  for (std::size_t i = 0; i < l.size(); ++i) by_id[static_cast<std::size_t>(l.id[i])] = part[i];
  return by_id;
}

TEST(CoordinateBisection, EveryPartGetsPointsAndAnEvenShareOfTheWeight) {
  const Lattice l = make_lattice(2, 40, 25);
  const std::int64_t total = std::accumulate(l.weight.begin(), l.weight.end(), std::int64_t{0});
  const std::int64_t heaviest_point = *std::max_element(l.weight.begin(), l.weight.end());
  for (int parts = 1; parts <= 9; ++parts) {
    const auto part = coordinate_bisection(l.partition_points(), parts);
    std::vector<std::int64_t> load(static_cast<std::size_t>(parts), 0);
    for (std::size_t i = 0; i < l.size(); ++i) {
      ASSERT_GE(part[i], 0);
      ASSERT_LT(part[i], parts);
      load[static_cast<std::size_t>(part[i])] += l.weight[i];
    }
    // Each cut lands within one point's weight of its share, and a part inherits the misses of the
    // cuts above it: ceil(log2(parts)) of them.
    const auto levels = static_cast<std::int64_t>(std::ceil(std::log2(parts)));
    for (const std::int64_t w : load) {
      EXPECT_GT(w, 0) << parts << " parts";
      EXPECT_LE(std::abs(w * parts - total), levels * heaviest_point * parts) << parts << " parts";
    }
  }
}

TEST(CoordinateBisection, DoesNotDependOnTheOrderOfThePoints) {
  const Lattice l = make_lattice(3, 9, 7, 6);
  std::mt19937 rng(3);
  for (int parts : {2, 3, 5, 8}) {
    const auto expected = part_by_id(l, coordinate_bisection(l.partition_points(), parts));
    Lattice shuffled;
    shuffled.dimension = 3;
    std::vector<std::size_t> order(l.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::shuffle(order.begin(), order.end(), rng);
    for (const std::size_t i : order) {
      for (int a = 0; a < 3; ++a) shuffled.position.push_back(l.position[i * 3 + a]);
      shuffled.id.push_back(l.id[i]);
      shuffled.weight.push_back(l.weight[i]);
    }
    EXPECT_EQ(part_by_id(shuffled, coordinate_bisection(shuffled.partition_points(), parts)), expected)
        << parts << " parts";
  }
}

TEST(CoordinateBisection, CutsAcrossTheLongestSide) {
  Lattice l = make_lattice(2, 40, 10);
  std::fill(l.weight.begin(), l.weight.end(), 1);
  const auto part = coordinate_bisection(l.partition_points(), 2);
  for (std::size_t i = 0; i < l.size(); ++i) EXPECT_EQ(part[i], l.position[i * 2] < 20.0 ? 0 : 1) << "point " << i;
}

// The run's partition weighs each point by its bonds plus the extra weight given (a viscoplastic
// run's return map): on a 40 x 10 strip with 30 extra on every point of the left quarter, the cut
// between 2 parts moves left from the middle to where the weights balance, within one column.
TEST(PartitionCloud, ExtraWeightsMoveTheCut) {
  const Lattice l = make_lattice(2, 40, 10);
  const double reach = bond_reach(kHorizon, 1.0);
  const auto even = partition_cloud(l.positions(), reach, 1.0, 2);
  std::vector<std::int64_t> extra(l.size(), 0);
  for (std::size_t i = 0; i < l.size(); ++i)
    if (l.position[i * 2] < 10.0) extra[i] = 30;
  const auto weighted = partition_cloud(l.positions(), reach, 1.0, 2, extra);
  auto first_column_of_part_1 = [&](const std::vector<std::int32_t>& part) {
    double x = 40.0;
    for (std::size_t i = 0; i < l.size(); ++i)
      if (part[i] == 1) x = std::min(x, l.position[i * 2]);
    return x;
  };
  EXPECT_EQ(first_column_of_part_1(even), 20.0);
  // Where the columns' weights balance: total and prefix sums over columns of bonds + extra.
  std::vector<double> column(40, 0.0);
  for (std::size_t i = 0; i < l.size(); ++i)
    column[static_cast<std::size_t>(l.position[i * 2])] += static_cast<double>(l.weight[i] + extra[i]);
  const double half = 0.5 * std::accumulate(column.begin(), column.end(), 0.0);
  double prefix = 0.0;
  int balance = 0;
  while (prefix + column[static_cast<std::size_t>(balance)] <= half)
    prefix += column[static_cast<std::size_t>(balance++)];
  EXPECT_NEAR(first_column_of_part_1(weighted), balance, 1.0);
  EXPECT_LT(first_column_of_part_1(weighted), 20.0);
  EXPECT_THROW(partition_cloud(l.positions(), reach, 1.0, 2, std::vector<std::int64_t>(3, 1)), std::invalid_argument);
}

// Points on the cut's coordinate are ordered by global id: ids decide, not memory order.
TEST(CoordinateBisection, BreaksTiesByGlobalId) {
  Lattice l;
  l.dimension = 2;
  for (std::int64_t id : {7, 3, 9, 1, 5, 2}) {
    l.position.insert(l.position.end(), {0.5, 0.5});
    l.id.push_back(id);
    l.weight.push_back(1);
  }
  const auto part = coordinate_bisection(l.partition_points(), 2);
  for (std::size_t i = 0; i < l.size(); ++i) EXPECT_EQ(part[i], l.id[i] <= 3 ? 0 : 1) << "id " << l.id[i];
}

TEST(CoordinateBisection, RefusesMorePartsThanPointsAndBadWeights) {
  Lattice l = make_lattice(2, 2, 2);
  EXPECT_THROW(coordinate_bisection(l.partition_points(), 5), std::invalid_argument);
  EXPECT_THROW(coordinate_bisection(l.partition_points(), 0), std::invalid_argument);
  l.weight[2] = 0;
  EXPECT_THROW(coordinate_bisection(l.partition_points(), 2), std::invalid_argument);
}

std::vector<std::size_t> brute_force_halo(const Lattice& l, const std::vector<std::int32_t>& part, std::int32_t p,
                                          double reach) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < l.size(); ++j) {
    if (part[j] == p) continue;
    for (std::size_t i = 0; i < l.size(); ++i)
      if (part[i] == p && within_reach(l, i, j, reach)) {
        out.push_back(j);
        break;
      }
  }
  return out;
}

TEST(HaloPoints, EqualABruteForceSearchIn2DAnd3D) {
  const double reach = bond_reach(kHorizon, 1.0);
  for (const Lattice& l : {make_lattice(2, 30, 20), make_lattice(3, 10, 9, 8)}) {
    for (int parts : {2, 5}) {
      const auto part = coordinate_bisection(l.partition_points(), parts);
      for (std::int32_t p = 0; p < parts; ++p) {
        const auto halo = halo_points(l.positions(), part, p, reach, 1.0);
        EXPECT_EQ(halo, brute_force_halo(l, part, p, reach)) << l.dimension << "-D, part " << p << " of " << parts;
        EXPECT_FALSE(halo.empty());
      }
    }
  }
}

// Parts two columns wide, the horizon three: each part's ghosts come from the parts two and three
// columns away as well as from its neighbours.
TEST(HaloPoints, ReachBeyondTheNextPartWhenPartsAreThinnerThanTheHorizon) {
  Lattice l = make_lattice(2, 40, 4);
  std::fill(l.weight.begin(), l.weight.end(), 1);
  const int parts = 20;
  const auto part = coordinate_bisection(l.partition_points(), parts);
  for (std::size_t i = 0; i < l.size(); ++i) ASSERT_EQ(part[i], static_cast<int>(l.position[i * 2]) / 2);
  const double reach = bond_reach(kHorizon, 1.0);
  const std::int32_t middle = 10;
  const auto halo = halo_points(l.positions(), part, middle, reach, 1.0);
  EXPECT_EQ(halo, brute_force_halo(l, part, middle, reach));
  std::set<std::int32_t> from;
  for (const std::size_t j : halo) from.insert(part[j]);
  EXPECT_EQ(from, (std::set<std::int32_t>{8, 9, 11, 12}));
}

// A part's families name only its own points and its ghosts, and every ghost is named.
TEST(HaloPoints, AreTheNeighboursThePartsFamiliesName) {
  const Lattice l = make_lattice(3, 10, 9, 8);
  PointData points;
  points.dimension = 3;
  points.position = l.position;
  points.owned = l.size();
  FamilyOptions options;
  options.horizon = kHorizon;
  options.spacing = 1.0;
  const BondFamilies families = build_families(points, options);
  const int parts = 3;
  const auto part = coordinate_bisection(l.partition_points(), parts);
  for (std::int32_t p = 0; p < parts; ++p) {
    std::set<std::size_t> named;
    for (std::size_t i = 0; i < l.size(); ++i) {
      if (part[i] != p) continue;
      for (std::int64_t b = families.offset[i]; b < families.offset[i + 1]; ++b)
        if (part[families.neighbor_of(b)] != p) named.insert(families.neighbor_of(b));
    }
    const auto halo =
        halo_points(l.positions(), part, p, bond_reach(options.horizon, options.spacing), options.spacing);
    EXPECT_EQ(std::vector<std::size_t>(named.begin(), named.end()), halo) << "part " << p;
  }
}

}  // namespace
