// The damage effect (docs/theory.md section 7) beyond its calibration (verification/test_solver_crack_energy):
// a body shattered by a violent velocity field stays finite, conserves momentum and closes its
// energy balance, its detached points move ballistically, and breakage is the same bits on 1 and 2
// threads; the closed-form stiffness block of point_stability.hpp equals the kernel's; a point left
// with a badly conditioned family is detached for the time step's sake; an overloaded point is
// detached when losing bonds raises its energy at all.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "solver/bond_breakage.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/point_stability.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

constexpr double kDx = 1e-3;

Scene damage_scene(int dimension, double g_cr) {
  Scene s = testing::make_scene(dimension, true, kDx, dimension == 2 ? 3.05 : 2.05);
  s.effects.damage = true;
  s.material.damage = DamageParameters{g_cr, 0.0, DamageCalibration::lattice, std::nullopt};
  return s;
}

struct ShatterRun {
  Model model;
  double balance_error = 0.0;
  std::array<double, 3> momentum_start{}, momentum_end{};
  double momentum_scale = 0.0;
  std::vector<double> detached_velocity;  // of the points detached at the end, one step earlier
  bool finite = true;
};

std::array<double, 3> momentum(const Model& m, double* scale = nullptr) {
  std::array<double, 3> out{0, 0, 0};
  const int D = m.dimension();
  for (std::size_t i = 0; i < m.points.owned; ++i)
    for (int c = 0; c < D; ++c) {
      const double v = m.constants.density * m.points.volume[i] * m.points.velocity[i * D + c];
      out[c] += v;
      if (scale) *scale += std::abs(v);
    }
  return out;
}

// A free lattice given a random velocity field of `speed` (an impact from every side at once):
// with a small G_cr most bonds break and many points lose all of theirs.
ShatterRun shatter(int dimension, std::array<int, 3> n, double speed, int steps, const Scene& scene) {
  ShatterRun r{testing::make_model(testing::make_lattice(dimension, n, kDx), scene), 0.0, {}, {}, 0.0, {}, true};
  Model& m = r.model;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& v : m.points.velocity) v = speed * g(rng);
  // The step of an undamaged model when damage is off (the same step for runs compared bit for bit).
  const double critical = critical_time_step(m).step;
  const double dt = 0.8 * (scene.effects.damage ? m.damage_critical_step(critical) : critical);
  m.set_breakage_time_step(dt);
  BoundaryConditions free_body(m.points);
  ExplicitDynamics dynamics(m, free_body, dt);
  dynamics.initialize();
  r.momentum_start = momentum(m, &r.momentum_scale);
  for (int k = 0; k < steps; ++k) dynamics.step(k == steps - 1);
  const int D = m.dimension();
  for (std::size_t i = 0; i < m.points.owned; ++i)
    if (m.points.detached[i])
      for (int c = 0; c < D; ++c) r.detached_velocity.push_back(m.points.velocity[i * D + c]);
  dynamics.step(true);
  r.finite = dynamics.finite();
  r.balance_error = dynamics.balance_error();
  r.momentum_end = momentum(m);
  return r;
}

ShatterRun shatter(int dimension, std::array<int, 3> n, double speed, int steps) {
  return shatter(dimension, n, speed, steps, damage_scene(dimension, 0.5));
}

