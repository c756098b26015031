// Energy bookkeeping of an elastic wave case (docs/theory.md section 9): a bar held at one end is hit by a
// velocity pulse of the other end's layer; the pulse runs back and forth for 10^4 steps. The
// kinetic (translational + rotational), elastic and stabilization energies must account for the
// external work of the prescribed layer (trapezoid rule on reaction . increment) to 0.5 %.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::add_end_layers;
using testing::kinematic_condition;
using testing::make_lattice;
using testing::make_scene;

constexpr double kDx = 1e-3;

void check_balance(bool micropolar) {
  const std::array<int, 3> n{48, 8, 1};
  Scene scene = make_scene(2, micropolar, kDx, 3.05);
  PointCloud cloud = make_lattice(2, n, kDx, scene.thickness);
  add_end_layers(cloud, n[0], 4, "displacement", "velocity");
  // A triangular velocity pulse of the right layer (x and y: longitudinal and shear waves).
  const double t1 = 10e-6;
  scene.boundary_conditions = {
      kinematic_condition("left", BoundaryType::displacement, {0.0}, {{0.0, 0.0}}),
      kinematic_condition("right", BoundaryType::velocity, {0.0, t1, 2 * t1}, {{0.0, 0.0}, {1.0, 0.5}, {0.0, 0.0}})};
  Model model = testing::make_model(cloud, scene);
  const BoundaryConditions conditions(scene, cloud, model.points, "bar");
  const CriticalTimeStep critical = critical_time_step(model);
  ExplicitDynamics dynamics(model, conditions, 0.8 * critical.step);
  dynamics.initialize();
  double worst = 0.0;
  constexpr int kSteps = 10000;
  for (int k = 1; k <= kSteps; ++k) {
    const bool check = k % 10 == 0;
    dynamics.step(check);
    if (check) worst = std::max(worst, std::abs(dynamics.balance_error()));
  }
  ASSERT_TRUE(dynamics.finite());
  const EnergyState& e = dynamics.energy();
  std::printf("energy balance (micropolar %d): %d steps to t = %g s, external work %.4g J, worst balance error %.3g\n",
              micropolar, kSteps, dynamics.time(), e.external_work, worst);
  // The pulse did work and left the bar vibrating (the check is not on a quiet bar).
  EXPECT_GT(e.external_work, 0.0);
  EXPECT_GT(e.kinetic, 0.05 * e.external_work);
  if (micropolar) {
    EXPECT_GT(e.rotational_kinetic, 0.0);
  }
  EXPECT_LT(worst, 0.005);
}

TEST(SolverEnergyBalance, ElasticWaveMicropolar) { check_balance(true); }
TEST(SolverEnergyBalance, ElasticWaveNonPolar) { check_balance(false); }

}  // namespace
}  // namespace mppm::solver
