// The retention model of unsaturated pore fluid (docs/theory.md section 12, "Unsaturated
// (retention)"): van Genuchten's saturation and Mualem's relative permeability at their ends and
// monotone between, the analytic dS_r/dp against a central difference, the fluid content's inverse
// (safeguarded Newton) round trip over suctions 0-1000 p_e, n 1.1-8 and several S_res, its failure
// status on an impossible target, and the saturated branch bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "solver/retention_curve.hpp"

namespace mppm::solver {
namespace {

constexpr double kPe = 1e4;  // p_e = 10 kPa
// Water in a soil: M ~ K_f / n0 ~ 1 GPa, so that even 1000 p_e = 10 MPa of suction changes the liquid
// term n0 + p/M by a few percent only.
constexpr FluidStorage kStorage{0.3, 1.0, 1e9};

const std::vector<double> kNs{1.1, 1.5, 2.0, 3.0, 5.0, 8.0};
const std::vector<double> kResiduals{0.0, 0.05, 0.2};

RetentionCurve curve(double n, double s_res) { return RetentionCurve{kPe, n, s_res}; }

// Suctions from 0 to 1000 p_e, log spaced above 1e-4 p_e.
std::vector<double> suctions() {
  std::vector<double> s{0.0};
  for (int k = -16; k <= 12; ++k) s.push_back(kPe * std::pow(10.0, k / 4.0));
  return s;
}

TEST(RetentionCurve, SaturationAndPermeabilityEndsAndMonotone) {
  for (double n : kNs) {
    for (double sr : kResiduals) {
      const RetentionCurve c = curve(n, sr);
      EXPECT_EQ(saturation(c, 0.0), 1.0);
      EXPECT_EQ(saturation(c, 5e3), 1.0);  // compression: saturated
      EXPECT_EQ(relative_permeability(c, 0.0), 1.0);
      EXPECT_EQ(relative_permeability(c, 5e3), 1.0);
      // Far beyond the air entry S_r -> S_res and k_r -> 0 (n = 1.1 approaches them slowly:
      // S_e ~ (s/p_e)^(-(n-1)), so the limits are checked at a suction where that is < 1e-3).
      const double far = kPe * std::pow(1e3, 1.0 / (n - 1.0) + 1.0);
      EXPECT_NEAR(saturation(c, -far), sr, 1e-3);
      EXPECT_LT(relative_permeability(c, -far), 1e-3);
      double s_prev = 2.0, k_prev = 2.0;
      for (double s : suctions()) {
        const double S = saturation(c, -s), k = relative_permeability(c, -s);
        EXPECT_LE(S, s_prev) << "n " << n << " s " << s;
        EXPECT_LE(k, k_prev) << "n " << n << " s " << s;
        EXPECT_GE(S, sr);
        EXPECT_GE(k, 0.0);
        EXPECT_LE(k, 1.0);
        s_prev = S;
        k_prev = k;
      }
      EXPECT_LT(saturation(c, -1e3 * kPe), saturation(c, -kPe));  // strictly, not only weakly
    }
  }
}

TEST(RetentionCurve, MualemIsOneAtFullSaturationAndContinuous) {
  for (double n : kNs) {
    const RetentionCurve c = curve(n, 0.1);
    // k_r(S_e = 1) = 1, and k_r -> 1 as the suction -> 0, slowly for small n: 1 - k_r ~ 2 (x^n)^m
    // with x = s/p_e, so the suction where that is 2e-4 is x = 1e-4^(1/(n-1)) (1e-40 at n = 1.1).
    EXPECT_EQ(relative_permeability(c, 0.0), 1.0);
    EXPECT_NEAR(relative_permeability(c, -kPe * std::pow(1e-4, 1.0 / (n - 1.0))), 1.0, 1e-3) << n;
    // Against the textbook form at a moderate suction, where it has no cancellation.
    const double se = effective_saturation(c, -kPe), m = c.m();
    const double textbook = std::sqrt(se) * std::pow(1.0 - std::pow(1.0 - std::pow(se, 1.0 / m), m), 2.0);
    EXPECT_NEAR(relative_permeability(c, -kPe), textbook, 1e-14);
  }
}

TEST(RetentionCurve, DerivativeMatchesCentralDifference) {
  // The central difference's error is h^2 S''' / 6 (below 1e-8 of S' with h = 1e-5 s on these
  // curves, n <= 8) plus the round-off 2 eps |S| / (2h): the bound is their sum with a factor 4.
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  double worst = 0.0;
  for (double n : kNs) {
    for (double sr : kResiduals) {
      const RetentionCurve c = curve(n, sr);
      for (double s : suctions()) {
        if (s < 1e-2 * kPe) continue;
        const double h = 1e-5 * s;
        const double fd = (saturation(c, -s + h) - saturation(c, -s - h)) / (2.0 * h);
        const double exact = saturation_derivative(c, -s);
        EXPECT_GT(exact, 0.0);
        const double err = std::abs(fd - exact) / exact;
        if (4.0 * kEps / (h * exact) < 1e-8) worst = std::max(worst, err);
        EXPECT_LT(err, 4e-8 + 4.0 * kEps / (h * exact)) << "n " << n << " S_res " << sr << " s " << s;
        const double fdz =
            (fluid_content(c, kStorage, -s + h, 0.0) - fluid_content(c, kStorage, -s - h, 0.0)) / (2.0 * h);
        const double dz = fluid_content_derivative(c, kStorage, -s, 0.0);
        EXPECT_GT(dz, 0.0);
        EXPECT_LT(std::abs(fdz - dz) / dz, 4e-8 + 4.0 * kEps * kStorage.porosity / (h * dz))
            << "n " << n << " S_res " << sr << " s " << s;
      }
    }
  }
  EXPECT_EQ(saturation_derivative(curve(2.0, 0.1), 1.0), 0.0);
  std::printf("worst relative error of dS_r/dp against the central difference (round-off < 1e-8): %.2e\n", worst);
}

TEST(RetentionCurve, InverseRoundTrip) {
  // zeta(p) -> p: 1e-12 relative, or where the content has lost p's digits the conditioning
  // bound: the change zeta - n0 = (b eps_v + p/M) - (1 - S_r) (n0 + b eps_v + p/M) is computed to
  // ~eps of its terms' sizes, so p carries 8 eps (|b eps_v| + |p|/M + (1 - S_r) n0) / (|p| dzeta/dp)
  // relative (e.g. with n = 8 and S_res = 0 beyond ~100 p_e, where S_e n0 < 1e-15: the content no
  // longer knows the pressure; or p = M (change - b eps_v) at a suction of a few Pa with eps_v != 0,
  // as in the saturated solver).
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  double worst = 0.0;
  int most_iterations = 0, condition_limited = 0, points = 0;
  for (double n : kNs) {
    for (double sr : kResiduals) {
      const RetentionCurve c = curve(n, sr);
      for (double eps_v : {-1e-3, 0.0, 2e-3}) {
        for (double s : suctions()) {
          const double p = -s;
          const double change = fluid_content_change(c, kStorage, p, eps_v);
          const RetentionInverse inv = pressure_from_fluid_content(c, kStorage, change, eps_v);
          const double scale = std::abs(kStorage.biot_coefficient * eps_v) + s / kStorage.biot_modulus +
                               (1.0 - saturation(c, p)) * kStorage.porosity;
          const double conditioning =
              s > 0.0 ? 8.0 * kEps * scale / (s * fluid_content_derivative(c, kStorage, p, eps_v)) : 0.0;
          // Where the content has lost the pressure (conditioning > 1), the content may equal the
          // driest admissible one to round-off: no bracket is then an honest answer.
          if (conditioning > 1.0 && inv.status == RetentionInverseStatus::no_bracket) {
            ++condition_limited;
            ++points;
            continue;
          }
          ASSERT_TRUE(inv.ok()) << "n " << n << " S_res " << sr << " s " << s;
          const double err = std::abs(inv.pressure - p) / std::max(std::abs(p), 1e-300);
          ++points;
          if (conditioning > 1e-12) {
            ++condition_limited;
          } else {
            worst = std::max(worst, err);
          }
          most_iterations = std::max(most_iterations, inv.iterations);
          EXPECT_LE(err, std::max(1e-12, conditioning))
              << "n " << n << " S_res " << sr << " s " << s << " eps_v " << eps_v;
        }
      }
    }
  }
  std::printf("inverse round trip: %d of %d points condition-limited\n", condition_limited, points);
  std::printf("inverse round trip: worst relative error %.2e (well-conditioned points), at most %d iterations\n", worst,
              most_iterations);
}

TEST(RetentionCurve, InverseFailsOnImpossibleTargets) {
  const RetentionCurve c = curve(2.0, 0.2);
  // Below the content at the largest suction searched (here 1000 p_e, where S_r is near S_res):
  // no bracket, a status and no exception.
  RetentionInverseOptions capped;
  capped.max_suction = 1e3 * kPe;
  const double lowest = fluid_content(c, kStorage, -1e3 * kPe, 0.0);
  const double impossible = 0.5 * c.residual_saturation * kStorage.porosity;  // half the S_res-limited minimum
  ASSERT_LT(impossible, lowest);
  RetentionInverse inv = pressure_from_fluid_content(c, kStorage, impossible - kStorage.porosity, 0.0, capped);
  EXPECT_EQ(inv.status, RetentionInverseStatus::no_bracket);
  // Uncapped, the search ends where the liquid term n0 + p/M vanishes (zeta = 0): a negative
  // content has no pressure.
  inv = pressure_from_fluid_content(c, kStorage, -0.01 - kStorage.porosity, 0.0);
  EXPECT_EQ(inv.status, RetentionInverseStatus::no_bracket);
  // A strain that leaves no pore space (n0 + b eps_v <= 0) either.
  inv = pressure_from_fluid_content(c, kStorage, -0.35, -0.31);
  EXPECT_EQ(inv.status, RetentionInverseStatus::no_bracket);
  // Too few iterations: iteration_limit, not a wrong converged answer.
  RetentionInverseOptions one;
  one.max_iterations = 1;
  const double change = fluid_content_change(c, kStorage, -30.0 * kPe, 0.0);
  inv = pressure_from_fluid_content(c, kStorage, change, 0.0, one);
  EXPECT_EQ(inv.status, RetentionInverseStatus::iteration_limit);
}

TEST(RetentionCurve, SaturatedBranchIsTheSaturatedFormulaBitForBit) {
  const RetentionCurve c = curve(2.0, 0.1);
  const double M = kStorage.biot_modulus, b = kStorage.biot_coefficient;
  for (double change : {0.0, 1e-7, 3.3e-5, 0.01, 1.0 / 3.0}) {
    for (double eps_v : {0.0, -2e-5, 1e-7, -1.0 / 7.0}) {
      if (change - b * eps_v < 0.0) continue;
      const RetentionInverse inv = pressure_from_fluid_content(c, kStorage, change, eps_v);
      const double saturated = M * (change - b * eps_v);  // the saturated solver's p
      EXPECT_TRUE(inv.ok());
      EXPECT_EQ(inv.iterations, 0);
      EXPECT_EQ(std::memcmp(&inv.pressure, &saturated, sizeof(double)), 0) << change << " " << eps_v;
    }
  }
}

}  // namespace
}  // namespace mppm::solver
