// Stability cases: the run-time guards of the solver (docs/theory.md section 9).
// 1. A NaN seeded in one point. Hazard: one corrupted value (a bad neighbour, a singular
//    update) spreads through the families and ends as a field of NaN written to disk, or as
//    a silent wrong answer when it sits in a quiet corner. Expected: the per-step guard sees it
//    at the next step, whichever field (displacement, velocity, micro-rotation) and whichever
//    point holds it. Two forms: on the integrator directly (a NaN placed between steps: the guard
//    sees it in the next step), and end to end through mppm-solve with its test hook
//    `--inject-nan STEP:POINT[:FIELD]` (solver/README.md "Test hooks": the NaN appears in the middle
//    of step STEP, after its force evaluation, as a singular local update would leave it): exit
//    code 3, run_info.json status numerical_failure naming the point and the step, the snapshots
//    kept all finite and older than the step, energy.csv without the bad row, no temporaries.
// 2. The periodic energy check's reporting path, end to end. A real instability cannot be
//    entered from a scene (every step above the critical one is refused up front, and the
//    solver's work bookkeeping balances to round-off, ~5e-16 here), so the check is made to
//    trip deliberately, for a known reason: the test hook --inject-kick adds 100 m/s to one
//    point's velocity in step 100, kinetic energy that no work accounts for, far beyond the
//    default tolerance (5 %). mppm-solve must then stop in that step with exit code 3, say why,
//    report the growth the kick put in (1/2 rho V dv^2, rho = solid_fraction * density), and leave a run directory
//    whose run_info.json says "numerical_failure" and whose kept snapshots are readable and finite. (This case used to
//    set numerics.energy_check_tolerance = 1e-300 and rely on the sign of the balance's round-off somewhere in 1100
//    rows: a change in summation order made it <= 0 in every row.)
// 3. No false alarm when a load starts late. In the step in which a load starts, the scheme's
//    kinetic energy 1/2 M v^(n-1/2) . v^(n+1/2) is a difference of two equal numbers (round-off,
//    ~1e-24 J here) while the work is still exactly 0: relative to an energy scale made of such
//    numbers the round-off was "100 % unexplained growth", and a run whose load started after the
//    check's first step (50) stopped with exit 3 (measured before the fix: a 1 MPa traction
//    starting at step 60 of an elastic block: "energy grew by 2.7e-24 J ... (1 of the energy scale
//    2.7e-24 J)"; balance_error 1, and -4.5e280 for a one-step run). The scale now holds the size
//    of the kinetic terms (solver/explicit_dynamics.hpp, EnergyState::kinetic_terms).
// 4. Both guards on a damage run (the fragmentation scene: bonds breaking, points detaching):
//    the energy check's sum includes the fracture dissipation (checked column by column in
//    test_stability_fragmentation.cpp), it trips on unexplained growth there as elsewhere, and a NaN
//    in a run with broken bonds and detached points is caught the same way.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/input_error.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "tests/stability/stability_support.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::stability {
namespace {

namespace fs = std::filesystem;

enum class Field { displacement, velocity, rotation };

// Steps a randomly moving free block, seeds a NaN in one component of one point and reports
// how many steps the guard needed to see it (-1: never within 10 steps).
int steps_to_detect(Field field, std::size_t point, int component) {
  Scene scene = solver::testing::make_scene(2, true, 1e-3, 3.05);
  solver::Model m =
      solver::testing::make_model(solver::testing::make_lattice(2, {20, 20, 1}, 1e-3, scene.thickness), scene);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& v : m.points.velocity) v = 0.01 * g(rng);
  const double dt = 0.8 * solver::critical_time_step(m).step;
  solver::BoundaryConditions free_body(m.points);
  solver::ExplicitDynamics dynamics(m, free_body, dt);
  dynamics.initialize();
  for (int s = 0; s < 20; ++s) dynamics.step(false);
  if (!dynamics.finite()) return -2;  // the guard fired before any seeding: a false alarm
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int D = m.dimension();
  switch (field) {
    case Field::displacement:
      m.points.displacement[point * D + component] = nan;
      break;
    case Field::velocity:
      m.points.velocity[point * D + component] = nan;
      break;
    case Field::rotation:
      m.points.rotation[point * m.points.rotation_components + component] = nan;
      break;
  }
  for (int s = 1; s <= 10; ++s) {
    dynamics.step(false);
    if (!dynamics.finite()) return s;
  }
  return -1;
}