void check_shatter(int dimension, std::array<int, 3> n, double speed) {
  ShatterRun r = shatter(dimension, n, speed, 200);
  const Model& m = r.model;
  std::printf(
      "%d-D shatter: %zu points, %zu of %zu bond pairs broken, %zu detached (%zu for the time step), balance "
      "error %.2g\n",
      dimension, m.points.owned, m.broken_bonds, m.bonds.bond_count() / 2, m.detached_points,
      m.unstable_detached_points, r.balance_error);
  ASSERT_TRUE(r.finite);
  for (double v : m.points.displacement) ASSERT_TRUE(std::isfinite(v));
  for (double v : m.points.rotation) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(m.broken_bonds, m.bonds.bond_count() / 10);  // the hazard did happen
  EXPECT_GT(m.detached_points, 10u);
  // Broken bonds keep their entries (sign bit): a point's pairs stay the tail of its sorted list,
  // where the kernel's shortcut and the bisection both find them.
  for (std::size_t i = 0; i < m.points.owned; ++i) ASSERT_EQ(m.bonds.first_pair_bond(i), first_bond_above(m.bonds, i));
  // Detached points carry no force and move ballistically: their velocity did not change over
  // the last step.
  std::size_t k = 0;
  const int D = m.dimension();
  for (std::size_t i = 0; i < m.points.owned; ++i)
    if (m.points.detached[i])
      for (int c = 0; c < D; ++c, ++k) {
        if (k >= r.detached_velocity.size()) break;  // detached in the very last step
        EXPECT_EQ(m.points.force[i * D + c], 0.0);
      }
  // Breakage removes bonds from both ends at once, so the pair forces stay equal and opposite:
  // momentum is conserved to round-off (1e-10 of the sum of magnitudes, as without damage).
  for (int c = 0; c < D; ++c) EXPECT_LT(std::abs(r.momentum_end[c] - r.momentum_start[c]), 1e-10 * r.momentum_scale);
  // The breaks' dissipation closes the energy balance (bond_breakage.hpp): round-off.
  EXPECT_LT(std::abs(r.balance_error), 1e-9);
}

// The no-fail zone (bond_breakage.hpp): the points nearer than the depth to a boundary point, the
// squared distance summed over the axes in order and compared strictly, as a search of every
// boundary point for every point decides it.
std::vector<std::uint8_t> no_fail_by_every_pair(const PointData& p, double depth, std::int32_t ignored) {
  const int D = p.dimension;
  std::vector<std::uint8_t> out(p.owned, 0);
  for (std::size_t i = 0; i < p.owned; ++i)
    for (std::size_t b = 0; b < p.owned && !out[i]; ++b) {
      if (p.boundary_id[b] <= 0 || p.boundary_id[b] == ignored) continue;
      double r2 = 0.0;
      for (int a = 0; a < D; ++a)
        r2 += (p.position[i * D + a] - p.position[b * D + a]) * (p.position[i * D + a] - p.position[b * D + a]);
      out[i] = r2 < depth * depth ? 1 : 0;
    }
  return out;
}

PointData points_with_boundaries(int dimension, std::vector<double> position, std::vector<std::int32_t> id) {
  PointData p;
  p.dimension = dimension;
  p.owned = id.size();
  p.position = std::move(position);
  p.boundary_id = std::move(id);
  p.no_fail.assign(p.owned, 7);
  return p;
}

TEST(SolverDamage, NoFailZoneHoldsThePointsNearerThanTheDepthToABoundaryPoint) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const int D : {2, 3}) {
    // A random cloud (with a few points far outside the boundary points' box), boundary ids 1 and 2
    // (2 ignored, as the pore fluid's own boundaries are), and depths from a hair to most of the box.
    std::vector<double> x;
    std::vector<std::int32_t> id;
    for (int k = 0; k < 1500; ++k) {
      for (int a = 0; a < D; ++a) x.push_back(k < 10 ? 5.0 * unit(rng) - 2.0 : unit(rng));
      const double r = unit(rng);
      id.push_back(k >= 10 && r < 0.05 ? 1 : (k >= 10 && r < 0.08 ? 2 : 0));
    }
    PointData p = points_with_boundaries(D, x, id);
    for (const double depth : {1e-9, 0.01, 0.07, 0.3, 2.0}) {
      mark_no_fail_zone(p, depth, {2});
      EXPECT_EQ(p.no_fail, no_fail_by_every_pair(p, depth, 2)) << D << "-D, depth " << depth;
    }
    mark_no_fail_zone(p, 0.0, {2});
    EXPECT_EQ(std::count(p.no_fail.begin(), p.no_fail.end(), 1), 0) << "no depth, no zone";
  }
  // On a lattice of unit spacing (exact squared distances) the points exactly at the depth from
  // the boundary row stay out of the zone.
  std::vector<double> x;
  std::vector<std::int32_t> id;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      x.insert(x.end(), {static_cast<double>(i), static_cast<double>(j)});
      id.push_back(j == 0 ? 1 : 0);
    }
  PointData lattice = points_with_boundaries(2, x, id);
  mark_no_fail_zone(lattice, 2.0, {});
  for (int j = 0; j < 8; ++j)
    EXPECT_EQ(lattice.no_fail[static_cast<std::size_t>(j * 8 + 3)], j < 2 ? 1 : 0) << "row " << j;
  EXPECT_EQ(lattice.no_fail, no_fail_by_every_pair(lattice, 2.0, 0));
}

