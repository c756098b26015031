// Forces and moments are minus the gradient of the total discrete energy (docs/theory.md section 4),
// stabilization included, checked by central finite differences in 2-D and 3-D, with and
// without the micropolar effect. This ties the balance laws (reverse-bond states, the
// 1/2 xi x (T_ij - T_ji) moment term, the folded stabilization of both ends) to the energy.
#include <gtest/gtest.h>

#include <random>

#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

constexpr double kDx = 1e-3;

double total_energy(Model& m) {
  m.compute_internal_forces(true);
  return internal_energy(m).total();
}

void check_gradient(int dimension, bool micropolar, std::array<int, 3> n, double horizon_factor) {
  Scene scene = make_scene(dimension, micropolar, kDx, horizon_factor);
  scene.numerics.stabilization = 0.3;  // well above default so that its part of the gradient counts
  Model m = make_model(make_lattice(dimension, n, kDx), scene);
  const int D = dimension;
  const int R = m.points.rotation_components;
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  // A random field: displacements ~1e-4 dx, rotations of comparable strain (1e-4).
  for (auto& u : m.points.displacement) u = 1e-4 * kDx * g(rng);
  for (auto& w : m.points.rotation) w = 1e-4 * g(rng);
  m.compute_internal_forces(true);
  const StoredEnergy e0 = internal_energy(m);
  ASSERT_GT(e0.stabilization, 1e-3 * e0.total()) << "the stabilization must be exercised";
  if (micropolar) {
    ASSERT_GT(e0.couple_stress, 1e-3 * e0.total());
  }
  const std::vector<double> force = m.points.force;
  const std::vector<double> moment = m.points.moment;
  double force_scale = 0.0, moment_scale = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    for (int c = 0; c < D; ++c) force_scale = std::max(force_scale, std::abs(force[i * D + c]) * m.points.volume[i]);
    for (int c = 0; c < R; ++c) moment_scale = std::max(moment_scale, std::abs(moment[i * R + c]) * m.points.volume[i]);
  }
  // The energy is quadratic, so central differences are exact up to round-off; with steps of
  // 1e-2 of the field size the round-off relative to the largest force is ~1e-12. 1e-7 leaves
  // ample room for that and still catches any wrong term (those are O(1) relative).
  constexpr double kTolerance = 1e-7;
  auto probe = [&](std::vector<double>& field, std::size_t k, double h) {
    const double saved = field[k];
    field[k] = saved + h;
    const double ep = total_energy(m);
    field[k] = saved - h;
    const double em = total_energy(m);
    field[k] = saved;
    return -(ep - em) / (2.0 * h);
  };
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    for (int c = 0; c < D; ++c) {
      const double fd = probe(m.points.displacement, i * D + c, 1e-6 * kDx);
      ASSERT_NEAR(force[i * D + c] * m.points.volume[i], fd, kTolerance * force_scale)
          << "D=" << D << " micropolar=" << micropolar << " point " << i << " component " << c;
    }
    for (int c = 0; c < R; ++c) {
      const double fd = probe(m.points.rotation, i * R + c, 1e-6);
      ASSERT_NEAR(moment[i * R + c] * m.points.volume[i], fd, kTolerance * moment_scale)
          << "D=" << D << " point " << i << " rotation component " << c;
    }
  }
}

TEST(SolverEnergyGradient, Micropolar2D) { check_gradient(2, true, {7, 6, 1}, 3.05); }
TEST(SolverEnergyGradient, NonPolar2D) { check_gradient(2, false, {7, 6, 1}, 3.05); }
TEST(SolverEnergyGradient, Micropolar3D) { check_gradient(3, true, {5, 4, 4}, 2.05); }
TEST(SolverEnergyGradient, NonPolar3D) { check_gradient(3, false, {5, 4, 4}, 2.05); }

}  // namespace
}  // namespace mppm::solver