TEST(StabilityGuards, NanSeededInOnePointIsSeenAtTheNextStep) {
  // Corner, edge and interior points; each field.
  struct Seed {
    Field field;
    std::size_t point;
    int component;
    const char* what;
  };
  const Seed seeds[] = {{Field::displacement, 0, 0, "displacement x of corner point 0"},
                        {Field::velocity, 210, 1, "velocity y of interior point 210"},
                        {Field::rotation, 399, 0, "micro-rotation of corner point 399"},
                        {Field::rotation, 10, 0, "micro-rotation of edge point 10"}};
  int worst = 0;
  for (const Seed& s : seeds) {
    const int detected = steps_to_detect(s.field, s.point, s.component);
    std::printf("NaN in %s: detected after %d step(s)\n", s.what, detected);
    EXPECT_EQ(detected, 1) << s.what;
    worst = detected < 0 ? 99 : std::max(worst, detected);
  }
  record_margin({"06-nan-seeded", "a NaN seeded in one point (displacement, velocity or micro-rotation)",
                 "the per-step guard sees it at the next step",
                 "detected after " + std::to_string(worst) + " step(s) (worst of 4 seeds: corner, edge, interior)",
                 "detection delay " + std::to_string(worst) + " step vs limit 1", worst == 1});
}

TEST(StabilityGuards, LoadStartingLateIsNoFalseAlarm) {
  const std::string scene = scene_path("fragmentation_block.yaml");
  const std::vector<std::string> elastic{"effects=[micropolar]", "output.fields=[displacement]",
                                         "boundary_conditions[0].value=[1 MPa, 0]"};
  const double dt = auto_time_step(scene, elastic, "late-load");
  int stopped = 0, runs = 0;
  double worst = 0.0;
  std::string stops;
  // Starts from step 56 to 65: the sign of the round-off differs from start to start (before the
  // fix 60 stopped).
  for (int start = 56; start <= 65; ++start) {
    std::vector<std::string> o = elastic;
    o.push_back("time.step=" + exact(dt));
    o.push_back("time.end=" + exact(80 * dt));
    o.push_back("output.interval=0");
    o.push_back("boundary_conditions[0].history=[[0, 0], [" + exact(start * dt) + ", 0], [" + exact((start + 5) * dt) +
                ", 1]]");
    o.push_back("output.load_interval=0");  // a row (and a check) every step
    ++runs;
    try {
      const RunReport r = solve_scene(scene, o, "late-load");
      worst = std::max(worst, r.worst_balance_error);
    } catch (const NumericalFailure& e) {
      ++stopped;
      stops += std::string(stops.empty() ? "" : "; ") + "start " + std::to_string(start) + ": " + e.what();
    }
  }
  std::printf("load starting at steps 56-65: %d of %d runs stopped, worst balance error %.3g\n%s\n", stopped, runs,
              worst, stops.c_str());
  EXPECT_EQ(stopped, 0) << stops;
  // An elastic run: the balance is round-off (the suite's 0.5 % as the limit).
  EXPECT_LT(worst, 5e-3);
  record_margin({"07c-late-load-no-false-alarm", "a load starting after the energy check's first step (steps 56-65)",
                 "no false alarm: every run completes, balance error at round-off",
                 std::to_string(runs - stopped) + " of " + std::to_string(runs) +
                     " runs complete, worst balance error " + sci(worst),
                 "balance " + sci(worst) + " vs 5e-3", stopped == 0 && worst < 5e-3});
}

