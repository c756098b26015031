// The 1-D Richards reference for unsaturated infiltration (tests/verification/problems/richards_column):
// the fluid conserved to the Newton tolerance, a constant-diffusivity column against its analytic
// solution (second order on grids refined with dt ~ dz^2), a draining unsaturated column's
// hydrostatic equilibrium against its quadrature (second order), and the unsaturated infiltration's
// wetting front and profile converging under grid and time refinement (observed orders printed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "tests/verification/problems/richards_column.hpp"

namespace mppm::verification {
namespace {

// A loam-like column: p_e = 10 kPa (about 1 m of water), n = 2, S_res = 0.1, n0 = 0.4, M = 1 GPa,
// k = 1e-12 m^2 with water (k' = 1e-9 m^2/(Pa s), K_sat = k' rho g ~ 1e-5 m/s), initially at 5 p_e of
// suction (S_r = 0.28, k_r ~ 2e-4), fed at half K_sat for 4.5 h: the front goes ~0.4 m down the 1 m column.
RichardsColumn infiltration(int cells, int steps) {
  RichardsColumn c;
  c.length = 1.0;
  c.cells = cells;
  c.curve = solver::RetentionCurve{1e4, 2.0, 0.1};
  c.storage = solver::FluidStorage{0.4, 1.0, 1e9};
  c.mobility = 1e-9;
  c.initial_pressure = -5e4;
  c.top_flux = 0.5 * c.mobility * c.fluid_density * c.gravity;
  c.end_time = 1.6e4;
  c.steps = steps;
  return c;
}

// The conservative restriction of a profile to the grid of half as many cells (pairs averaged).
std::vector<double> restrict_profile(const std::vector<double>& fine) {
  std::vector<double> coarse(fine.size() / 2);
  for (std::size_t i = 0; i < coarse.size(); ++i) coarse[i] = 0.5 * (fine[2 * i] + fine[2 * i + 1]);
  return coarse;
}

double mean_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += std::abs(a[i] - b[i]);
  return s / static_cast<double>(a.size());
}

double ierfc(double u) { return std::exp(-u * u) / std::sqrt(std::numbers::pi) - u * std::erfc(u); }

TEST(RichardsReference, InfiltrationConservesTheFluid) {
  const RichardsResult r = solve_richards_column(infiltration(100, 100));
  ASSERT_TRUE(r.converged);
  // Inflow q t exactly (the flux condition), the stored fluid the Newton tolerance away from it: each
  // step converges to 1e-13 of the pressures, whose fluid imbalance is far below 1e-10 of the inflow.
  EXPECT_NEAR(r.inflow, 0.5 * 1e-9 * 1000.0 * 9.81 * 1.6e4, 1e-15);
  EXPECT_LT(r.mass_balance_error, 1e-10);
  EXPECT_GT(r.front_depth, 0.2);
  EXPECT_LT(r.front_depth, 0.8);
  std::printf(
      "infiltration 100 cells x 100 steps: inflow %.6e m, mass balance %.2e, front %.4f m, Newton %d, "
      "splits %d\n",
      r.inflow, r.mass_balance_error, r.front_depth, r.newton_iterations, r.step_splits);
  // A prescribed top pressure (ponding at 0 Pa) as well: the inflow is then the top face's flux.
  RichardsColumn ponded = infiltration(100, 100);
  ponded.top_pressure_given = true;
  ponded.top_pressure = 0.0;
  ponded.end_time = 4e3;
  const RichardsResult q = solve_richards_column(ponded);
  ASSERT_TRUE(q.converged);
  EXPECT_GT(q.inflow, 0.0);
  EXPECT_LT(q.mass_balance_error, 1e-10);
  std::printf("ponded 100 cells x 100 steps: inflow %.6e m, mass balance %.2e, front %.4f m\n", q.inflow,
              q.mass_balance_error, q.front_depth);
}

// Saturated throughout (p >= 0: S_r = 1, k_r = 1, c = 1/M) and without gravity the column is linear
// diffusion with D = k' M; a constant inflow q into the top of a column deep enough to be semi-infinite
// (erfc(L / 2 sqrt(D t)) = erfc(5) ~ 1e-12) gives p - p0 = (2 q / k') sqrt(D t) ierfc(x / 2 sqrt(D t)) at
// the depth x. Backward Euler's O(dt) and the centred fluxes' O(dz^2) with dt ~ dz^2: second order.
TEST(RichardsReference, ConstantDiffusivityColumnMatchesItsAnalyticSolution) {
  std::vector<double> errors;
  for (int cells : {20, 40, 80, 160}) {
    RichardsColumn c;
    c.length = 1.0;
    c.cells = cells;
    c.curve = solver::RetentionCurve{1e4, 2.0, 0.1};
    c.storage = solver::FluidStorage{0.4, 1.0, 1e8};
    c.mobility = 1e-9;
    c.gravity = 0.0;
    c.initial_pressure = 1e4;
    c.top_flux = 1e-6;
    c.end_time = 0.1;  // sqrt(D t) = 0.1 m
    c.steps = cells * cells / 40;
    const RichardsResult r = solve_richards_column(c);
    ASSERT_TRUE(r.converged);
    EXPECT_LT(r.mass_balance_error, 1e-10);
    const double D = c.mobility * c.storage.biot_modulus, root = std::sqrt(D * c.end_time);
    const double amplitude = 2.0 * c.top_flux / c.mobility * root;
    double worst = 0.0;
    for (std::size_t i = 0; i < r.z.size(); ++i) {
      const double exact = c.initial_pressure + amplitude * ierfc((c.length - r.z[i]) / (2.0 * root));
      worst = std::max(worst, std::abs(r.pressure[i] - exact));
    }
    errors.push_back(worst / amplitude);
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    std::printf("constant diffusivity: max error %.3e -> %.3e (of the surface rise), observed order %.3f\n", errors[k],
                errors[k + 1], order);
    EXPECT_GT(order, 1.8);  // second order, the first grids slightly pre-asymptotic
  }
  EXPECT_LT(errors.back(), 1e-3);
}

// With no inflow, a column at a uniform suction drains under gravity towards the hydrostatic
// equilibrium p = p_b - rho_f g z (no flux anywhere), with p_b set by the fluid it holds:
// int_0^L zeta(p_b - rho_f g z) dz = L zeta(p_0). The scheme's steady state is linear with slope
// -rho_f g exactly (each face's flux vanishes) and its p_b solves the midpoint rule of that integral,
// so p_b converges at second order to the root computed here by Simpson's rule and bisection. This
// checks the unsaturated storage zeta(p) through the whole range the column spans (0.5-1.5 p_e).
TEST(RichardsReference, DrainedColumnReachesTheHydrostaticEquilibrium) {
  RichardsColumn c = infiltration(50, 200);
  c.initial_pressure = -1e4;  // p_e: k_r ~ 0.1, the diffusion time L^2 c / (k' k_r) ~ 1e5 s
  c.top_flux = 0.0;
  c.end_time = 4e6;  // tens of diffusion times: the transient has decayed below round-off
  const double rho_g = c.fluid_density * c.gravity;
  const auto content = [&](double p) { return solver::fluid_content_change(c.curve, c.storage, p, 0.0); };
  const double target = c.length * content(c.initial_pressure);
  const auto held = [&](double pb) {  // Simpson's rule, 2e4 intervals
    const int m = 20000;
    const double h = c.length / m;
    double sum = content(pb) + content(pb - rho_g * c.length);
    for (int k = 1; k < m; ++k) sum += (k % 2 ? 4.0 : 2.0) * content(pb - rho_g * k * h);
    return sum * h / 3.0;
  };
  double lo = c.initial_pressure, hi = c.initial_pressure + rho_g * c.length;  // p_b lies between
  for (int k = 0; k < 100; ++k) (held(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
  const double exact = 0.5 * (lo + hi);
  std::vector<double> errors;
  for (int cells : {25, 50, 100}) {
    c.cells = cells;
    const RichardsResult r = solve_richards_column(c);
    ASSERT_TRUE(r.converged);
    EXPECT_LT(std::abs(r.stored), 1e-12);  // nothing came in: the fluid is the same to round-off
    double lowest = 1e300, highest = -1e300;
    for (std::size_t i = 0; i < r.z.size(); ++i) {
      lowest = std::min(lowest, r.pressure[i] + rho_g * r.z[i]);
      highest = std::max(highest, r.pressure[i] + rho_g * r.z[i]);
    }
    EXPECT_LT(highest - lowest, 1e-8 * rho_g * c.length);  // hydrostatic: the potential is uniform
    errors.push_back(std::abs(0.5 * (lowest + highest) - exact) / (rho_g * c.length));
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    std::printf("hydrostatic equilibrium: p_b error %.3e -> %.3e (of rho g L), observed order %.3f\n", errors[k],
                errors[k + 1], order);
    EXPECT_GT(order, 1.8);
  }
}

// The unsaturated infiltration converges: the front and the saturation profile change less at each
// refinement, at the observed order log2(|f_1 - f_2| / |f_2 - f_3|). Backward Euler is first order in
// time; the centred face conductivity first to second order in space behind the steep front.
TEST(RichardsReference, InfiltrationConvergesUnderGridAndTimeRefinement) {
  // Time: 100 cells, 50 to 400 steps.
  std::vector<RichardsResult> t;
  for (int steps : {50, 100, 200, 400}) {
    t.push_back(solve_richards_column(infiltration(100, steps)));
    ASSERT_TRUE(t.back().converged);
    EXPECT_LT(t.back().mass_balance_error, 1e-10);
  }
  for (std::size_t k = 0; k + 2 < t.size(); ++k) {
    const double front = std::log2(std::abs(t[k].front_depth - t[k + 1].front_depth) /
                                   std::abs(t[k + 1].front_depth - t[k + 2].front_depth));
    const double profile = std::log2(mean_abs_difference(t[k].saturation, t[k + 1].saturation) /
                                     mean_abs_difference(t[k + 1].saturation, t[k + 2].saturation));
    std::printf("time refinement: fronts %.5f %.5f %.5f m, observed order front %.2f, profile %.2f\n", t[k].front_depth,
                t[k + 1].front_depth, t[k + 2].front_depth, front, profile);
    EXPECT_GT(front, 0.8);  // first order (backward Euler)
    EXPECT_GT(profile, 0.8);
  }
  // Space: 400 steps, 50 to 400 cells.
  std::vector<RichardsResult> s;
  for (int cells : {50, 100, 200, 400}) {
    s.push_back(solve_richards_column(infiltration(cells, 400)));
    ASSERT_TRUE(s.back().converged);
    EXPECT_LT(s.back().mass_balance_error, 1e-10);
  }
  for (std::size_t k = 0; k + 2 < s.size(); ++k) {
    const double front = std::log2(std::abs(s[k].front_depth - s[k + 1].front_depth) /
                                   std::abs(s[k + 1].front_depth - s[k + 2].front_depth));
    // The three profiles on the coarsest grid of the three (s[k]'s): the finer ones restricted.
    const auto middle = restrict_profile(s[k + 1].saturation);
    const auto finest = restrict_profile(restrict_profile(s[k + 2].saturation));
    const double profile =
        std::log2(mean_abs_difference(s[k].saturation, middle) / mean_abs_difference(middle, finest));
    std::printf("grid refinement: fronts %.5f %.5f %.5f m, observed order front %.2f, profile %.2f\n", s[k].front_depth,
                s[k + 1].front_depth, s[k + 2].front_depth, front, profile);
    EXPECT_GT(front, 0.8);
    EXPECT_GT(profile, 0.8);
  }
}

}  // namespace
}  // namespace mppm::verification
