// Boundary conditions (docs/theory.md section 8): exact integration of velocity histories, traction and
// pressure as body force densities that add up to t_bar A, prescribed micro-rotation of a layer,
// and the gravity effect (free fall at g, its work booked as external work).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

constexpr double kDx = 1e-3;

TEST(SolverBoundaryConditions, VelocityHistoriesIntegrateExactly) {
  // ramp to 2 at t = 1, then a table down to -1 at t = 3, then held.
  History h;
  h.times = {0.0, 1.0, 3.0};
  h.values = {{0.0}, {2.0}, {-1.0}};
  // Closed forms of the integral of the piecewise-linear velocity.
  auto exact = [](double t) {
    if (t <= 1.0) return t * t;                                                 // v = 2t
    if (t <= 3.0) return 1.0 + 2.0 * (t - 1.0) - 0.75 * (t - 1.0) * (t - 1.0);  // v = 2 - 1.5 (t-1)
    return 1.0 + 4.0 - 3.0 - (t - 3.0);                                         // v = -1
  };
  for (double t : {0.0, 0.3, 1.0, 1.7, 3.0, 4.5}) EXPECT_NEAR(history_integral(h, t, 0), exact(t), 1e-14) << t;
  EXPECT_DOUBLE_EQ(history_slope(h, 0.5, 0), 2.0);
  EXPECT_DOUBLE_EQ(history_slope(h, 2.0, 0), -1.5);
  EXPECT_DOUBLE_EQ(history_slope(h, 5.0, 0), 0.0);
  // A table that starts after t = 0 holds its first value before it.
  History late;
  late.times = {1.0, 2.0};
  late.values = {{3.0}, {3.0}};
  EXPECT_NEAR(history_integral(late, 2.5, 0), 7.5, 1e-14);
}

// A block with a traction on its top rows, a pressure on its right column and a kinematic
// bottom layer that also prescribes the micro-rotation.
struct Block {
  Scene scene;
  PointCloud cloud;
};

Block block() {
  Block b;
  b.scene = make_scene(2, true, kDx, 3.05);
  b.cloud = make_lattice(2, {12, 12, 1}, kDx, b.scene.thickness);
  std::int64_t top = 0, right = 0, layer = 0;
  for (std::size_t i = 0; i < b.cloud.size(); ++i) {
    if (b.cloud.y[i] < 4 * kDx) {
      b.cloud.region[i] = b.cloud.boundary_id[i] = 3;
      ++layer;
    } else if (b.cloud.y[i] > 11 * kDx) {
      b.cloud.boundary_id[i] = 1;
      b.cloud.normal_y[i] = 1.0;
      ++top;
    } else if (b.cloud.x[i] > 11 * kDx) {
      b.cloud.boundary_id[i] = 2;
      b.cloud.normal_x[i] = 1.0;
      ++right;
    }
  }
  const double t = b.scene.thickness;
  b.cloud.boundaries = {BoundaryInfo{"top", "traction", 12 * kDx * t, top, "", 0.0},
                        BoundaryInfo{"right", "pressure", 8 * kDx * t, right, "", 0.0},
                        BoundaryInfo{"bottom", "displacement", 12 * kDx * t, layer, "", 0.0}};
  BoundaryCondition traction;
  traction.name = "top";
  traction.type = BoundaryType::traction;
  traction.value.times = {0.0, 1e-6};
  traction.value.values = {{0.0, 0.0}, {3e6, -2e6}};
  BoundaryCondition pressure;
  pressure.name = "right";
  pressure.type = BoundaryType::pressure;
  pressure.value.times = {0.0};
  pressure.value.values = {{5e6}};
  BoundaryCondition bottom = testing::kinematic_condition("bottom", BoundaryType::displacement, {0.0}, {{0.0, 0.0}});
  bottom.rotation = History{{0.0, 1e-6}, {{0.0}, {2e-3}}};
  b.scene.boundary_conditions = {traction, pressure, bottom};
  return b;
}

TEST(SolverBoundaryConditions, SurfaceLoadsAddUpToTractionTimesAreaAndRotationIsPrescribed) {
  const Block b = block();
  Model m = make_model(b.cloud, b.scene);
  const BoundaryConditions bc(b.scene, b.cloud, m.points, "block");
  std::vector<double> load(m.points.owned * 2, 0.0);
  bc.add_surface_loads(m.points, 0.5e-6, load);  // half-way up the ramp
  double fx = 0.0, fy = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    fx += load[i * 2] * m.points.volume[i];
    fy += load[i * 2 + 1] * m.points.volume[i];
  }
  const double t = b.scene.thickness;
  // traction 0.5 * (3, -2) MPa on 12 mm; pressure 5 MPa on 8 mm pushing along -x.
  EXPECT_NEAR(fx, 1.5e6 * 12 * kDx * t - 5e6 * 8 * kDx * t, 1e-9 * 5e6 * 8 * kDx * t);
  EXPECT_NEAR(fy, -1e6 * 12 * kDx * t, 1e-9 * 1e6 * 12 * kDx * t);
  const auto values = bc.load_values(m.points, 0.5e-6);
  ASSERT_EQ(values.size(), 3u);
  EXPECT_NEAR(values[0].force[0], 1.5e6 * 12 * kDx * t, 1e-6);
  EXPECT_NEAR(values[1].force[0], -5e6 * 8 * kDx * t, 1e-6);
  // The bottom layer's micro-rotation follows its history; its displacement is held.
  bc.prescribe(m.points, 0.25e-6);
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    if (m.points.region[i] != 3) continue;
    EXPECT_DOUBLE_EQ(m.points.rotation[i], 0.5e-3);
    EXPECT_DOUBLE_EQ(m.points.spin[i], 2e3);
    EXPECT_TRUE(bc.prescribed_rotation(i, 0));
  }
}

TEST(SolverBoundaryConditions, GravityAcceleratesAFreeBodyAtGAndItsWorkIsBooked) {
  Scene s = make_scene(2, true, kDx, 3.05);
  s.effects.gravity = true;
  Model m = make_model(make_lattice(2, {8, 6, 1}, kDx, s.thickness), s);
  BoundaryConditions none(m.points);
  const CriticalTimeStep c = critical_time_step(m);
  const double dt = 0.5 * c.step;
  ExplicitDynamics dynamics(m, none, dt, {0.0, -9.81, 0.0});
  dynamics.initialize();
  const int steps = 100;
  for (int k = 0; k < steps; ++k) dynamics.step(k == steps - 1);
  const double t = steps * dt;
  // A uniform body force leaves the body undeformed: every point falls as 1/2 g t^2.
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    EXPECT_NEAR(m.points.displacement[i * 2 + 1], -0.5 * 9.81 * t * t, 1e-12 * 9.81 * t * t);
    EXPECT_NEAR(m.points.velocity[i * 2 + 1], -9.81 * t, 1e-12 * 9.81 * t);
  }
  EXPECT_GT(dynamics.energy().external_work, 0.0);
  EXPECT_LT(std::abs(dynamics.balance_error()), 1e-9);
}

}  // namespace
}  // namespace mppm::solver
