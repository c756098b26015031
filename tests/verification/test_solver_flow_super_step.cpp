// Verification of the flow's RKL2 super-time-stepping (docs/theory.md section 12):
// - the stage count is the fewest whose stability interval holds the step with the margin 0.9;
// - the stage coefficients give the method's polynomial, R_s(z) = 1 - b_s + b_s P_s(1 + w1 z) (P_s
//   Legendre's, computed here by its own three-term recurrence), bounded by 1 on the interval
//   [-(s^2 + s - 2) / 2, 0], growing beyond it, and second order (local error O(z^3));
// - on a periodic lattice one super step multiplies a cosine mode by R_s(-lambda_k tau), and super
//   steps of half the length cut the error against the exact decay exp(-lambda_k t) fourfold.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/flow_super_step.hpp"
#include "solver/pore_fluid.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

// The stability interval's length (s^2 + s - 2) / 2 in units of tau L (L the largest |eigenvalue|).
double interval_length(std::int64_t s) { return 0.5 * static_cast<double>(s * s + s - 2); }

// The super step applied to y' = z y over tau = 1 from y = 1, with the stage coefficients.
double amplification(std::int64_t s, double z) {
  const Rkl2Coefficients c = rkl2_coefficients(s);
  double previous = 1.0, current = 1.0 + c.first_rate * z;
  for (const Rkl2Stage& st : c.stages) {
    const double next =
        st.mu * current + st.nu * previous + (1.0 - st.mu - st.nu) + st.rate * z * current + st.start_rate * z;
    previous = current;
    current = next;
  }
  return current;
}

// Legendre's polynomial by (n + 1) P_{n+1} = (2n + 1) x P_n - n P_{n-1}.
double legendre(std::int64_t s, double x) {
  double before = 1.0, now = x;
  for (std::int64_t n = 1; n < s; ++n) {
    const double next =
        (static_cast<double>(2 * n + 1) * x * now - static_cast<double>(n) * before) / static_cast<double>(n + 1);
    before = now;
    now = next;
  }
  return now;
}

double rkl2_polynomial(std::int64_t s, double z) {
  const auto sd = static_cast<double>(s);
  const double b = (sd * sd + sd - 2.0) / (2.0 * sd * (sd + 1.0));
  return 1.0 - b + b * legendre(s, 1.0 + z / interval_length(s) * 2.0);
}

TEST(SolverFlowSuperStep, StagesAreTheFewestThatHoldTheStep) {
  for (const double ratio : {0.5, 1.0, 2.7, 10.0, 100.0, 1234.5, 1e6}) {
    const std::int64_t s = rkl2_stages(ratio, 1.0);
    EXPECT_GE(s, 2);
    // The step fits: span <= 0.9 fluid_step (s^2 + s - 2) / 4 ...
    EXPECT_LE(ratio, 0.9 * 0.5 * interval_length(s)) << ratio;
    // ... and one stage fewer would not hold it.
    if (s > 2) {
      EXPECT_GT(ratio, 0.9 * 0.5 * interval_length(s - 1)) << ratio;
    }
  }
}

// 100 points across each interval. 1e-13: the recurrences run up to 31 stages of O(1) terms (the
// measured differences are below 5e-15).
TEST(SolverFlowSuperStep, StagesGiveTheShiftedLegendrePolynomialBoundedOnItsInterval) {
  for (const std::int64_t s : {2, 3, 5, 10, 31}) {
    const double length = interval_length(s);
    for (int k = 0; k <= 100; ++k) {
      const double z = -length * k / 100.0;
      EXPECT_NEAR(amplification(s, z), rkl2_polynomial(s, z), 1e-13) << s << " stages, z " << z;
      EXPECT_LE(std::abs(amplification(s, z)), 1.0 + 1e-13) << s << " stages, z " << z;
    }
    // 10 % beyond the interval the polynomial leaves [-1, 1] (from 5 stages on; fewer need more).
    if (s >= 5) {
      EXPECT_GT(std::abs(amplification(s, -1.1 * length)), 1.0) << s << " stages";
    }
  }
}

// R_s(z) - exp(z) = O(z^3): halving z divides it by about 8 (measured 7.99-8.00; a first-order
// method would give 4).
TEST(SolverFlowSuperStep, StepIsSecondOrderAccurate) {
  for (const std::int64_t s : {2, 5, 31}) {
    const double z = -0.02;
    const double error = amplification(s, z) - std::exp(z), half = amplification(s, z / 2) - std::exp(z / 2);
    EXPECT_NEAR(error / half, 8.0, 0.2) << s << " stages";
  }
}