TEST(SolverDamage, ShatteredBodyStaysFiniteAndConservesMomentum2d) { check_shatter(2, {24, 24, 1}, 10.0); }
TEST(SolverDamage, ShatteredBodyStaysFiniteAndConservesMomentum3d) { check_shatter(3, {10, 10, 10}, 0.5); }

// Same bits for 1 and 2 threads, with the parallel thresholds lowered so that every loop really
// runs on two threads.
TEST(SolverDamage, BreakageIsIdenticalOnOneAndTwoThreads) {
  const ParallelThresholds saved = parallel_thresholds();
  parallel_thresholds() = ParallelThresholds{1, 1, 1};
  omp_set_num_threads(1);
  const ShatterRun one = shatter(2, {24, 24, 1}, 10.0, 100);
  omp_set_num_threads(2);
  const ShatterRun two = shatter(2, {24, 24, 1}, 10.0, 100);
  parallel_thresholds() = saved;
  auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  ASSERT_GT(one.model.broken_bonds, 0u);
  EXPECT_EQ(one.model.broken_bonds, two.model.broken_bonds);
  EXPECT_EQ(one.model.bonds.neighbor, two.model.bonds.neighbor);  // with the broken bonds marked
  EXPECT_TRUE(same(one.model.bonds.work, two.model.bonds.work));
  EXPECT_TRUE(same(one.model.points.displacement, two.model.points.displacement));
  EXPECT_TRUE(same(one.model.points.rotation, two.model.points.rotation));
  EXPECT_EQ(std::memcmp(&one.balance_error, &two.balance_error, sizeof(double)), 0);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// material.damage.region: a bond with an end outside the box never breaks (and its work is not
// booked), bonds inside break as without a region.
TEST(SolverDamage, RegionLimitsBreakageToItsBox) {
  Scene scene = damage_scene(2, 0.5);
  Selector left;
  left.box = std::array<std::array<double, 3>, 2>{{{-1.0, -1.0, -1.0}, {12e-3, 1.0, 1.0}}};  // x < 12 of 24 mm
  scene.material.damage->region = left;
  const ShatterRun r = shatter(2, {24, 24, 1}, 10.0, 100, scene);
  const Model& m = r.model;
  ASSERT_TRUE(r.finite);
  std::size_t broken_inside = 0;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    for (auto b = m.bonds.offset[i]; b < m.bonds.offset[i + 1]; ++b) {
      const std::size_t j = m.bonds.neighbor_of(b);
      const bool outside = m.points.position[i * 2] > 12e-3 || m.points.position[j * 2] > 12e-3;
      if (outside) {
        ASSERT_TRUE(m.bonds.acting(b)) << "bond " << i << "-" << j << " with an end outside the region broke";
        ASSERT_EQ(bond_work(m.bonds, i, b), 0.0);
      } else if (!m.bonds.acting(b)) {
        ++broken_inside;
      }
    }
  // The shatter breaks more than a tenth of all bonds without a region (check_shatter): inside the
  // half that may break, it still does.
  EXPECT_GT(broken_inside, m.bonds.bond_count() / 20);
  EXPECT_LT(std::abs(r.balance_error), 1e-9);
}

// A region holding the whole body is no region: the same bits.
TEST(SolverDamage, RegionHoldingTheBodyChangesNothing) {
  Scene scene = damage_scene(2, 0.5);
  Selector all;
  all.box = std::array<std::array<double, 3>, 2>{{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}}};
  scene.material.damage->region = all;
  const ShatterRun with = shatter(2, {24, 24, 1}, 10.0, 60, scene);
  const ShatterRun without = shatter(2, {24, 24, 1}, 10.0, 60);
  ASSERT_GT(without.model.broken_bonds, 0u);
  EXPECT_EQ(with.model.bonds.neighbor, without.model.bonds.neighbor);  // with the broken bonds marked
  EXPECT_TRUE(same_bits(with.model.points.displacement, without.model.points.displacement));
  EXPECT_TRUE(same_bits(with.model.points.rotation, without.model.points.rotation));
}