TEST(StabilityGuards, EnergyCheckStopsTheRunWithExitCode3AndKeepsAReadableRunDirectory) {
  const std::string dir = fresh_directory("energy-guard-cli");
  const std::string points = fresh_directory("energy-guard-points") + ".vtp";
  const std::string scene = scene_path("elastic_block.yaml");
  const CommandResult pre = run_program(program("mppm-preprocess"), {scene, "-o", points, "--quiet"});
  ASSERT_EQ(pre.exit_code, 0) << pre.output;
  constexpr double kKick = 100.0;  // m/s, added to velocity component 0 of point 0 in step 100
  const CommandResult r =
      run_program(program("mppm-solve"),
                  {scene, "--points", points, "-o", dir, "--quiet", "--inject-kick", "100:0:0:" + std::to_string(kKick),
                   "--set", "time.end=400us", "--set", "output.interval=5us"});
  std::printf("mppm-solve with a velocity kick in step 100: exit %d\n%s", r.exit_code, r.output.c_str());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("energy"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("numerics.energy_check_tolerance"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at step 100,"), std::string::npos) << r.output;  // in the kick's own step
  // The growth it reports is the kick's kinetic energy 1/2 rho V dv^2 (+ rho V v dv with the
  // point's own velocity v, ~0.01 m/s at that step: 2 v / dv ~ 2e-4; 1 % bounds it with margin).
  const std::size_t grew = r.output.find("energy grew by ");
  ASSERT_NE(grew, std::string::npos) << r.output;
  const double reported = std::stod(r.output.substr(grew + 15));
  const Snapshot reference = read_snapshot(dir + "/" + run_layout::reference);
  const double volume = reference.find("volume")->data[0];
  constexpr double kDensity = 0.95 * 2650.0;  // elastic_block.yaml: rho = solid_fraction * density
  const double kick_energy = 0.5 * kDensity * volume * kKick * kKick;
  EXPECT_NEAR(reported, kick_energy, 1e-2 * kick_energy);
  const RunReport report = read_run(dir);
  EXPECT_EQ(report.status, "numerical_failure");
  EXPECT_NE(report.message.find("energy"), std::string::npos) << report.message;
  EXPECT_TRUE(report.all_finite);
  int kept = 0;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir)) {
    if (e.path().extension() != ".snap") continue;
    const Snapshot s = read_snapshot(e.path().string());
    for (const auto& f : s.fields)
      for (double v : f.data) ASSERT_TRUE(std::isfinite(v)) << e.path();
    ++kept;
  }
  EXPECT_GE(kept, 1);
  // No temporary left behind by an interrupted write.
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  record_margin({"07-energy-guard-exit-3", "the periodic energy check's stop path, end to end (mppm-solve)",
                 "exit 3, run_info status numerical_failure with the reason, last good snapshot kept and finite",
                 "exit " + std::to_string(r.exit_code) + ", status " + report.status + ", " + std::to_string(kept) +
                     " snapshot(s) kept",
                 "contract check (no numeric margin)",
                 r.exit_code == 3 && report.status == "numerical_failure" && kept >= 1});
}

// A run directory left by a guard's stop: status, message, the kept snapshots (all finite, the
// last one's step), no temporaries.
struct StoppedRun {
  RunReport report;
  int kept = 0;
  std::int64_t last_snapshot_step = -1;
  bool snapshots_finite = true;
  bool temporaries = false;
};

StoppedRun read_stopped_run(const std::string& dir) {
  StoppedRun s;
  s.report = read_run(dir);
  for (const std::string& file : s.report.snapshots) {
    const Snapshot snap = read_snapshot(file);
    for (const auto& f : snap.fields)
      for (double v : f.data) s.snapshots_finite = s.snapshots_finite && std::isfinite(v);
    s.last_snapshot_step = std::max(s.last_snapshot_step, snap.step);
    ++s.kept;
  }
  for (const auto& e : fs::recursive_directory_iterator(dir))
    s.temporaries = s.temporaries || e.path().filename().string().find(".tmp") != std::string::npos;
  return s;
}

