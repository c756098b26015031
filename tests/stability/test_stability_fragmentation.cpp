// Stability case: fragmentation under a high-rate impact (scenes/fragmentation_block.yaml, docs/theory.md
// section 7), through mppm::solver::solve and read back from the run directory.
// Hazard: when an impact breaks most bonds, points are left with few, lopsided or no bonds. A
// shape tensor that is inverted while (nearly) singular, a point whose lopsided family makes the
// step unstable, a bond that breaks at one end only, or a break whose energy is not accounted for
// turns into NaN, into momentum created from nothing or into an energy balance that no longer
// closes, usually long after the impact.
// Expected: every value written (energy.csv, snapshots) is finite; the points that lost their
// bonds are detached and reported (run_info.json `detached_points`, the log, the snapshot's
// `detached` field, all three the same number), and a detached point that lost every bond moves
// ballistically (its velocity does not change once the pulse is over); the linear momentum equals the impulse of the
// traction pulse at every snapshot after the pulse (no other external load acts: the body is
// free); the energy balance, with the fracture dissipation in it, stays within the suite's 0.5 %,
// and the balance_error column is what the columns give.
// Breaking bonds must take energy out of the model: the fracture dissipation must not decrease
// (it did, by up to 1.9 x the work, until the damage code detached the points whose stored energy
// rises by more than half when they lose bonds: bond_breakage.cpp; left: 1e-6 of the work). Test 1: the pulse over 5
// steps (2.6 us); test 2: over 2 steps (1.05 us); test 3: the no-fail points keep their bonds.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "tests/stability/stability_support.hpp"