// The damage effect on but inactive (an enormous G_cr) moves the body exactly as the
// model without it, at the same time step (the damage step bound is not applied to the run
// without damage, so the damaged run is given the same step).
TEST(SolverDamage, EnormousCriticalEnergyGivesTheUndamagedRunBitForBit) {
  for (int d : {2, 3}) {
    const std::array<int, 3> n = d == 2 ? std::array<int, 3>{16, 16, 1} : std::array<int, 3>{7, 7, 7};
    Scene off = damage_scene(d, 1e30);
    off.effects.damage = false;
    off.material.damage.reset();
    ShatterRun undamaged = shatter(d, n, 0.05, 80, off);
    // The same step: the one of the undamaged model.
    Scene on = damage_scene(d, 1e30);
    Model m = testing::make_model(testing::make_lattice(d, n, kDx), on);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    for (auto& v : m.points.velocity) v = 0.05 * g(rng);
    const double dt = 0.8 * critical_time_step(m).step;
    m.set_breakage_time_step(dt);
    BoundaryConditions free_body(m.points);
    ExplicitDynamics dynamics(m, free_body, dt);
    dynamics.initialize();
    for (int k = 0; k < 81; ++k) dynamics.step(k >= 79);
    EXPECT_EQ(m.broken_bonds, 0u);
    EXPECT_TRUE(same_bits(m.points.displacement, undamaged.model.points.displacement)) << d << "-D";
    EXPECT_TRUE(same_bits(m.points.velocity, undamaged.model.points.velocity)) << d << "-D";
    EXPECT_TRUE(same_bits(m.points.rotation, undamaged.model.points.rotation)) << d << "-D";
  }
}

// The closed-form block H_i equals the kernel's own stiffness: with every other point at rest,
// moving point i by q gives the forces f V = -H q on it (the kernel is linear in u and w).
TEST(SolverDamage, StiffnessBlockMatchesTheKernel) {
  for (int dimension : {2, 3}) {
    ShatterRun r = shatter(dimension, dimension == 2 ? std::array<int, 3>{16, 16, 1} : std::array<int, 3>{8, 8, 8},
                           dimension == 2 ? 8.0 : 0.3, 60);
    Model& m = r.model;
    PointData& p = m.points;
    const int D = p.dimension, R = p.rotation_components, N = D + R;
    int checked = 0;
    for (std::size_t i = 0; i < p.owned && checked < 12; i += 7) {
      if (p.detached[i]) continue;
      std::vector<double> block(static_cast<std::size_t>(N * N));
      point_stiffness_block(p, m.bonds, m.constants, i, block.data());
      double scale = 0.0;
      for (double v : block) scale = std::max(scale, std::abs(v));
      for (int q = 0; q < N; ++q) {
        std::fill(p.displacement.begin(), p.displacement.end(), 0.0);
        std::fill(p.rotation.begin(), p.rotation.end(), 0.0);
        if (q < D)
          p.displacement[i * D + q] = 1.0;
        else
          p.rotation[i * R + (q - D)] = 1.0;
        m.compute_internal_forces();
        for (int row = 0; row < N; ++row) {
          const double f = row < D ? p.force[i * D + row] : p.moment[i * R + (row - D)];
          EXPECT_NEAR(block[static_cast<std::size_t>(row * N + q)], -f * p.volume[i], 1e-9 * scale)
              << "D=" << dimension << " point " << i << " entry " << row << "," << q;
        }
      }
      ++checked;
    }
    EXPECT_GE(checked, 8);
  }
}

