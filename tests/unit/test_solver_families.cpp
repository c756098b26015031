// Families and bond storage (docs/theory.md section 1): the search (by cells, or on a lattice by its
// sites) finds exactly the points within the horizon (tolerance 1e-9 dx), every bond is stored from
// both ends, and bonds across a pre-crack are cut from both ends before the first step.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "common/precrack_crossing.hpp"
#include "solver/lattice_sites.hpp"
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

// A cloud whose box is far larger than its points' reach (two clusters 10^11 spacings apart: cells
// of the reach would number 10^10 and more) is searched by a grid of larger cells, with the same
// families as every pair gives.
TEST(SolverFamilies, SparseCloudIsSearchedWithoutACellPerReach) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.2 * kDx, 0.2 * kDx);
  PointCloud cloud;
  cloud.dimension = 2;
  cloud.spacing = kDx;
  cloud.thickness = 1.0;
  for (const double shift : {0.0, 1e11 * kDx})
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        cloud.x.push_back(shift + i * kDx + jitter(random));
        cloud.y.push_back(j * kDx + jitter(random));
      }
  const std::size_t n = cloud.x.size();
  cloud.z.assign(n, 0.0);
  cloud.volume.assign(n, kDx * kDx);
  cloud.region.assign(n, 0);
  cloud.boundary_id.assign(n, 0);
  const Model m = make_model(cloud, make_scene(2, false, kDx, 3.05));
  const double reach = 3.05 * kDx + 1e-9 * kDx;
  std::set<std::pair<int, int>> expected;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double dx = m.points.position[2 * j] - m.points.position[2 * i];
      const double dy = m.points.position[2 * j + 1] - m.points.position[2 * i + 1];
      if (i != j && dx * dx + dy * dy <= reach * reach) expected.insert({static_cast<int>(i), static_cast<int>(j)});
    }
  EXPECT_EQ(bond_set(m), expected);
}

// The pair index of the damage effect requires every bond between owned points stored at both
// ends: a family with a bond at one end only, or twice at one, is refused.
TEST(SolverFamilies, PairIndexRefusesABondNotStoredAtBothEnds) {
  const Model m = make_model(make_lattice(2, {9, 7, 1}, kDx), make_scene(2, true, kDx, 3.05));
  BondFamilies symmetric = m.bonds;
  EXPECT_NO_THROW(index_bond_pairs(symmetric));
  EXPECT_EQ(symmetric.pair_offset.back(), symmetric.bond_count() / 2);
  // Point 30's last bond dropped from its list (the neighbour keeps its end).
  BondFamilies one_end;
  one_end.dimension = 2;
  one_end.offset.assign(1, 0);
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    for (std::int64_t b = m.bonds.offset[i]; b < m.bonds.offset[i + 1]; ++b)
      if (!(i == 30 && b + 1 == m.bonds.offset[i + 1])) one_end.neighbor.push_back(m.bonds.neighbor[b]);
    one_end.offset.push_back(static_cast<std::int64_t>(one_end.neighbor.size()));
  }
  EXPECT_THROW(index_bond_pairs(one_end), std::logic_error);
  // Point 30's first bond stored twice, and its mirror once.
  BondFamilies twice = m.bonds;
  const auto first = twice.neighbor.begin() + twice.offset[30];
  twice.neighbor.insert(first, *first);
  for (std::size_t i = 31; i < twice.offset.size(); ++i) ++twice.offset[i];
  EXPECT_THROW(index_bond_pairs(twice), std::logic_error);
}

// Points of a d-dimensional lattice of spacing dx from an origin that does not round exactly
// (0.1234 m), with a fifth of the sites left empty at random (holes, notches, a body's outline).
std::vector<double> lattice_with_holes(int d, const std::array<int, 3>& n, double dx, unsigned seed) {
  std::mt19937 random(seed);
  std::bernoulli_distribution keep(0.8);
  std::vector<double> x;
  for (int k = 0; k < (d == 3 ? n[2] : 1); ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (!keep(random)) continue;
        const int site[3] = {i, j, k};
        for (int a = 0; a < d; ++a) x.push_back(0.1234 + (site[a] + 0.5) * dx);
      }
  return x;
}

PointData points_at(int d, const std::vector<double>& x) {
  PointData p;
  p.dimension = d;
  p.position = x;
  p.owned = x.size() / static_cast<std::size_t>(d);
  return p;
}

// Each point's neighbours by the cell search of horizon_search.hpp, sorted: what build_families
// stored before lattices were searched by their sites.
std::vector<std::vector<std::int32_t>> cell_search_families(const PointData& p, double horizon, double dx) {
  const PointPositions positions{p.dimension, p.position.data(), p.total()};
  const double reach = bond_reach(horizon, dx);
  const CellGrid grid = make_grid(positions, reach);
  std::vector<std::vector<std::int32_t>> out(p.owned);
  for (std::size_t i = 0; i < p.owned; ++i) {
    for_each_in_horizon(positions, &grid, {0.0, 0.0, 0.0}, i, reach * reach,
                        [&](std::size_t j, const double*) { out[i].push_back(static_cast<std::int32_t>(j)); });
    std::sort(out[i].begin(), out[i].end());
  }
  return out;
}

std::vector<std::vector<std::int32_t>> stored_families(const BondFamilies& f) {
  std::vector<std::vector<std::int32_t>> out(f.offset.size() - 1);
  for (std::size_t i = 0; i + 1 < f.offset.size(); ++i)
    out[i].assign(&f.neighbor[f.offset[i]], &f.neighbor[f.offset[i + 1]]);
  return out;
}