namespace mppm::stability {
namespace {

constexpr double kDensity = 0.95 * 2650.0;  // rho = solid_fraction * density (the scene)
constexpr double kPeakTraction = 1e9;       // the scene's 1 GPa
constexpr double kFaceArea = 20e-3 * 1e-3;  // the left face: 20 mm high, thickness 1 mm

struct Momentum {
  std::array<double, 2> p{0.0, 0.0};
  double scale = 0.0;  // sum of |rho V v| over points and components
};

Momentum momentum(const Snapshot& s, const std::vector<double>& volume) {
  Momentum m;
  const SnapshotField* v = s.find("velocity");
  if (!v) return m;
  for (std::size_t i = 0; i < s.point_count; ++i)
    for (int c = 0; c < 2; ++c) {
      const double q = kDensity * volume[i] * v->data[i * 2 + c];
      m.p[c] += q;
      m.scale += std::abs(q);
    }
  return m;
}

bool all_finite(const Snapshot& s) {
  for (const auto& f : s.fields)
    for (double v : f.data)
      if (!std::isfinite(v)) return false;
  return true;
}

// One run of the scene with the pulse over `rise` steps up and `rise` down (its corners on step
// times, so the scheme's trapezoid rule integrates the applied force exactly: the impulse is the
// triangle's, F_peak * rise * dt), read back.
struct FragmentationRun {
  RunReport r;
  bool stopped = false;  // NumericalFailure (exit code 3 from mppm-solve)
  std::string failure;
  std::size_t points = 0;
  double impulse = 0.0;
  double momentum_error = 0.0;  // worst |P - impulse| over the snapshots after the pulse / momentum scale
  std::size_t snapshots_after_pulse = 0;
  bool snapshots_finite = true;
  std::size_t detached_in_last = 0, ballistic_checked = 0, ballistic_changed = 0;
  std::size_t loaded_points = 0, loaded_detached = 0;  // the no-fail points that carry the traction
  bool log_reports = false;
};

FragmentationRun run_fragmentation(int rise, std::int64_t steps, const std::string& name,
                                   std::vector<std::string> extra = {}) {
  const std::string scene = scene_path("fragmentation_block.yaml");
  const double dt = auto_time_step(scene, {}, name);
  const std::int64_t snapshot_every = std::max<std::int64_t>(1, steps / 20);
  std::vector<std::string> overrides{
      "time.step=" + exact(dt), "time.end=" + exact(static_cast<double>(steps) * dt),
      "boundary_conditions[0].history=[[0, 0], [" + exact(rise * dt) + ", 1], [" + exact(2 * rise * dt) + ", 0]]",
      "output.interval=" + exact(static_cast<double>(snapshot_every) * dt),
      "output.load_interval=" + exact(std::min<std::int64_t>(10, steps / 100 + 1) * dt)};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  FragmentationRun f;
  try {
    f.r = solve_scene(scene, overrides, name);
  } catch (const NumericalFailure& e) {
    f.stopped = true;
    f.failure = e.what();
    f.r = read_run(work_path(name));
  }
  const std::string run = work_path(name);
  const Snapshot reference = read_snapshot(run + "/" + run_layout::reference);
  const std::vector<double>& volume = reference.find("volume")->data;
  const std::vector<double>& boundary = reference.find("boundary_id")->data;
  f.points = reference.point_count;
  f.impulse = kPeakTraction * kFaceArea * rise * dt;
  const double pulse_end = 2 * rise * dt * (1 + 1e-9);
  double worst = 0.0, scale = 0.0;
  Snapshot previous;
  for (const std::string& file : f.r.snapshots) {
    const Snapshot s = read_snapshot(file);
    f.snapshots_finite = f.snapshots_finite && all_finite(s);
    if (s.time > pulse_end) {
      const Momentum m = momentum(s, volume);
      scale = std::max(scale, m.scale);
      worst = std::max({worst, std::abs(m.p[0] - f.impulse), std::abs(m.p[1])});
      ++f.snapshots_after_pulse;
    }
    if (&file == &f.r.snapshots.back()) {
      const auto& detached = s.find("detached")->data;
      f.detached_in_last = 0;
      f.loaded_points = f.loaded_detached = 0;
      for (std::size_t i = 0; i < f.points; ++i) {
        f.detached_in_last += detached[i] != 0.0;
        if (boundary[i] > 0.0) {
          ++f.loaded_points;
          f.loaded_detached += detached[i] != 0.0;
        }
      }
      if (previous.find("detached") && previous.time > pulse_end) {
        const auto& was = previous.find("detached")->data;
        const auto& lost = previous.find("damage")->data;
        const auto& v0 = previous.find("velocity")->data;
        const auto& v1 = s.find("velocity")->data;
        for (std::size_t i = 0; i < f.points; ++i) {
          // Ballistic: detached with every bond gone (damage 1). A detached point keeps its bonds
          // to no-fail points (docs/theory.md section 7: they never break), which still pull it.
          if (was[i] == 0.0 || lost[i] != 1.0) continue;
          ++f.ballistic_checked;
          f.ballistic_changed += v0[2 * i] != v1[2 * i] || v0[2 * i + 1] != v1[2 * i + 1];
        }
      }
    }
    previous = s;
  }
  f.momentum_error = worst / std::max(scale, 1e-300);
  f.log_reports = f.r.log.find("detached points " + std::to_string(f.r.detached_points)) != std::string::npos;
  std::printf(
      "fragmentation, pulse over %d + %d steps: %s%s, %lld steps of %.4g s, %zu points, broken bond pairs %lld, "
      "detached %lld (last snapshot %zu, log %s; loaded no-fail points detached %zu of %zu); momentum after the "
      "pulse vs impulse %.6g N s: worst |error| / scale %.3g over %zu snapshots; ballistic: %zu of %zu detached "
      "points changed velocity; fracture dissipation %.4g J (decreases summed %.4g J) of %.4g J work, final "
      "energy %.4g J; worst balance error %.3g (recomputed from the columns %.3g, without the fracture column "
      "%.3g)\n",
      rise, rise, f.r.status.c_str(), f.stopped ? (" (" + f.r.message + ")").c_str() : "",
      static_cast<long long>(f.r.steps), f.r.time_step, f.points, static_cast<long long>(f.r.broken_bonds),
      static_cast<long long>(f.r.detached_points), f.detached_in_last, f.log_reports ? "yes" : "no", f.loaded_detached,
      f.loaded_points, f.impulse, f.momentum_error, f.snapshots_after_pulse, f.ballistic_changed, f.ballistic_checked,
      f.r.final_fracture_dissipation, f.r.fracture_dissipation_decrease, f.r.final_external_work,
      f.r.final_total_energy, f.r.worst_balance_error, f.r.worst_recomputed_balance_error,
      f.r.worst_balance_without_fracture);
  return f;
}

// Energy put in by breakage, relative to the work, and the energy check's default tolerance.
constexpr double kEnergyCheckTolerance = 0.05;

TEST(StabilityFragmentation, HighRateImpactShattersTheBlockFiniteWithMomentumAndBalanceKept) {
  // Short form 2000 steps (the pulse, the shattering and ~1990 steps of flying fragments and a
  // ringing remainder), long form 10^5.
  const std::int64_t steps = steps_for_form(2000, 100000);
  const FragmentationRun f = run_fragmentation(5, steps, "fragmentation");
  const RunReport& r = f.r;
  const double created = r.fracture_dissipation_decrease / r.final_external_work;
  const bool shattered = r.detached_points >= static_cast<std::int64_t>(f.points / 10);
  const bool pass = !f.stopped && r.status == "completed" && r.steps == steps && r.all_finite && f.snapshots_finite &&
                    shattered && r.detached_points == static_cast<std::int64_t>(f.detached_in_last) && f.log_reports &&
                    f.ballistic_changed == 0 && f.momentum_error < 1e-10 && r.worst_balance_error < 5e-3 &&
                    r.worst_recomputed_balance_error < 1e-9 && created < kEnergyCheckTolerance;
  record_margin({"12-fragmentation",
                 "high-rate impact (1 GPa traction pulse over 2 x 2.6 us, G_cr 20 N/m): many points lose all bonds",
                 "finite; detached points reported; momentum = impulse after the pulse; balance with fracture "
                 "dissipation within 0.5 %",
                 std::to_string(r.steps) + " steps, " + std::to_string(r.broken_bonds) + " bond pairs broken, " +
                     std::to_string(r.detached_points) + " of " + std::to_string(f.points) +
                     " points detached (run_info = log = snapshot), momentum error / scale " + sci(f.momentum_error) +
                     ", worst balance error " + sci(r.worst_balance_error) + "; fracture dissipation " +
                     sci(r.final_fracture_dissipation) + " J: breakage put " + sci(r.fracture_dissipation_decrease) +
                     " J = " + sci(created) + " of the work into the model (finding)",
                 "momentum " + sci(f.momentum_error) + " vs 1e-10; balance " + sci(r.worst_balance_error) +
                     " vs 5e-3 (" + sci(5e-3 / std::max(r.worst_balance_error, 1e-300), 2) +
                     " x); energy from breakage " + sci(created) + " vs the energy check's 0.05",
                 pass});

  ASSERT_FALSE(f.stopped) << f.failure;
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.steps, steps);
  EXPECT_TRUE(r.all_finite);
  EXPECT_TRUE(f.snapshots_finite);
  // The hazard did happen: a tenth of the points or more lost every bond.
  EXPECT_GE(r.detached_points, static_cast<std::int64_t>(f.points / 10));
  EXPECT_GT(r.broken_bonds, 0);
  // Reported, and the same number everywhere.
  EXPECT_EQ(r.detached_points, static_cast<std::int64_t>(f.detached_in_last));
  EXPECT_TRUE(f.log_reports) << r.log;
  EXPECT_GT(f.ballistic_checked, 0u);
  EXPECT_EQ(f.ballistic_changed, 0u);
  EXPECT_GE(f.snapshots_after_pulse, 10u);
  // Momentum: the internal forces cancel pair by pair (a bond breaks at both ends in the same
  // step), so what is left is the round-off of summing the point forces over the run: 1e-10 of
  // the sum of the momentum magnitudes, the bound of the free-body momentum test
  // (tests/unit/test_solver_momentum.cpp) and of the damage shatter test.
  EXPECT_LT(f.momentum_error, 1e-10);
  EXPECT_LT(r.worst_balance_error, 5e-3);
  // The balance is that of every column, fracture dissipation included (the energy check uses the
  // same sum, ExplicitDynamics::energy().accounted()): recomputed from the columns it is round-off
  // (1e-9 is far above the rounding of the recomputation and far below what leaving out the
  // fracture column gives, printed above).
  EXPECT_LT(r.worst_recomputed_balance_error, 1e-9);
  // What breakage put into the model stays below what the energy check tolerates (else the run
  // would have stopped: test 2). This is the measured finding, not the physics: it should be 0.
  EXPECT_LT(created, kEnergyCheckTolerance);
}

// The same impact with the pulse over 2 + 2 steps: more points lose their families at once.
// Breakage must not put energy into the model (it did before the damage code detached the points
// whose stored energy rises when they lose bonds: 1.86 x the work); the run completes with the
// default energy check.
TEST(StabilityFragmentation, FasterImpactPutsNoEnergyIntoTheModel) {
  const FragmentationRun f = run_fragmentation(2, 300, "fragmentation-fast");
  const RunReport& r = f.r;
  const double created = r.fracture_dissipation_decrease / std::max(r.final_external_work, 1e-300);
  record_margin({"12b-fragmentation-fast", "the same impact with the pulse over 2 x 1.05 us",
                 "completes; breakage puts (almost) no energy into the model (the fracture dissipation falls by at "
                 "most 1e-4 of the work); finite",
                 std::string(f.stopped ? "stopped: " + r.message : "completed") + "; " +
                     std::to_string(r.detached_points) + " points detached; energy from breakage " + sci(created) +
                     " of the work; worst balance error " + sci(r.worst_balance_error),
                 "energy from breakage " + sci(created) + " vs 1e-4",
                 !f.stopped && r.status == "completed" && created <= 1e-4 && f.snapshots_finite && r.all_finite});
  EXPECT_FALSE(f.stopped) << f.failure;
  EXPECT_EQ(r.status, "completed");
  EXPECT_TRUE(f.snapshots_finite);
  EXPECT_TRUE(r.all_finite);
  // What is left: the rises below the detachment margin (50 % of a point's energy,
  // solver/bond_breakage.hpp) and the O(dt) kick term; measured 1.1e-6 of the work. The bound,
  // 1e-4, is 100 x that and 19 000 x below what breakage put in before the rule.
  EXPECT_LE(r.fracture_dissipation_decrease, 1e-4 * r.final_external_work);
  EXPECT_LE(r.final_total_energy, r.final_external_work * (1 + 1e-4));
  EXPECT_LT(r.worst_balance_error, 5e-3);
}

// A no-fail point keeps its bonds (docs/theory.md section 7: the no-fail zone protects the loaded
// boundary), also when a neighbour is detached (the cascade leaves bonds to no-fail points).
TEST(StabilityFragmentation, NoFailPointsKeepTheirBonds) {
  const FragmentationRun f = run_fragmentation(5, 300, "fragmentation-no-fail");
  EXPECT_GT(f.loaded_points, 0u);
  EXPECT_EQ(f.loaded_detached, 0u);
}

}  // namespace
}  // namespace mppm::stability
