// Stability cases: damage runs of the project's own geometries under extreme loading, end to end
// through the stage executables (the exit code is part of the outcome).
// 1. The crack-branching plate (workflows/crack-branching/scene.yaml, geometry/branching_plate.geo)
//    with its tractions ramped to 30 MPa over 0.5 us instead of 8 MPa over 6.25 us: 3.75 x the
//    stress at 46 x the rate. Hazard: the load arrives as a shock; the crack runs, branches and
//    the zones beyond the no-fail strips shatter; points left with lopsided families make the step
//    unstable, a NaN or energy from nothing follows. Expected: every written value
//    finite, the energy balance within 0.5 %, and either completion or a stop with exit code 3 and
//    a clear reason; measured: it completes (see the record and README.md for why), so completion
//    is what the test requires. Short form: the plate at dx = 1 mm for 10 us; long form: the
//    case's own lattice (dx = 0.5 mm, 16 000 points) for the case's 60 us.
// 2. The 3-D notched CAD specimen (geometry/notched_specimen_3d.step, scenes/notched_impact_3d.yaml)
//    under a Charpy-like impact with damage. Hazard: the same in 3-D, where a point needs 4
//    non-coplanar bonds and a shattered zone under the striker leaves many nearly singular shape
//    tensors. Expected: finite, balance within 0.5 %, detached points reported.
//    Measured: it completes with the default energy check; breaking bonds puts 0.012 % of the
//    work into the model in the short form, 0.13 % in the long one (28 % until the damage code
//    detached the points whose stored energy rises by more than half when they lose bonds; 0.54 %
//    and 1.16 % until it also detached overloaded points on any rise); test 2b the same with the
//    check relaxed, 2c the impact at 15 m/s. Short form: dx = 2 mm (2 752 points) for 40 us; long
//    form: dx = 1 mm for 60 us.
// 3. Breaking the bonds between a prescribed layer and the body keeps the booked balance.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/snapshot_file.hpp"
#include "tests/stability/stability_support.hpp"

