// Linear and angular momentum of a free, unloaded body with random initial velocities and spins
// are conserved by the discrete balance laws and the velocity-Verlet integrator (docs/theory.md section 4):
// P = sum rho V v, L = sum (x x rho V v + I V spin) with x the reference position.
#include <gtest/gtest.h>

#include <random>

#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

constexpr double kDx = 1e-3;

struct Momenta {
  std::array<double, 3> linear{0, 0, 0}, angular{0, 0, 0};
  double linear_scale = 0.0, angular_scale = 0.0;  // sums of magnitudes, for relative errors
};

Momenta momenta(const Model& m) {
  const PointData& p = m.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  const double rho = m.constants.density, inertia = m.constants.micro_inertia;
  Momenta out;
  for (std::size_t i = 0; i < p.owned; ++i) {
    double x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int c = 0; c < D; ++c) {
      x[c] = p.position[i * D + c];
      v[c] = rho * p.volume[i] * p.velocity[i * D + c];
      out.linear[c] += v[c];
      out.linear_scale += std::abs(v[c]);
    }
    const double l[3] = {x[1] * v[2] - x[2] * v[1], x[2] * v[0] - x[0] * v[2], x[0] * v[1] - x[1] * v[0]};
    for (int c = 0; c < 3; ++c) {
      out.angular[c] += l[c];
      out.angular_scale += std::abs(l[c]);
    }
    for (int c = 0; c < R; ++c) {
      const double s = inertia * p.volume[i] * p.spin[i * R + c];
      out.angular[R == 1 ? 2 : c] += s;
      out.angular_scale += std::abs(s);
    }
  }
  return out;
}

void check_conservation(int dimension, bool micropolar, std::array<int, 3> n, double horizon_factor) {
  Model m = make_model(make_lattice(dimension, n, kDx), make_scene(dimension, micropolar, kDx, horizon_factor));
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& v : m.points.velocity) v = g(rng);          // 1 m/s
  for (auto& s : m.points.spin) s = 1.0 / kDx * g(rng);  // a rotation rate of the same strain rate
  const CriticalTimeStep critical = critical_time_step(m);
  BoundaryConditions free_body(m.points);
  ExplicitDynamics dynamics(m, free_body, 0.8 * critical.step);
  dynamics.initialize();
  const Momenta start = momenta(m);
  for (int k = 0; k < 300; ++k) dynamics.step(false);
  const Momenta end = momenta(m);
  ASSERT_TRUE(dynamics.finite());
  // The body deformed: the check is not on a trivially unloaded state.
  double moved = 0.0;
  for (double f : m.points.force) moved = std::max(moved, std::abs(f));
  ASSERT_GT(moved, 0.0);
  // Round-off of 300 steps of sums over O(10^3) terms: ~1e-13; the bar is 1e-10, well above it.
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(std::abs(end.linear[c] - start.linear[c]), 1e-10 * start.linear_scale)
        << "D=" << dimension << " micropolar=" << micropolar << " component " << c;
    EXPECT_LT(std::abs(end.angular[c] - start.angular[c]), 1e-10 * start.angular_scale)
        << "D=" << dimension << " micropolar=" << micropolar << " component " << c;
  }
}

TEST(SolverMomentum, Micropolar2D) { check_conservation(2, true, {12, 9, 1}, 3.05); }
TEST(SolverMomentum, NonPolar2D) { check_conservation(2, false, {12, 9, 1}, 3.05); }
TEST(SolverMomentum, Micropolar3D) { check_conservation(3, true, {6, 5, 5}, 2.05); }
TEST(SolverMomentum, NonPolar3D) { check_conservation(3, false, {6, 5, 5}, 2.05); }

}  // namespace
}  // namespace mppm::solver

namespace mppm::solver {
namespace {

// numerics.damping: a mass-proportional damping force -c rho v takes energy out at the rate
// 2 c KE; the energy lost is booked as (negative) external work, so the balance still closes.
TEST(SolverDamping, FreeVibrationDecaysAndTheBalanceAccountsForIt) {
  Model m = make_model(make_lattice(2, {12, 9, 1}, kDx), make_scene(2, true, kDx, 3.05));
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& u : m.points.displacement) u = 1e-7 * g(rng);
  const CriticalTimeStep critical = critical_time_step(m);
  BoundaryConditions free_body(m.points);
  ExplicitDynamics dynamics(m, free_body, 0.5 * critical.step);
  // A damping time of 100 steps.
  dynamics.set_damping(1.0 / (100 * 0.5 * critical.step));
  dynamics.initialize();
  const double e0 = dynamics.energy().total();
  for (int k = 0; k < 999; ++k) dynamics.step(false);
  dynamics.step(true);
  const EnergyState& e = dynamics.energy();
  EXPECT_LT(e.total(), 0.01 * e0);               // mostly dissipated
  EXPECT_NEAR(e.external_work, -e0, 1e-3 * e0);  // ... and booked as the damper's work
  // Trapezoid-rule bookkeeping of the damping work: O((c dt)^2) per step; measured 1e-8 here,
  // 1e-6 bounds it with margin while any missing or double-counted term would be O(1).
  std::printf("damping: remaining %.3g of E0, work %.5g E0, balance error %.3g\n", e.total() / e0, e.external_work / e0,
              dynamics.balance_error());
  EXPECT_LT(std::abs(dynamics.balance_error()), 1e-6);
}

}  // namespace
}  // namespace mppm::solver