// Leaves bond b of point i as the kernel leaves a bond that reached its critical work: the
// pair's work at w_cr and the break counted at the pair's lower-index end.
void leave_as_reached_critical_work(PointData& p, BondFamilies& f, const CosseratConstants& c, std::size_t i,
                                    std::int64_t b) {
  const std::size_t j = f.neighbor_of(b);
  const std::size_t low = std::min(i, j);
  const std::int64_t entry = low == i ? b : mirror_bond(f, i, j);
  f.work[static_cast<std::size_t>(f.pair_offset[low] + (entry - first_bond_above(f, low)))] = c.critical_bond_work;
  ++p.bonds_broken[low];
}

// A point whose family is reduced to nearly collinear bonds (reciprocal condition number above
// the singular limit of 1e-6, so not detached for singularity) has a stiffness block far above
// what the time step allows and is detached, with its remaining bonds; with no limit it stays.
TEST(SolverDamage, BadlyConditionedPointIsDetachedForTheTimeStep) {
  for (bool with_limit : {true, false}) {
    Model m = testing::make_model(testing::make_lattice(2, {15, 15, 1}, kDx), damage_scene(2, 100.0));
    const double critical = critical_time_step(m).step;
    const double start_max = max_point_block_eigenvalue(m.points, m.bonds, m.constants);
    if (with_limit) m.set_breakage_time_step(0.8 * m.damage_critical_step(critical));
    PointData& p = m.points;
    BondFamilies& f = m.bonds;
    const std::size_t centre = 7 * 15 + 7;
    // Keep the bonds along the x axis and the one with offset (2, 1): break the rest (K_i is then
    // [[32, 2], [2, 1]] V dx^2, reciprocal condition number 0.027, against 1 for the full family),
    // as the kernel leaves a bond that reached its critical work: the pair's work at w_cr and the
    // break counted at its lower end.
    std::fill(p.bonds_broken.begin(), p.bonds_broken.end(), 0);
    for (std::int64_t b = f.offset[centre]; b < f.offset[centre + 1]; ++b) {
      double xi[3];
      bond_vector(f, p, centre, b, xi);
      const double ax = xi[0] / kDx, ay = xi[1] / kDx;
      const bool keep = std::abs(ay) < 0.5 || (std::abs(ax - 2) < 0.1 && std::abs(ay - 1) < 0.1);
      if (keep) continue;
      leave_as_reached_critical_work(p, f, m.constants, centre, b);
    }
    const BreakageUpdate u =
        update_after_breakage(p, f, m.constants, m.kernel, m.block_eigenvalue_limit, m.breakage_workspace);
    if (with_limit) {
      EXPECT_TRUE(p.detached[centre]);
      EXPECT_GE(u.unstable_detached, 1u);
      for (std::int64_t b = f.offset[centre]; b < f.offset[centre + 1]; ++b) EXPECT_FALSE(f.acting(b));
    } else {
      EXPECT_FALSE(p.detached[centre]);
      // What the rule saw: far above the start-up maximum times the step's margin (2^2).
      EXPECT_GT(point_block_eigenvalue(p, f, m.constants, centre), 4.0 * start_max);
    }
  }
}