constexpr double kDx = 1e-3;
constexpr int kNx = 32, kNy = 8;  // periods above twice the horizon

Model periodic_fluid_model() {
  Scene s = make_scene(2, false, kDx, 3.05);
  s.effects.pore_fluid = true;
  s.material.pore_fluid = testing::water(1e-12, 1.0);
  return make_model(make_lattice(2, {kNx, kNy, 1}, kDx, s.thickness), s, {kNx * kDx, kNy * kDx, 0.0});
}

// The lattice's decay rate of the mode cos(k x): M kappa0 sum_j V_j (1 - cos(k xi_x)) / |xi| over
// point 0's family.
double mode_rate(const Model& m, double k) {
  double sum = 0.0;
  for (std::int64_t b = m.bonds.offset[0]; b < m.bonds.offset[1]; ++b) {
    double xi[2];
    bond_vector<2>(m.bonds, m.points.position.data(), 0, b, xi);
    const auto j = static_cast<std::size_t>(m.bonds.neighbor[b]);
    sum += m.points.volume[j] * (1.0 - std::cos(k * xi[0])) / std::hypot(xi[0], xi[1]);
  }
  return m.fluid->biot_modulus * m.fluid->micro_conductivity * sum;
}

// Puts p = cos(k (x - x_0)) and runs `steps` super steps of `span` in `stages` stages; returns the
// amplitude at the first point (where the cosine is 1).
double amplitude_after_super_steps(Model& m, double k, double span, std::int64_t stages, int steps) {
  const double x0 = m.points.position[0];
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    m.points.pore_pressure[i] = std::cos(k * (m.points.position[2 * i] - x0));
    m.points.fluid_content_change[i] = m.points.pore_pressure[i] / m.fluid->biot_modulus;
  }
  FlowSuperStepWork work;
  for (int n = 0; n < steps; ++n) {
    const std::vector<double> before = m.points.pore_pressure;
    flow_super_step(m.points, m.bonds, *m.fluid, span, stages, nullptr, before, work);
  }
  return m.points.pore_pressure[0];
}

// One super step of the longest span its stages hold multiplies a smooth mode and the shortest
// one (two points per wave) by R_s(-lambda_k tau). 1e-12: each stage's rate is a sum of a few dozen
// terms rounded at 1e-16, over up to 31 stages.
TEST(SolverFlowSuperStep, SuperStepMultipliesACosineModeByThePolynomial) {
  Model m = periodic_fluid_model();
  const double limit = fluid_step_limit(m.points, m.bonds, *m.fluid);
  for (const std::int64_t stages : {4, 12, 31}) {
    const double span = 0.9 * limit * 0.5 * interval_length(stages);
    ASSERT_EQ(rkl2_stages(span, limit), stages);
    for (const int waves : {1, kNx / 2}) {
      const double k = 2.0 * std::numbers::pi * waves / (kNx * kDx);
      const double z = -mode_rate(m, k) * span;
      EXPECT_NEAR(amplitude_after_super_steps(m, k, span, stages, 1), rkl2_polynomial(stages, z), 1e-12)
          << stages << " stages, " << waves << " waves, z " << z;
    }
  }
}

// Decay of the smooth mode over a fixed time to about exp(-1): its error against exp(-lambda t)
// falls fourfold when the super steps halve (second order). The stage count is held (the coarse
// step's): the leading error's coefficient depends on it.
TEST(SolverFlowSuperStep, SuperStepsConvergeAtSecondOrderToTheExactDecay) {
  Model m = periodic_fluid_model();
  const double k = 2.0 * std::numbers::pi / (kNx * kDx);
  const double rate = mode_rate(m, k), limit = fluid_step_limit(m.points, m.bonds, *m.fluid);
  const double end = 1.0 / rate;
  const std::int64_t stages = rkl2_stages(end / 8, limit);
  auto error_with = [&](int steps) {
    return amplitude_after_super_steps(m, k, end / steps, stages, steps) - std::exp(-rate * end);
  };
  const double coarse = error_with(8), fine = error_with(16);
  EXPECT_LT(std::abs(coarse), 1e-2);
  EXPECT_NEAR(fine / coarse, 0.25, 0.05);
}

}  // namespace
}  // namespace mppm::solver