// The last time in energy.csv.
double last_energy_time(const std::string& dir) {
  const std::string text = read_text(dir + "/" + run_layout::energy);
  const auto end = text.find_last_not_of('\n');
  const auto start = text.rfind('\n', end);
  return std::strtod(text.c_str() + (start == std::string::npos ? 0 : start + 1), nullptr);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class StabilityGuardsEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // Named per process: ctest runs the tests of this fixture as parallel processes.
    const std::string tag = std::to_string(::getpid());
    block_points_ = fresh_directory("guards-block-points-" + tag) + ".vtp";
    fragmentation_points_ = fresh_directory("guards-fragmentation-points-" + tag) + ".vtp";
    for (const auto& [scene, points] : {std::pair{scene_path("elastic_block.yaml"), block_points_},
                                        std::pair{scene_path("fragmentation_block.yaml"), fragmentation_points_}}) {
      const CommandResult r = run_program(program("mppm-preprocess"), {scene, "-o", points, "--quiet"});
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
  }
  static void TearDownTestSuite() {
    fs::remove(block_points_);
    fs::remove(fragmentation_points_);
  }
  static std::string block_points_, fragmentation_points_;
};
std::string StabilityGuardsEndToEnd::block_points_, StabilityGuardsEndToEnd::fragmentation_points_;