namespace mppm::stability {
namespace {

namespace fs = std::filesystem;

// What a damage run directory says, read back through its files.
struct DamageRun {
  CommandResult solve;
  RunReport report;
  bool snapshots_finite = true;
  std::size_t snapshots = 0;
  std::int64_t detached_in_last = -1;
  double max_damage = 0.0;
  std::size_t points = 0;
  double seconds = 0.0;
};

DamageRun run_case(const std::string& scene, const std::string& name, const std::vector<std::string>& geometry_sets,
                   const std::vector<std::string>& run_sets) {
  DamageRun d;
  const std::string points = fresh_directory(name + "-points") + ".vtp";
  fs::remove(points);
  std::vector<std::string> pre{scene, "-o", points, "--quiet"};
  for (const auto& s : geometry_sets) {
    pre.push_back("--set");
    pre.push_back(s);
  }
  const CommandResult p = run_program(program("mppm-preprocess"), pre);
  EXPECT_EQ(p.exit_code, 0) << p.output;
  const std::string run = fresh_directory(name);
  std::vector<std::string> args{scene, "--points", points, "-o", run, "--quiet", "--threads", "1"};
  for (const auto& s : geometry_sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  for (const auto& s : run_sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  const auto start = std::chrono::steady_clock::now();
  d.solve = run_program(program("mppm-solve"), args);
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  d.report = read_run(run);
  for (const std::string& file : d.report.snapshots) {
    const Snapshot s = read_snapshot(file);
    for (const auto& f : s.fields)
      for (double v : f.data) d.snapshots_finite = d.snapshots_finite && std::isfinite(v);
    if (const SnapshotField* damage = s.find("damage"))
      for (double v : damage->data) d.max_damage = std::max(d.max_damage, v);
    if (const SnapshotField* detached = s.find("detached"))
      d.detached_in_last =
          std::count_if(detached->data.begin(), detached->data.end(), [](double v) { return v != 0.0; });
    d.points = s.point_count;
    ++d.snapshots;
  }
  fs::remove(points);
  return d;
}

std::string outcome(const DamageRun& d) {
  const std::string& m = d.report.message;
  return "exit " + std::to_string(d.solve.exit_code) + ", status " + d.report.status +
         (m.empty() ? std::string() : " (" + m.substr(0, m.find("; the last good")) + ")");
}

std::string summary(const DamageRun& d) {
  const RunReport& r = d.report;
  return outcome(d) + ", " + std::to_string(r.steps) + " steps of " + sci(r.time_step) + " s (critical " +
         sci(r.critical_time_step) + " s, " + r.limiting_mode + "), " + std::to_string(d.points) + " points, " +
         std::to_string(r.broken_bonds) + " bond pairs broken, max damage " + sci(d.max_damage) + ", " +
         std::to_string(r.detached_points) + " detached (last snapshot " + std::to_string(d.detached_in_last) +
         "), fracture dissipation " + sci(r.final_fracture_dissipation) + " J of " + sci(r.final_external_work) +
         " J work (breakage put " + sci(r.fracture_dissipation_decrease) +
         " J = " + sci(r.fracture_dissipation_decrease / std::max(r.final_external_work, 1e-300)) +
         " of the work in), worst balance error " + sci(r.worst_balance_error) + ", " + sci(d.seconds, 3) + " s wall";
}

// The checks both cases share: finite, balanced, reported the same everywhere.
void expect_consistent(const DamageRun& d) {
  const RunReport& r = d.report;
  EXPECT_TRUE(r.all_finite);
  EXPECT_TRUE(d.snapshots_finite);
  EXPECT_GE(d.snapshots, 2u);
  EXPECT_LT(r.worst_balance_error, 5e-3);
  // The balance a reader of energy.csv recomputes from its columns, fracture dissipation included
  // (the sum the energy check uses), meets the same bound. (Not round-off here, unlike the free
  // fragmentation block: with prescribed layers the 3-D specimen at dx = 1 mm books 4e-6, see
  // README.md finding 5.)
  EXPECT_LT(r.worst_recomputed_balance_error, 5e-3);
  EXPECT_EQ(r.detached_points, d.detached_in_last);
  EXPECT_NE(r.log.find("detached points " + std::to_string(r.detached_points)), std::string::npos) << r.log;
}

TEST(StabilityCrackBranchingRate, ThirtyMegapascalsOverHalfAMicrosecondStaysFiniteAndBalanced) {
  const std::string scene = std::string(MPPM_SOURCE_DIR) + "/workflows/crack-branching/scene.yaml";
  // Short form: dx = 1 mm (4 000 points, the case's horizon factor 4.05) for 10 us (the shock
  // crosses half the plate and the crack starts); long form: the case itself (dx = 0.5 mm, 60 us).
  std::vector<std::string> geometry;
  std::vector<std::string> sets{"boundary_conditions[0].value=[0, 30 MPa]", "boundary_conditions[0].ramp=0.5 us",
                                "boundary_conditions[1].value=[0, -30 MPa]", "boundary_conditions[1].ramp=0.5 us",
                                "output.fields=[displacement, rotation, damage, detached]"};
  if (long_form()) {
    sets.push_back("output.interval=2.5 us");
  } else {
    geometry.push_back("geometry.spacing=1 mm");
    sets.push_back("time.end=10 us");
    sets.push_back("output.interval=1 us");
  }
  const DamageRun d = run_case(scene, "crack-branching-30MPa", geometry, sets);
  const RunReport& r = d.report;
  std::printf("crack-branching plate, 30 MPa over 0.5 us: %s\n%s", summary(d).c_str(), d.solve.output.c_str());
  const bool pass = d.solve.exit_code == 0 && r.status == "completed" && r.all_finite && d.snapshots_finite &&
                    r.worst_balance_error < 5e-3 && r.detached_points == d.detached_in_last && r.broken_bonds > 0;
  record_margin(
      {"13-crack-branching-30MPa",
       "crack-branching plate, tractions ramped to 30 MPa over 0.5 us (3.75 x the load, 46 x the rate)",
       "finite, energy balance within 0.5 %, completes or stops with exit 3 and a reason (measured: completes)",
       summary(d),
       "balance " + sci(r.worst_balance_error) + " vs 5e-3 (" + sci(5e-3 / std::max(r.worst_balance_error, 1e-300), 2) +
           " x)",
       pass});
  EXPECT_EQ(d.solve.exit_code, 0) << d.solve.output;
  EXPECT_EQ(r.status, "completed") << r.message;
  expect_consistent(d);
  EXPECT_GT(r.broken_bonds, 0);  // the crack did run (the hazard happened)
  EXPECT_GT(r.final_fracture_dissipation, 0.0);
}

std::vector<std::string> notched_geometry() {
  return long_form() ? std::vector<std::string>{"geometry.spacing=1 mm"} : std::vector<std::string>{};
}
std::vector<std::string> notched_time() {
  return long_form() ? std::vector<std::string>{"time.end=60 us"} : std::vector<std::string>{};
}

TEST(StabilityNotchedImpact3d, ImpactCompletesWithTheDefaultEnergyCheck) {
  const DamageRun d =
      run_case(scene_path("notched_impact_3d.yaml"), "notched-impact-3d", notched_geometry(), notched_time());
  const RunReport& r = d.report;
  std::printf("3-D notched specimen, impact, default energy check: %s\n%s", summary(d).c_str(), d.solve.output.c_str());
  const double created = r.fracture_dissipation_decrease / std::max(r.final_external_work, 1e-300);
  const bool pass = d.solve.exit_code == 0 && r.status == "completed" && r.all_finite && d.snapshots_finite &&
                    r.worst_balance_error < 5e-3 && created <= 1e-2 && r.detached_points > 0;
  record_margin(
      {"14-notched-impact-3d",
       "3-D notched CAD specimen (STEP), Charpy-like impact at 20 m/s, damage, default energy check",
       "finite, energy balance within 0.5 %, detached points reported, energy from breakage below 1 % of the work",
       summary(d),
       "balance " + sci(r.worst_balance_error) + " vs 5e-3; energy from breakage " + sci(created) + " vs 1e-2", pass});
  EXPECT_EQ(d.solve.exit_code, 0) << d.solve.output;
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_TRUE(r.all_finite);
  EXPECT_TRUE(d.snapshots_finite);
  EXPECT_LT(r.worst_balance_error, 5e-3);
  // Breaking bonds takes energy out; what is left are rises below the detachment margins
  // (solver/bond_breakage.hpp: 50 % of a point's energy, any rise of an overloaded point) and the
  // O(dt) kick term: measured 0.012 % of the work in the short form, 0.13 % in the long one (28 %
  // at 20 m/s before the 50 % rule; 0.54 % and 1.16 % with it alone, README.md finding 8); the
  // bound is the energy check's 5 % / 5.
  EXPECT_LE(created, 1e-2);
  EXPECT_GT(r.detached_points, 0);
  expect_consistent(d);
}

TEST(StabilityNotchedImpact3d, WithTheCheckRelaxedTheRunCompletesFiniteAndReportsDetachedPoints) {
  std::vector<std::string> sets = notched_time();
  sets.push_back("numerics.energy_check_tolerance=1e300");
  const DamageRun d =
      run_case(scene_path("notched_impact_3d.yaml"), "notched-impact-3d-relaxed", notched_geometry(), sets);
  const RunReport& r = d.report;
  std::printf("3-D notched specimen, impact, energy check relaxed: %s\n%s", summary(d).c_str(), d.solve.output.c_str());
  const bool pass = d.solve.exit_code == 0 && r.status == "completed" && r.all_finite && d.snapshots_finite &&
                    r.worst_balance_error < 5e-3 && r.detached_points == d.detached_in_last && r.broken_bonds > 0 &&
                    r.detached_points > 0;
  record_margin({"14b-notched-impact-3d-relaxed", "the same with numerics.energy_check_tolerance = 1e300",
                 "exit 0, finite, booked energy balance within 0.5 %, detached points reported consistently",
                 summary(d),
                 "balance " + sci(r.worst_balance_error) + " vs 5e-3 (" +
                     sci(5e-3 / std::max(r.worst_balance_error, 1e-300), 2) + " x)",
                 pass});
  EXPECT_EQ(d.solve.exit_code, 0) << d.solve.output;
  EXPECT_EQ(r.status, "completed") << r.message;
  expect_consistent(d);
  EXPECT_GT(r.broken_bonds, 0);
  EXPECT_GT(r.detached_points, 0);  // the hazard happened: points lost their families
}

// The same impact at 15 m/s: a slower striker crushes the zone under its edges longer before the
// points there lose their families, so they ratchet their stored energy up over more losses
// (finding 8 of README.md). Before overloaded points were detached on any rise, breakage put
// 4.8 % of the work in here in the long form (0.91 % in the short one), against the same bound as
// at 20 m/s: the energy check's 5 % / 5.
TEST(StabilityNotchedImpact3d, SlowerImpactPutsBelowOnePercentOfTheWorkIn) {
  std::vector<std::string> sets = notched_time();
  sets.push_back("boundary_conditions[0].value=[0, -15 m/s, 0]");
  const DamageRun d =
      run_case(scene_path("notched_impact_3d.yaml"), "notched-impact-3d-15ms", notched_geometry(), sets);
  const RunReport& r = d.report;
  std::printf("3-D notched specimen, impact at 15 m/s: %s\n%s", summary(d).c_str(), d.solve.output.c_str());
  const double created = r.fracture_dissipation_decrease / std::max(r.final_external_work, 1e-300);
  const bool pass = d.solve.exit_code == 0 && r.status == "completed" && r.all_finite && d.snapshots_finite &&
                    r.worst_balance_error < 5e-3 && created <= 1e-2 && r.detached_points > 0;
  record_margin(
      {"14c-notched-impact-3d-15ms", "the same impact at 15 m/s (the striker's edges crush longer)",
       "finite, energy balance within 0.5 %, detached points reported, energy from breakage below 1 % of the work",
       summary(d),
       "balance " + sci(r.worst_balance_error) + " vs 5e-3; energy from breakage " + sci(created) + " vs 1e-2", pass});
  EXPECT_EQ(d.solve.exit_code, 0) << d.solve.output;
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_LE(created, 1e-2);
  EXPECT_GT(r.detached_points, 0);
  expect_consistent(d);
}

// Bonds between a prescribed (velocity) layer and the body break without spoiling the booked
// balance (elastic_block.yaml with damage, G_cr 20 N/m, no no-fail zone, the layer's pulse at 5
// and 50 m/s: the layer's bonds break in its first steps of motion). The reaction work of the
// step in which they break is taken with the forces before the breaks (ExplicitDynamics::step).
TEST(StabilityCrackBranchingRate, BreakingTheBondsOfAPrescribedLayerKeepsTheBalance) {
  for (const char* speed : {"5 m/s", "50 m/s"}) {
    const std::string scene = scene_path("elastic_block.yaml");
    const DamageRun d = run_case(
        scene, "layer-bonds", {},
        {"effects=[micropolar, damage]", "material.damage={critical_energy_release_rate: 20 N/m, no_fail_depth: 0}",
         std::string("boundary_conditions[0].value=[") + speed + ", 0]", "boundary_conditions[0].rotation_rate=0",
         "time.end=40us", "numerics.energy_check_tolerance=1e300"});
    EXPECT_LT(d.report.worst_balance_error, 5e-3) << speed;
  }
}

}  // namespace
}  // namespace mppm::stability
