// The run directory of mppm-solve (docs/stages.md): files, tables, snapshots, refusal to overwrite,
// bitwise-identical output for 1 and 2 threads, and the numerical-failure path (exit code 3
// with the last good snapshot kept).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/input_error.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "solver/interruption.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/solve_run.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

namespace fs = std::filesystem;
using testing::add_end_layers;
using testing::kinematic_condition;
using testing::make_lattice;
using testing::make_scene;

constexpr double kDx = 1e-3;

std::string fresh_directory(const std::string& name) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "solver-test-runs" / name;
  fs::remove_all(dir);
  return dir.string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A bar held on the left and pulled on the right (velocity ramp), micropolar, 2-D.
struct BarCase {
  Scene scene;
  PointCloud cloud;
};

BarCase bar(std::array<int, 3> n, double horizon_factor) {
  BarCase c;
  c.scene = make_scene(2, true, kDx, horizon_factor);
  const int depth = static_cast<int>(std::ceil(horizon_factor));
  c.cloud = make_lattice(2, n, kDx, c.scene.thickness);
  c.cloud.horizon = horizon_factor * kDx;
  add_end_layers(c.cloud, n[0], depth, "displacement", "velocity");
  c.scene.boundary_conditions = {
      kinematic_condition("left", BoundaryType::displacement, {0.0}, {{0.0, 0.0}}),
      kinematic_condition("right", BoundaryType::velocity, {0.0, 20e-6}, {{0.0, 0.0}, {0.5, 0.0}})};
  c.scene.time.end = 40e-6;
  c.scene.output.interval = 10e-6;
  c.scene.output.fields = {"displacement", "rotation", "rotation_rate", "stress", "porosity", "damage"};
  return c;
}

SolveOptions options_for(const std::string& dir) {
  SolveOptions o;
  o.run_directory = dir;
  o.points_file = "bar.vtp";
  return o;
}

TEST(SolverRun, WritesTheRunDirectory) {
  const BarCase c = bar({24, 6, 1}, 3.05);
  const std::string dir = fresh_directory("bar");
  const SolveResult r = solve(c.scene, c.cloud, options_for(dir));
  EXPECT_GT(r.steps, 10);
  EXPECT_LE(r.time_step, c.scene.time.safety * r.critical_time_step * (1 + 1e-12));
  for (const char* f : {run_layout::resolved_scene, run_layout::log, run_layout::load, run_layout::energy,
                        run_layout::run_info, run_layout::reference})
    EXPECT_TRUE(fs::exists(fs::path(dir) / f)) << f;
  // load.csv: header from the contract, one row per step (load_interval 0) plus t = 0.
  const std::string load = read_text(dir + "/" + run_layout::load);
  EXPECT_EQ(load.substr(0, load.find('\n')),
            "time_s,left_ux_m,left_uy_m,left_Fx_N,left_Fy_N,right_ux_m,right_uy_m,right_Fx_N,right_Fy_N");
  EXPECT_EQ(std::count(load.begin(), load.end(), '\n'), r.steps + 2);
  const std::string energy = read_text(dir + "/" + run_layout::energy);
  EXPECT_EQ(energy.substr(0, energy.find(',')), "time_s");
  const std::string info = read_text(dir + "/" + run_layout::run_info);
  EXPECT_NE(info.find("\"status\": \"completed\""), std::string::npos) << info;
  EXPECT_NE(info.find("\"limiting_mode\""), std::string::npos);
  // Snapshots at 0, 10, 20, 30, 40 us hold the requested fields the run has (no damage: off).
  int snapshots = 0;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir)) {
    const Snapshot s = read_snapshot(e.path().string());
    ++snapshots;
    EXPECT_NE(s.find("displacement"), nullptr);
    EXPECT_NE(s.find("rotation"), nullptr);
    EXPECT_NE(s.find("rotation_rate"), nullptr);
    EXPECT_NE(s.find("stress"), nullptr);
    EXPECT_NE(s.find("porosity"), nullptr);
    EXPECT_EQ(s.find("damage"), nullptr);
    EXPECT_EQ(s.point_count, c.cloud.size());
  }
  EXPECT_EQ(snapshots, 5);
  // The right end was pulled by 0.5 m/s * (40 - 10) us: its mean displacement in the last row.
  const std::string last = load.substr(load.rfind('\n', load.size() - 2) + 1);
  double values[9];
  std::stringstream row(last);
  for (double& v : values) {
    std::string cell;
    std::getline(row, cell, ',');
    v = std::stod(cell);
  }
  EXPECT_NEAR(values[5], 0.5 * 30e-6, 1e-15);
  EXPECT_GT(values[7], 0.0);            // the bar resists the pull: reaction along the motion
  EXPECT_NEAR(values[1], 0.0, 1e-300);  // the held end does not move
  // Refuses to overwrite without --force, accepts with it.
  EXPECT_THROW(solve(c.scene, c.cloud, options_for(dir)), InputError);
  SolveOptions forced = options_for(dir);
  forced.force = true;
  EXPECT_NO_THROW(solve(c.scene, c.cloud, forced));
}