// The centre of a lattice under u_x = e (s + s^2 / (20 dx)) (s = x - x_centre) loses the bonds on
// one side: the right side reads a larger strain (its energy rises by 22 %), the left a smaller one
// (falls by 20 %). `load` is its stored energy before the loss over its family's breaking energy:
// the stored energy does not depend on w_cr, so w_cr sets how overloaded the centre is. Every other
// point is no-fail: the rule is seen on the centre alone, without a cascade (the bonds are left at
// their critical work by hand: the kernel books no work on bonds with a no-fail end).
struct OneSidedLoss {
  bool detached = false;
  std::size_t energy_detached = 0;
  double energy_ratio = 0.0;  // after / before, if not detached
};
OneSidedLoss lose_one_side(double load, bool keep_right, const Numerics& numerics = {},
                           CompressedBonds compressed = CompressedBonds::break_) {
  Scene scene = damage_scene(2, 100.0);
  scene.numerics = numerics;
  scene.material.damage->compressed_bonds = compressed;
  Model m = testing::make_model(testing::make_lattice(2, {15, 15, 1}, kDx), scene);
  PointData& p = m.points;
  BondFamilies& f = m.bonds;
  const std::size_t centre = 7 * 15 + 7;
  const double xc = p.position[centre * 2];
  for (std::size_t i = 0; i < p.owned; ++i) {
    const double s = p.position[i * 2] - xc;
    p.displacement[i * 2] = 1e-3 * (s + 0.05 * s * s / kDx);
  }
  const double before = m.kernel.point_energy(p, f, m.constants, centre).total();
  m.constants.critical_bond_work = 1.0;
  m.constants.critical_bond_work = before / (load * family_breaking_energy(p, f, m.constants, centre));
  EXPECT_NEAR(before / family_breaking_energy(p, f, m.constants, centre), load, 1e-12);
  std::fill(p.no_fail.begin(), p.no_fail.end(), 1);
  p.no_fail[centre] = 0;
  std::fill(p.bonds_broken.begin(), p.bonds_broken.end(), 0);
  for (std::int64_t b = f.offset[centre]; b < f.offset[centre + 1]; ++b) {
    double xi[3];
    bond_vector(f, p, centre, b, xi);
    if (keep_right ? xi[0] >= 0.0 : xi[0] <= 0.0) continue;
    leave_as_reached_critical_work(p, f, m.constants, centre, b);
  }
  const BreakageUpdate u = update_after_breakage(p, f, m.constants, m.kernel, 0.0, m.breakage_workspace);
  OneSidedLoss out;
  out.detached = p.detached[centre];
  out.energy_detached = u.energy_detached;
  if (!out.detached) out.energy_ratio = m.kernel.point_energy(p, f, m.constants, centre).total() / before;
  return out;
}

// A point that stores more than numerics.overload_factor times its family's breaking energy is
// detached when losing bonds raises its stored energy at all, by less than
// numerics.detach_energy_rise too; below that multiple, or when its energy falls, it stays
// (finding 8 of tests/stability/README.md: points crushed at a striker's edges ratcheted up by
// less than 50 % per loss).
TEST(SolverDamage, OverloadedPointIsDetachedWhenLosingBondsRaisesItsEnergyAtAll) {
  struct Case {
    const char* what;
    double load;      // stored energy before the loss / family breaking energy
    bool keep_right;  // the bonds kept: those with xi_x >= 0 (the energy rises) or <= 0 (falls)
    bool detached;    // expected
  };
  const Case cases[] = {{"overloaded, energy rises", 2.0, true, true},
                        {"not overloaded, energy rises", 1.0, true, false},
                        {"overloaded, energy falls", 2.0, false, false}};
  double rise_ratio = 0.0, fall_ratio = 0.0;
  for (const Case& k : cases) {
    const OneSidedLoss r = lose_one_side(k.load, k.keep_right);
    EXPECT_EQ(r.detached, k.detached) << k.what;
    EXPECT_EQ(r.energy_detached, k.detached ? 1u : 0u) << k.what;
    if (!r.detached) (k.keep_right ? rise_ratio : fall_ratio) = r.energy_ratio;
  }
  std::printf("centre's energy after / before the loss: %.4f keeping the right side, %.4f the left\n", rise_ratio,
              fall_ratio);
  // What makes the first case this rule's: a rise the relative margin lets through.
  EXPECT_GT(rise_ratio, 1.0);
  EXPECT_LT(rise_ratio, 1.0 + Numerics{}.detach_energy_rise);
  EXPECT_GT(fall_ratio, 0.0);
  EXPECT_LT(fall_ratio, 1.0);
}