TEST_F(StabilityGuardsEndToEnd, NanInjectedInOnePointStopsMppmSolveWithExitCode3NamingPointAndStep) {
  // elastic_block.yaml: 400 points (20 x 20, index = row * 20 + column) and a left layer; the
  // auto step is ~0.385 us, so 400 us are ~1040 steps with a snapshot every 20 us (~52 steps).
  struct Seed {
    std::int64_t step;
    std::size_t point;
    std::string field;
    const char* where;
  };
  const std::vector<Seed> seeds{{500, 210, "velocity", "interior"},
                                {333, 0, "rotation", "corner"},
                                {777, 19, "displacement", "corner (free edge)"},
                                {612, 390, "force", "edge"},
                                {401, 105, "rotation_rate", "interior"}};
  std::string measured;
  bool all = true;
  for (const Seed& k : seeds) {
    const std::string dir = fresh_directory("nan-inject-" + k.field);
    const std::string hook = std::to_string(k.step) + ":" + std::to_string(k.point) + ":" + k.field;
    const CommandResult r = run_program(
        program("mppm-solve"), {scene_path("elastic_block.yaml"), "--points", block_points_, "-o", dir, "--quiet",
                                "--inject-nan", hook, "--set", "time.end=400us", "--set", "output.interval=20us"});
    std::printf("--inject-nan %s: exit %d\n%s", hook.c_str(), r.exit_code, r.output.c_str());
    const StoppedRun s = read_stopped_run(dir);
    // The point named is the one seeded, in the step seeded, and it is the only one: the guard
    // ran before the NaN could reach a neighbour. A force NaN reaches the velocity in that step's
    // kick; the other fields are caught as themselves.
    const std::string field = k.field == "force" ? "velocity" : k.field;
    const std::string where = "step " + std::to_string(k.step) + ",";
    const std::string what = "non-finite " + field + " at point " + std::to_string(k.point) + " ";
    const bool ok = r.exit_code == 3 && s.report.status == "numerical_failure" && contains(s.report.message, where) &&
                    contains(s.report.message, what) && contains(s.report.message, "1 point(s) non-finite") &&
                    contains(r.output, what) && s.report.steps == k.step && s.kept >= 1 && s.snapshots_finite &&
                    s.last_snapshot_step < k.step && s.report.all_finite && !s.temporaries &&
                    contains(s.report.log, "test hook (--inject-nan)");
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_EQ(s.report.status, "numerical_failure");
    EXPECT_TRUE(contains(s.report.message, where)) << s.report.message;
    EXPECT_TRUE(contains(s.report.message, what)) << s.report.message;
    EXPECT_TRUE(contains(s.report.message, "1 point(s) non-finite")) << s.report.message;
    EXPECT_TRUE(contains(r.output, what)) << r.output;
    EXPECT_EQ(s.report.steps, k.step);
    EXPECT_GE(s.kept, 1);
    EXPECT_TRUE(s.snapshots_finite);
    EXPECT_LT(s.last_snapshot_step, k.step);
    EXPECT_TRUE(s.report.all_finite);  // no row of the bad step in energy.csv
    EXPECT_LT(last_energy_time(dir), static_cast<double>(k.step) * s.report.time_step);
    EXPECT_FALSE(s.temporaries);
    // The run says it was made to fail: nobody mistakes the stop for a real one.
    EXPECT_TRUE(contains(s.report.log, "test hook (--inject-nan)")) << s.report.log;
    measured += (measured.empty() ? "" : "; ") + k.field + " of " + k.where + " point " + std::to_string(k.point) +
                " at step " + std::to_string(k.step) + ": exit " + std::to_string(r.exit_code) + ", reported step " +
                std::to_string(s.report.steps) + ", last snapshot step " + std::to_string(s.last_snapshot_step);
    all = all && ok;
  }

  // The hooks themselves refuse what they cannot do (exit 2, nothing written): --inject-nan, and
  // --inject-kick (whose stop path is case 2). {option, value, a word the message must hold}.
  struct BadHook {
    std::string option, value, word;
  };
  const std::vector<BadHook> bad{{"--inject-nan", "0:1", "STEP"},
                                 {"--inject-nan", "x:1", "STEP"},
                                 {"--inject-nan", "5:100000", "POINT"},
                                 {"--inject-nan", "5:1:pressure", "FIELD"},
                                 {"--inject-nan", "5", "STEP:POINT"},
                                 {"--inject-nan", "5:1:velocity:2", "COMPONENT"},
                                 {"--inject-nan", "100000:1", "beyond"},
                                 {"--inject-kick", "0:1:0:5", "STEP"},
                                 {"--inject-kick", "5:x:0:5", "POINT"},
                                 {"--inject-kick", "5:100000:0:5", "POINT"},
                                 {"--inject-kick", "5:1:7:5", "COMPONENT"},
                                 {"--inject-kick", "5:1:0:5 MPa", "VELOCITY"},
                                 {"--inject-kick", "5:1:0", "STEP:POINT:COMPONENT:VELOCITY"},
                                 {"--inject-kick", "5:1:0:nan", "VELOCITY"},
                                 {"--inject-kick", "100000:1:0:5", "beyond"}};
  for (const BadHook& h : bad) {
    const std::string dir = fresh_directory("inject-bad");
    const CommandResult r = run_program(
        program("mppm-solve"),
        {scene_path("elastic_block.yaml"), "--points", block_points_, "-o", dir, "--quiet", h.option, h.value});
    std::printf("%s %s: exit %d\n%s", h.option.c_str(), h.value.c_str(), r.exit_code, r.output.c_str());
    EXPECT_EQ(r.exit_code, 2) << h.option << " " << h.value;
    EXPECT_TRUE(contains(r.output, h.option)) << r.output;
    EXPECT_TRUE(contains(r.output, h.word)) << r.output;
    EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir)) << dir;
    all = all && r.exit_code == 2;
  }
  record_margin(
      {"06b-nan-injected-end-to-end", "a NaN appearing in one point mid-step, end to end (mppm-solve --inject-nan)",
       "exit 3, run_info numerical_failure naming the point and the step, kept snapshots finite and older", measured,
       "contract check (no numeric margin): detected in the step of the fault, 1 point named", all});
}