// On a lattice the families come from the sites (lattice_sites.hpp), and they are the cell search's,
// entry for entry: factor 2.0 and 3.0 put lattice points exactly on the horizon's sphere (kept by the
// 1e-9 dx tolerance in both), 2.05 to 4.05 are the factors the cases use.
TEST(SolverFamilies, LatticeSitesGiveTheCellSearchFamiliesEntryForEntry) {
  for (int d : {2, 3})
    for (double factor : {2.0, 2.05, 3.0, 3.05, 4.05}) {
      const std::array<int, 3> n = d == 2 ? std::array<int, 3>{29, 21, 1} : std::array<int, 3>{13, 11, 9};
      const PointData p = points_at(d, lattice_with_holes(d, n, kDx, 7u + static_cast<unsigned>(factor * 100)));
      const double reach = bond_reach(factor * kDx, kDx);
      ASSERT_TRUE(lattice_sites({d, p.position.data(), p.total()}, kDx, reach).has_value()) << d << " " << factor;
      FamilyOptions o;
      o.horizon = factor * kDx;
      o.spacing = kDx;
      const BondFamilies f = build_families(p, o);
      const auto expected = cell_search_families(p, factor * kDx, kDx);
      EXPECT_EQ(stored_families(f), expected) << "d=" << d << " factor=" << factor;
      std::size_t bonds = 0;
      for (const auto& family : expected) bonds += family.size();
      EXPECT_GT(bonds, p.owned * (d == 2 ? 8u : 20u)) << "the holes left families to compare";
    }
}

// Points off their sites by up to half the site tolerance, and a horizon of 2.995 dx: pairs three
// sites apart (offset (3, 0)) come within it, or not, by their jitter, so the candidates must reach
// past the horizon by the tolerance (a candidate set cut at the horizon misses them).
TEST(SolverFamilies, JitteredLatticeKeepsThePairsItsJitterBringsWithinTheHorizon) {
  for (int d : {2, 3}) {
    const std::array<int, 3> n = d == 2 ? std::array<int, 3>{25, 19, 1} : std::array<int, 3>{11, 10, 9};
    std::vector<double> x = lattice_with_holes(d, n, kDx, 11u);
    std::mt19937 random(13u);
    std::uniform_real_distribution<double> jitter(-0.005 * kDx, 0.005 * kDx);
    for (double& c : x) c += jitter(random);
    const PointData p = points_at(d, x);
    const double horizon = 2.995 * kDx;
    ASSERT_TRUE(lattice_sites({d, p.position.data(), p.total()}, kDx, bond_reach(horizon, kDx)).has_value());
    FamilyOptions o;
    o.horizon = horizon;
    o.spacing = kDx;
    const auto expected = cell_search_families(p, horizon, kDx);
    EXPECT_EQ(stored_families(build_families(p, o)), expected) << "d=" << d;
    // Some pairs three sites apart are bonded, and some are not.
    std::size_t three_apart = 0;
    for (std::size_t i = 0; i < p.owned; ++i)
      for (const std::int32_t j : expected[i]) {
        double r2 = 0.0;
        for (int a = 0; a < d; ++a) r2 += std::pow(x[static_cast<std::size_t>(j) * d + a] - x[i * d + a], 2);
        three_apart += std::sqrt(r2) > 2.9 * kDx;
      }
    EXPECT_GT(three_apart, 0u) << "d=" << d;
  }
}

// Anything that is not one lattice is searched by cells: a jittered lattice, two points on a site,
// a lattice of another spacing, a sparse body (two blocks far apart), a coordinate that is not a
// number (the points reader refuses it; the site map must not take it for a site).
TEST(SolverFamilies, OnlyALatticeIsSearchedBySites) {
  const double reach = bond_reach(3.05 * kDx, kDx);
  std::vector<double> x = lattice_with_holes(2, {15, 12, 1}, kDx, 3u);
  EXPECT_TRUE(lattice_sites({2, x.data(), x.size() / 2}, kDx, reach).has_value());
  EXPECT_FALSE(lattice_sites({2, x.data(), x.size() / 2}, 0.7 * kDx, reach).has_value());
  std::vector<double> jittered = x;
  std::mt19937 random(5u);
  std::uniform_real_distribution<double> jitter(-0.05 * kDx, 0.05 * kDx);
  for (double& c : jittered) c += jitter(random);
  EXPECT_FALSE(lattice_sites({2, jittered.data(), jittered.size() / 2}, kDx, reach).has_value());
  std::vector<double> doubled = x;
  doubled.push_back(x[0]);
  doubled.push_back(x[1]);
  EXPECT_FALSE(lattice_sites({2, doubled.data(), doubled.size() / 2}, kDx, reach).has_value());
  std::vector<double> sparse = x;
  for (std::size_t k = 0; k < x.size(); k += 2) {
    sparse.push_back(x[k] + 400 * kDx);
    sparse.push_back(x[k + 1] + 400 * kDx);
  }
  EXPECT_FALSE(lattice_sites({2, sparse.data(), sparse.size() / 2}, kDx, reach).has_value());
  std::vector<double> not_a_number = x;
  not_a_number[7] = std::nan("");
  EXPECT_FALSE(lattice_sites({2, not_a_number.data(), not_a_number.size() / 2}, kDx, reach).has_value());
  // The cell search gives a jittered cloud its families as before.
  const PointData p = points_at(2, jittered);
  FamilyOptions o;
  o.horizon = 3.05 * kDx;
  o.spacing = kDx;
  EXPECT_EQ(stored_families(build_families(p, o)), cell_search_families(p, 3.05 * kDx, kDx));
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