// With compressed_bonds: hold the overload rule is off (a material whose compressed bonds cannot
// fail is not crushed, and the rule took compressive energy for crushing): the overloaded point of
// the first case above stays, its energy rising by less than detach_energy_rise; a larger rise
// still detaches it.
TEST(SolverDamage, OverloadRuleIsOffWhenCompressedBondsHold) {
  const OneSidedLoss held = lose_one_side(2.0, true, {}, CompressedBonds::hold);
  EXPECT_FALSE(held.detached);
  EXPECT_GT(held.energy_ratio, 1.0);
  Numerics strict;
  strict.detach_energy_rise = 0.1;  // below the 22 % rise of this loss
  EXPECT_TRUE(lose_one_side(2.0, true, strict, CompressedBonds::hold).detached);
}

// The thresholds come from the scene's numerics block: a rise of 22 % detaches a point that is not
// overloaded once detach_energy_rise is below it, and the overloaded point of the first case above
// stays once overload_factor is above its load.
TEST(SolverDamage, DetachThresholdsFollowTheSceneNumerics) {
  Numerics strict;
  strict.detach_energy_rise = 0.1;
  EXPECT_FALSE(lose_one_side(1.0, true).detached);
  EXPECT_TRUE(lose_one_side(1.0, true, strict).detached);
  Numerics tolerant;
  tolerant.overload_factor = 3.0;
  EXPECT_TRUE(lose_one_side(2.0, true).detached);
  EXPECT_FALSE(lose_one_side(2.0, true, tolerant).detached);
}

// A smaller damaged_frequency_ratio allows a larger time step for a damage run (by the square root
// of the ratio of the two ratios), and a larger stiffness block before a point is detached.
TEST(SolverDamage, DamagedFrequencyRatioSetsTheDamageTimeStep) {
  Scene scene = damage_scene(2, 100.0);
  Model standard = testing::make_model(testing::make_lattice(2, {12, 12, 1}, kDx), scene);
  scene.numerics.damaged_frequency_ratio = 2.0;
  Model relaxed = testing::make_model(testing::make_lattice(2, {12, 12, 1}, kDx), scene);
  const double critical = critical_time_step(standard).step;
  const double dt_standard = standard.damage_critical_step(critical);
  const double dt_relaxed = relaxed.damage_critical_step(critical);
  ASSERT_LT(dt_relaxed, critical);  // still the damage bound, not the start-up critical step
  EXPECT_NEAR(dt_relaxed / dt_standard, std::sqrt(3.5 / 2.0), 1e-12);
  standard.set_breakage_time_step(1e-7);
  relaxed.set_breakage_time_step(1e-7);
  EXPECT_NEAR(relaxed.block_eigenvalue_limit / standard.block_eigenvalue_limit, 3.5 / 2.0, 1e-12);
}