TEST(SolverRun, OneAndTwoThreadsGiveIdenticalFiles) {
  // Every loop threaded, also on this small lattice (see solver/parallel_policy.hpp).
  const ParallelThresholds saved_thresholds = parallel_thresholds();
  parallel_thresholds() = ParallelThresholds{1, 1, 1};
  BarCase c = bar({40, 12, 1}, 3.05);
  c.scene.time.end = 30e-6;
  c.scene.output.interval = 10e-6;
  c.scene.output.fields = {"displacement", "rotation", "velocity", "stress", "couple_stress"};
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::string one = fresh_directory("threads1");
  solve(c.scene, c.cloud, options_for(one));
  omp_set_num_threads(2);
  const std::string two = fresh_directory("threads2");
  solve(c.scene, c.cloud, options_for(two));
  omp_set_num_threads(saved);
  parallel_thresholds() = saved_thresholds;
  EXPECT_EQ(read_text(one + "/" + run_layout::load), read_text(two + "/" + run_layout::load));
  EXPECT_EQ(read_text(one + "/" + run_layout::energy), read_text(two + "/" + run_layout::energy));
  int compared = 0;
  for (const auto& e : fs::directory_iterator(fs::path(one) / run_layout::snapshot_dir)) {
    const std::string other = (fs::path(two) / run_layout::snapshot_dir / e.path().filename()).string();
    ASSERT_TRUE(fs::exists(other));
    EXPECT_EQ(read_text(e.path().string()), read_text(other)) << e.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 3);
}

// How often energies are reported must not change the motion: the kernel evaluated with energies
// (every step here) gives the same forces, to the bit, as without them (only at the end).
TEST(SolverRun, EnergyRowsDoNotChangeTheMotion) {
  BarCase c = bar({40, 12, 1}, 3.05);
  c.scene.time.end = 20e-6;
  c.scene.output.interval = 20e-6;
  c.scene.output.fields = {"displacement", "rotation", "velocity"};
  c.scene.output.load_interval = 0.0;
  const std::string every = fresh_directory("energy_every_step");
  solve(c.scene, c.cloud, options_for(every));
  c.scene.output.load_interval = 20e-6;
  const std::string end = fresh_directory("energy_at_end");
  const SolveResult r = solve(c.scene, c.cloud, options_for(end));
  ASSERT_GT(r.steps, 5);
  const std::string last = std::string(run_layout::snapshot_dir) + "/" + run_layout::snapshot_name(r.steps);
  ASSERT_TRUE(fs::exists(fs::path(end) / last)) << last;
  EXPECT_EQ(read_text(every + "/" + last), read_text(end + "/" + last));
}