TEST_F(StabilityGuardsEndToEnd, BothGuardsCoverDamageRuns) {
  // The fragmentation scene as it is (1 GPa pulse over 2 x 2.5 us, G_cr 20 N/m): by 8 us a third
  // of the block has lost every bond (test_stability_fragmentation.cpp); 100 us are ~190 steps.
  const std::vector<std::string> common{scene_path("fragmentation_block.yaml"),
                                        "--points",
                                        fragmentation_points_,
                                        "--quiet",
                                        "--set",
                                        "time.end=100us",
                                        "--set",
                                        "output.interval=10us"};
  auto solve = [&](const std::string& dir, const std::vector<std::string>& extra) {
    std::vector<std::string> args = common;
    args.push_back("-o");
    args.push_back(dir);
    args.insert(args.end(), extra.begin(), extra.end());
    return run_program(program("mppm-solve"), args);
  };
  // a. The energy check, made to trip by a velocity kick (as in case 2): 1000 m/s on point 0 in
  //    step 100, about 2 J against an energy scale of about 9 J: it runs on the damage balance.
  const std::string energy_dir = fresh_directory("damage-energy-guard");
  const CommandResult e = solve(energy_dir, {"--inject-kick", "100:0:0:1000"});
  std::printf("damage run, velocity kick: exit %d\n%s", e.exit_code, e.output.c_str());
  const StoppedRun se = read_stopped_run(energy_dir);
  EXPECT_EQ(e.exit_code, 3) << e.output;
  EXPECT_EQ(se.report.status, "numerical_failure");
  EXPECT_TRUE(contains(se.report.message, "numerics.energy_check_tolerance")) << se.report.message;
  EXPECT_TRUE(se.snapshots_finite);
  EXPECT_GE(se.kept, 1);
  EXPECT_FALSE(se.temporaries);

  // b. The same scene at the default tolerance completes: no false alarm while bonds break.
  const std::string quiet_dir = fresh_directory("damage-energy-guard-default");
  const CommandResult q = solve(quiet_dir, {});
  const StoppedRun sq = read_stopped_run(quiet_dir);
  std::printf("damage run, default energy check: exit %d, %lld detached, %lld pairs broken, worst balance %.3g\n%s",
              q.exit_code, static_cast<long long>(sq.report.detached_points),
              static_cast<long long>(sq.report.broken_bonds), sq.report.worst_balance_error, q.output.c_str());
  EXPECT_EQ(q.exit_code, 0) << q.output;
  EXPECT_GT(sq.report.detached_points, 0);

  // c. A NaN in step 150 (~80 us), long after bonds broke and points detached, in the corner
  //    point 0 of the loaded face (detached by then: a ballistic point is guarded too).
  const std::string nan_dir = fresh_directory("damage-nan");
  const CommandResult n = solve(nan_dir, {"--inject-nan", "150:0:velocity"});
  std::printf("damage run, NaN injected: exit %d\n%s", n.exit_code, n.output.c_str());
  const StoppedRun sn = read_stopped_run(nan_dir);
  EXPECT_EQ(n.exit_code, 3) << n.output;
  EXPECT_TRUE(contains(sn.report.message, "non-finite velocity at point 0 ")) << sn.report.message;
  EXPECT_TRUE(contains(sn.report.message, "step 150,")) << sn.report.message;
  EXPECT_TRUE(sn.snapshots_finite);

  record_margin(
      {"07b-guards-on-damage-runs",
       "the guards on a damage run (fragmentation scene: bonds breaking, points detaching)",
       "energy check trips on unexplained growth with the fracture dissipation in its sum (exit 3); no false alarm at "
       "the default tolerance (exit 0); a NaN caught in its step (exit 3)",
       "velocity kick: exit " + std::to_string(e.exit_code) + "; default: exit " + std::to_string(q.exit_code) +
           " with " + std::to_string(sq.report.detached_points) + " points detached, worst balance error " +
           sci(sq.report.worst_balance_error) + "; NaN: exit " + std::to_string(n.exit_code),
       "balance " + sci(sq.report.worst_balance_error) + " vs the check's 5e-2 (" +
           sci(5e-2 / std::max(sq.report.worst_balance_error, 1e-300), 2) + " x)",
       e.exit_code == 3 && q.exit_code == 0 && n.exit_code == 3 && sq.report.detached_points > 0});
}

}  // namespace
}  // namespace mppm::stability