// A lattice under the homogeneous displacement u = strain x, every bond given twice the critical
// work and counted as the kernel counts it; then the breakage update decides.
BreakageUpdate break_at_critical_work(double strain, CompressedBonds compressed, Model& m) {
  Scene scene = damage_scene(2, 0.5);
  scene.material.damage->compressed_bonds = compressed;
  m = testing::make_model(testing::make_lattice(2, {12, 12, 1}, kDx), scene);
  for (std::size_t i = 0; i < m.points.owned * 2; ++i) m.points.displacement[i] = strain * m.points.position[i];
  m.kernel.forces(m.points, m.bonds, m.constants, nullptr);
  for (double& w : m.bonds.work) w = 2.0 * m.constants.critical_bond_work;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    m.points.bonds_broken[i] = static_cast<std::int32_t>(m.bonds.offset[i + 1] - m.bonds.first_pair_bond(i));
  return update_after_breakage(m.points, m.bonds, m.constants, m.kernel, 0.0, m.breakage_workspace);
}

// material.damage.compressed_bonds: hold: bonds at their critical work break only when stretched,
// |xi + U| > |xi|. Squeezed (every bond shorter) none breaks; pulled every one does; with `break`
// all break either way.
TEST(SolverDamage, CompressedBondsHoldUntilStretched) {
  Model m;
  const std::size_t pairs = [] {
    Model probe;
    break_at_critical_work(0.0, CompressedBonds::break_, probe);
    return probe.bonds.bond_count() / 2;
  }();
  EXPECT_EQ(break_at_critical_work(-1e-3, CompressedBonds::hold, m).broken_pairs, 0u);
  for (std::size_t i = 0; i < m.points.owned; ++i) EXPECT_EQ(m.points.detached[i], 0) << i;
  EXPECT_EQ(break_at_critical_work(-1e-3, CompressedBonds::break_, m).broken_pairs, pairs);
  EXPECT_EQ(break_at_critical_work(1e-3, CompressedBonds::hold, m).broken_pairs, pairs);
  EXPECT_EQ(break_at_critical_work(1e-3, CompressedBonds::break_, m).broken_pairs, pairs);
}

// In a run: a free body set expanding breaks its first bonds in the same step and the same bits
// with `hold` as with `break` (the candidates of a homogeneous expansion are all stretched).
ShatterRun expand_until_first_break(CompressedBonds compressed) {
  Scene scene = damage_scene(2, 0.5);
  scene.material.damage->compressed_bonds = compressed;
  ShatterRun r{testing::make_model(testing::make_lattice(2, {24, 24, 1}, kDx), scene), 0.0, {}, {}, 0.0, {}, true};
  Model& m = r.model;
  constexpr double kRate = 2500.0;  // 1/s: the edges move out at 30 m/s
  for (std::size_t i = 0; i < m.points.owned; ++i)
    for (int c = 0; c < 2; ++c) m.points.velocity[i * 2 + c] = kRate * (m.points.position[i * 2 + c] - 11.5e-3);
  const double dt = 0.8 * m.damage_critical_step(critical_time_step(m).step);
  m.set_breakage_time_step(dt);
  BoundaryConditions free_body(m.points);
  ExplicitDynamics dynamics(m, free_body, dt);
  dynamics.initialize();
  for (int k = 0; k < 200 && m.broken_bonds == 0; ++k) dynamics.step(true);
  r.finite = dynamics.finite();
  return r;
}

TEST(SolverDamage, CompressedBondsHoldChangesNoTensileBreak) {
  const ShatterRun pulled = expand_until_first_break(CompressedBonds::break_);
  const ShatterRun held = expand_until_first_break(CompressedBonds::hold);
  ASSERT_GT(pulled.model.broken_bonds, 0u);
  EXPECT_EQ(held.model.broken_bonds, pulled.model.broken_bonds);
  EXPECT_EQ(held.model.bonds.neighbor, pulled.model.bonds.neighbor);
  EXPECT_TRUE(same_bits(held.model.points.displacement, pulled.model.points.displacement));
}

}  // namespace
}  // namespace mppm::solver
