// Stability case: a near-incompressible skeleton (Poisson ratio 0.49) with a very soft couple
// modulus (mu_c = 1e-4 mu), time.step: auto (scenes/elastic_block.yaml with --set).
// Hazard: lambda = 49 mu makes the P-wave 7 times stiffer than the shear wave (a step sized
// from mu would be unstable), and a nearly vanishing mu_c leaves the micro-rotation almost
// uncoupled (its rotational block is then driven by the bending modulus alone, and a badly
// conditioned split could show up as drift).
// Expected: the run completes with finite values and the energy balance stays within 0.5 %;
// the auto step shrinks with the P-wave speed: dt ~ 1/sqrt(lambda + 2 mu) to within the share
// of the stabilization, which scales with lambda + mu rather than lambda + 2 mu.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/stability/stability_support.hpp"

namespace mppm::stability {
namespace {

TEST(StabilityNearIncompressible, PoissonRatio049AndSoftCoupleModulusStayStable) {
  const std::string scene = scene_path("elastic_block.yaml");
  constexpr double kMu = 14e9, kLambdaBase = 14e9;
  constexpr double kNu = 0.49;
  const double lambda = 2.0 * kMu * kNu / (1.0 - 2.0 * kNu);  // 686 GPa
  const double mu_c = 1e-4 * kMu;
  const std::vector<std::string> material{"material.lambda=" + exact(lambda), "material.mu_c=" + exact(mu_c)};
  const double dt = auto_time_step(scene, material, "near-incompressible");
  const double dt_base = auto_time_step(scene, {}, "near-incompressible-base");
  const std::int64_t steps = steps_for_form(10000, 100000);
  std::vector<std::string> overrides = material;
  overrides.push_back("time.end=" + exact(static_cast<double>(steps) * dt));
  overrides.push_back("boundary_conditions[0].history=[[0, 0], [" + exact(20 * dt) + ", 1], [" + exact(40 * dt) +
                      ", 0]]");
  overrides.push_back("output.load_interval=" + exact(20 * dt));
  const RunReport r = solve_scene(scene, overrides, "near-incompressible");
  const double p_wave_ratio = std::sqrt((kLambdaBase + 2 * kMu) / (lambda + 2 * kMu));
  std::printf(
      "near-incompressible: %s, %lld steps of %.4g s (base material %.4g s; step ratio %.4f, P-wave speed "
      "ratio %.4f), limiting mode %s, worst balance error %.3g\n",
      r.status.c_str(), static_cast<long long>(r.steps), r.time_step, dt_base, dt / dt_base, p_wave_ratio,
      r.limiting_mode.c_str(), r.worst_balance_error);
  const bool pass = r.status == "completed" && r.steps == steps && r.all_finite && r.worst_balance_error < 5e-3;
  record_margin({"03-near-incompressible", "Poisson ratio 0.49 (lambda = 49 mu) and mu_c = 1e-4 mu, auto step",
                 "stable, energy balance within 0.5 %",
                 std::to_string(r.steps) + " steps of " + sci(r.time_step) + " s (" + sci(dt / dt_base) +
                     " x the base material's step; P-wave ratio " + sci(p_wave_ratio) + "), limiting mode " +
                     r.limiting_mode + ", worst balance error " + sci(r.worst_balance_error),
                 "balance error " + sci(r.worst_balance_error) + " vs limit 5e-3 (" +
                     sci(5e-3 / std::max(r.worst_balance_error, 1e-300), 2) + " x)",
                 pass});
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.steps, steps);
  EXPECT_TRUE(r.all_finite);
  EXPECT_GT(r.final_external_work, 0.0);
  EXPECT_LT(r.worst_balance_error, 5e-3);
  EXPECT_EQ(r.limiting_mode, "translational");
  // The step follows the P-wave speed. The stabilization term G_s (C:K^-1) scales with
  // lambda + mu and adds ~10 % to the stiffness: 15 % covers that difference of the moduli mix.
  EXPECT_NEAR(dt / dt_base, p_wave_ratio, 0.15 * p_wave_ratio);
}

}  // namespace
}  // namespace mppm::stability
