// Stability case: energy balance of a long elastic run (scenes/energy_balance.yaml).
// Hazard: an explicit scheme that is stable can still drift: a force that is not exactly the
// energy gradient, work of a prescribed layer or a traction integrated inconsistently, or
// round-off accumulating over 10^5 steps shows up as energy created or lost.
// Expected: |kinetic + rotational + elastic + stabilization - external work - initial| stays
// below 0.5 % of the energy scale at every row of energy.csv (the suite's tolerance), over 10^4
// steps (short form) and 10^5 steps (long form), with the solver's own guards on.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/stability/stability_support.hpp"

namespace mppm::stability {
namespace {

TEST(StabilityEnergyBalance, ElasticRunBalancesToHalfAPercent) {
  const std::string scene = scene_path("energy_balance.yaml");
  const std::int64_t steps = steps_for_form(10000, 100000);
  const double dt = auto_time_step(scene, {}, "energy-balance");
  // The pulse lasts 40 steps and the traction ramps over 200: both are resolved by the step,
  // so the trapezoid rule on the work is accurate and the balance tests the scheme itself.
  const std::vector<std::string> overrides{
      "time.end=" + exact(static_cast<double>(steps) * dt),
      "boundary_conditions[0].history=[[0, 0], [" + exact(20 * dt) + ", 1], [" + exact(40 * dt) + ", 0]]",
      "boundary_conditions[1].ramp=" + exact(200 * dt), "output.load_interval=" + exact(10 * dt)};
  const RunReport r = solve_scene(scene, overrides, "energy-balance");
  std::printf(
      "energy balance: %s, %lld steps of %.4g s, %zu rows, worst balance error %.3g, external work %.4g J, "
      "final energy %.4g J\n",
      r.status.c_str(), static_cast<long long>(r.steps), r.time_step, r.energy_rows, r.worst_balance_error,
      r.final_external_work, r.final_total_energy);
  const bool pass = r.status == "completed" && r.steps == steps && r.all_finite && r.worst_balance_error < 5e-3;
  record_margin({"05-energy-balance", "energy drift over a long elastic run (pulse + held traction)",
                 "balance error below 0.5 % at every energy row",
                 std::to_string(r.steps) + " steps, " + std::to_string(r.energy_rows) + " rows, worst balance error " +
                     sci(r.worst_balance_error) + ", external work " + sci(r.final_external_work) + " J",
                 "worst balance error " + sci(r.worst_balance_error) + " vs limit 5e-3 (" +
                     sci(5e-3 / std::max(r.worst_balance_error, 1e-300), 2) + " x)",
                 pass});
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.steps, steps);
  EXPECT_TRUE(r.all_finite);
  // Rows every 10 steps, plus t = 0 and the last step.
  EXPECT_GE(r.energy_rows, static_cast<std::size_t>(steps / 10));
  // The loads did work and the block still holds energy at the end (not a quiet block).
  EXPECT_GT(r.final_external_work, 0.0);
  EXPECT_GT(r.final_total_energy, 0.1 * r.final_external_work);
  EXPECT_LT(r.worst_balance_error, 5e-3);
}

}  // namespace
}  // namespace mppm::stability