// Energy the balance does not explain (here a negative damping coefficient, whose work the
// integrator does not book) stops the run from numerics.energy_check_start_step on; a start after
// the run's last step lets it finish.
TEST(SolverRun, EnergyCheckStartsAtTheSceneStep) {
  BarCase c = bar({24, 6, 1}, 3.05);
  c.scene.numerics.damping = -5e4;
  c.scene.time.end = 400e-6;  // about 280 steps: the check starts at step 50 by default
  c.scene.output.interval = 100e-6;
  c.scene.output.fields = {"displacement"};
  const std::string tripped = fresh_directory("energy-check-default");
  EXPECT_THROW(solve(c.scene, c.cloud, options_for(tripped)), NumericalFailure);
  const std::string info = read_text(tripped + "/" + run_layout::run_info);
  EXPECT_NE(info.find("energy grew by"), std::string::npos) << info;
  c.scene.numerics.energy_check_start_step = 1000000;
  const std::string late = fresh_directory("energy-check-late");
  EXPECT_NO_THROW(solve(c.scene, c.cloud, options_for(late)));
}

TEST(SolverRun, NonFiniteStateStopsWithNumericalFailureAndKeepsTheLastGoodSnapshot) {
  BarCase c = bar({24, 6, 1}, 3.05);
  // A velocity history that turns non-finite after 20 us (the guard must catch it, whatever the cause).
  c.scene.boundary_conditions[1].value.times = {0.0, 20e-6, 25e-6};
  c.scene.boundary_conditions[1].value.values = {
      {0.0, 0.0}, {0.5, 0.0}, {std::numeric_limits<double>::infinity(), 0.0}};
  const std::string dir = fresh_directory("failure");
  EXPECT_THROW(solve(c.scene, c.cloud, options_for(dir)), NumericalFailure);
  const std::string info = read_text(dir + "/" + run_layout::run_info);
  EXPECT_NE(info.find("\"status\": \"numerical_failure\""), std::string::npos) << info;
  EXPECT_NE(info.find("non-finite"), std::string::npos);
  // Snapshots before the failure are kept and readable; none after it.
  int kept = 0;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir)) {
    const Snapshot s = read_snapshot(e.path().string());
    EXPECT_LE(s.time, 20e-6 + 1e-12);
    for (const auto& f : s.fields)
      for (double v : f.data) ASSERT_TRUE(std::isfinite(v));
    ++kept;
  }
  EXPECT_GE(kept, 2);
}

TEST(SolverRun, InterruptionStopsCleanlyWithALastSnapshot) {
  const BarCase c = bar({24, 6, 1}, 3.05);
  const std::string dir = fresh_directory("interrupted");
  request_interruption();  // as the SIGINT handler would, before the first step ends
  const SolveResult r = solve(c.scene, c.cloud, options_for(dir));
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.steps, 1);
  EXPECT_FALSE(interruption_requested());
  const std::string info = read_text(dir + "/" + run_layout::run_info);
  EXPECT_NE(info.find("\"status\": \"interrupted\""), std::string::npos) << info;
  const Snapshot last = read_snapshot(dir + "/" + run_layout::snapshot_dir + "/" + run_layout::snapshot_name(1));
  EXPECT_EQ(last.step, 1);
  const std::string load = read_text(dir + "/" + run_layout::load);
  EXPECT_EQ(std::count(load.begin(), load.end(), '\n'), 3);  // header, t = 0, step 1
}

TEST(SolverRun, InconsistentPointsFileIsBadInput) {
  BarCase c = bar({24, 6, 1}, 3.05);
  c.cloud.boundaries[1].type = "traction";
  EXPECT_THROW(solve(c.scene, c.cloud, options_for(fresh_directory("bad1"))), InputError);
  c = bar({24, 6, 1}, 3.05);
  c.scene.geometry.horizon_factor = 4.05;  // points were made for 3.05
  EXPECT_THROW(solve(c.scene, c.cloud, options_for(fresh_directory("bad2"))), InputError);
  // A horizon below the spacing: no bonds, every point detached.
  c = bar({24, 6, 1}, 0.9);
  EXPECT_THROW(solve(c.scene, c.cloud, options_for(fresh_directory("bad3"))), InputError);
}

}  // namespace
}  // namespace mppm::solver
