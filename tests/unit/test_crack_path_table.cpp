// The crack-arrival table run/crack_path.csv (common/crack_path.hpp, docs/stages.md) from the
// solver to the crack metrics: on a notched bar torn apart, every listed time agrees with the damage
// of every snapshot (a point is on the crack path in exactly the snapshots at or after its time),
// the table is the same on 1 and 2 threads, and a run without damage writes none; the crack metrics
// from the table's frames at the snapshot times are those of the snapshots' damage fields, and
// the table's fine frames hold every snapshot's frame, so that the start and branching times are
// never after the snapshots' ones, the start within one snapshot interval before (the solver's
// notched bar, and the synthetic branching crack of test_post_crack);
// mppm-postprocess says which source it used. (Restarts: test_checkpoint_restart.)
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "common/crack_path.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "postprocess/crack_path_table.hpp"
#include "postprocess/postprocess_run.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/solve_run.hpp"
#include "tests/unit/test_scratch_directory.hpp"
#include "tests/verification/solver_test_lattice.hpp"
#include "tests/verification/solver_viscoplastic_cases.hpp"

namespace mppm {
namespace {

namespace fs = std::filesystem;
using post::CrackArrival;
using solver::testing::add_end_layers;
using solver::testing::kinematic_condition;
using solver::testing::make_lattice;
using solver::testing::make_scene;
using solver::testing::read_text;

constexpr double kDx = 1e-3;
constexpr std::array<int, 3> kBar{24, 8, 1};
constexpr double kHorizonFactor = 3.05;
constexpr double kSnapshotInterval = 2e-6;

const std::string kScratch = "crack_path_table";
[[maybe_unused]] const ::testing::Environment* const kRemoveScratch =
    ::testing::AddGlobalTestEnvironment(new mppm::testing::RemoveScratch(kScratch));

std::string fresh_directory(const std::string& name) { return mppm::testing::fresh_scratch_directory(kScratch, name); }

struct Case {
  Scene scene;
  PointCloud cloud;
};

// A micropolar bar, 24 x 8 mm, held on the left and pulled on the right (the layers are the end
// four columns), with a 3 mm notch from the bottom edge at mid-length: the crack runs from the
// notch across the bar while it is pulled apart.
Case notched_bar(bool damage) {
  Case c;
  c.scene = make_scene(2, true, kDx, kHorizonFactor);
  c.cloud = make_lattice(2, kBar, kDx, c.scene.thickness);
  c.cloud.horizon = kHorizonFactor * kDx;
  add_end_layers(c.cloud, kBar[0], 4, "displacement", "velocity");
  c.cloud.precrack_vertices = {12e-3, -1e-3, 0.0, 12e-3, 3e-3, 0.0};
  c.scene.boundary_conditions = {
      kinematic_condition("left", BoundaryType::displacement, {0.0}, {{0.0, 0.0}}),
      kinematic_condition("right", BoundaryType::velocity, {0.0, 40e-6}, {{0.0, 0.0}, {6.0, 0.0}})};
  c.scene.effects.damage = damage;
  if (damage) c.scene.material.damage = DamageParameters{20.0, 0.0, DamageCalibration::lattice, std::nullopt};
  c.scene.time.end = 40e-6;
  c.scene.output.interval = kSnapshotInterval;
  c.scene.output.fields = {"displacement", "damage"};
  return c;
}

// The run on `threads` threads, every loop threaded (even on this small lattice).
std::string run(const Case& c, const std::string& name, int threads = 1) {
  const std::string dir = fresh_directory(name);
  const solver::ParallelThresholds saved_thresholds = solver::parallel_thresholds();
  const int saved = omp_get_max_threads();
  solver::parallel_thresholds() = solver::ParallelThresholds{1, 1, 1};
  omp_set_num_threads(threads);
  solver::SolveOptions o;
  o.run_directory = dir;
  o.points_file = "bar.vtp";
  solver::solve(c.scene, c.cloud, o);
  omp_set_num_threads(saved);
  solver::parallel_thresholds() = saved_thresholds;
  return dir;
}

std::vector<Snapshot> snapshots_of(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir))
    files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<Snapshot> out;
  for (const auto& f : files) out.push_back(read_snapshot(f));
  return out;
}

// The notched bar's run (1 thread), made once for the tests that read it.
const std::string& damage_run() {
  static const std::string dir = run(notched_bar(true), "notched_bar");
  return dir;
}

TEST(CrackPathTable, EveryTimeAgreesWithTheDamageOfEverySnapshot) {
  const std::vector<Snapshot> snapshots = snapshots_of(damage_run());
  ASSERT_GE(snapshots.size(), 10u);
  const std::size_t n = snapshots.front().point_count;
  const auto table = post::read_crack_path_table(damage_run(), n);
  ASSERT_TRUE(table);
  std::vector<double> arrival(n, std::numeric_limits<double>::infinity());
  for (const CrackArrival& a : *table) arrival[a.point] = a.time;
  for (const Snapshot& s : snapshots) {
    const std::vector<double>& damage = s.find("damage")->data;
    for (std::size_t i = 0; i < n; ++i)
      ASSERT_EQ(damage[i] >= kCrackDamageThreshold, arrival[i] <= s.time)
          << "point " << i << " (damage " << damage[i] << ", listed at " << arrival[i] << " s) in the snapshot at "
          << s.time << " s";
  }
  // The comparison is on a table with the pre-crack (time 0), a crack that grew, and times
  // between the snapshots.
  const auto at_start = std::count_if(table->begin(), table->end(), [](const CrackArrival& a) { return a.time == 0; });
  EXPECT_GT(at_start, 0);
  EXPECT_GT(table->size(), static_cast<std::size_t>(at_start) + 10);
  const auto between = std::count_if(table->begin(), table->end(), [](const CrackArrival& a) {
    const double k = a.time / kSnapshotInterval;
    return std::abs(k - std::round(k)) > 1e-6;
  });
  EXPECT_GT(between, 0);
}

TEST(CrackPathTable, IsTheSameOnOneAndTwoThreads) {
  const std::string two = run(notched_bar(true), "notched_bar_2_threads", 2);
  const std::string table = read_text(damage_run() + "/" + run_layout::crack_path);
  EXPECT_FALSE(table.empty());
  EXPECT_EQ(table, read_text(two + "/" + run_layout::crack_path));
}

TEST(CrackPathTable, RunWithoutDamageWritesNone) {
  const std::string dir = run(notched_bar(false), "notched_bar_elastic");
  EXPECT_TRUE(fs::exists(fs::path(dir) / run_layout::run_info));
  EXPECT_FALSE(fs::exists(fs::path(dir) / run_layout::crack_path));
}

// The body points of a run's reference snapshot (region 0), and the tracker's settings.
post::CrackTracker tracker_of(const Snapshot& reference, double dx, double horizon) {
  const std::size_t n = reference.point_count;
  const std::vector<double>& position = reference.find("position")->data;
  std::vector<double> x(n), y(n), z(n);
  std::vector<char> body(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = position[3 * i];
    y[i] = position[3 * i + 1];
    z[i] = position[3 * i + 2];
    body[i] = reference.find("region")->data[i] == 0.0;
  }
  post::CrackSettings settings;
  settings.spacing = dx;
  settings.horizon = horizon;
  return post::CrackTracker(x, y, z, body, settings);
}

// An event of the fine frames against the same event of the snapshots: both or neither, and then
// not after it and less than one snapshot interval before it.
void expect_within_one_interval_before(const std::optional<double>& fine, const std::optional<double>& coarse,
                                       double interval, const char* what) {
  ASSERT_EQ(fine.has_value(), coarse.has_value()) << what;
  if (!fine) return;
  EXPECT_LE(*fine, *coarse) << what;
  EXPECT_GT(*fine, *coarse - interval * (1 + 1e-9)) << what;
}

// The fine frames hold every snapshot's frame: the last fine frame at or before a snapshot's time
// has the snapshot's crack path, so the same tips and lengths. So an event (the first frame
// where something holds) of the fine frames is never after the snapshots' one; it is earlier by
// less than an interval when what it tests, once true, stays true (the start: the leading path
// length only grows), but a two-tip state that appears between two snapshots and is gone at the
// next one makes the fine branching time earlier than that.
void expect_fine_frames_hold_the_snapshot_frames(const post::CrackMetrics& fine, const post::CrackMetrics& coarse) {
  std::size_t f = 0;
  for (const post::CrackFrame& c : coarse.frames) {
    while (f + 1 < fine.frames.size() && fine.frames[f + 1].time <= c.time) ++f;
    ASSERT_LE(fine.frames[f].time, c.time);
    EXPECT_EQ(fine.frames[f].cracked_points, c.cracked_points) << "at " << c.time << " s";
    EXPECT_EQ(fine.frames[f].tips.size(), c.tips.size()) << "at " << c.time << " s";
    EXPECT_EQ(fine.frames[f].lead_path_length, c.lead_path_length) << "at " << c.time << " s";
    EXPECT_EQ(fine.frames[f].crack_length, c.crack_length) << "at " << c.time << " s";
  }
  if (coarse.branch_time_s) {
    ASSERT_TRUE(fine.branch_time_s);
    EXPECT_LE(*fine.branch_time_s, *coarse.branch_time_s);
  }
}

TEST(CrackPathTable, MetricsAgreeWithThoseOfTheSnapshots) {
  const std::vector<Snapshot> snapshots = snapshots_of(damage_run());
  const Snapshot reference = read_snapshot(damage_run() + "/" + run_layout::reference);
  const auto table = post::read_crack_path_table(damage_run(), reference.point_count);
  ASSERT_TRUE(table);
  const double horizon = kHorizonFactor * kDx;
  post::CrackTracker from_snapshots = tracker_of(reference, kDx, horizon);
  std::vector<double> times;
  for (const Snapshot& s : snapshots) {
    from_snapshots.add_frame(s.time, s.find("damage")->data);
    times.push_back(s.time);
  }
  post::CrackTracker at_snapshot_times = tracker_of(reference, kDx, horizon);
  post::add_table_frames(at_snapshot_times, *table, times);
  const post::CrackMetrics coarse = from_snapshots.finish(), same = at_snapshot_times.finish();
  ASSERT_TRUE(coarse.start_time_s) << "the crack must grow for this comparison";
  EXPECT_EQ(same.start_time_s, coarse.start_time_s);
  EXPECT_EQ(same.branch_time_s, coarse.branch_time_s);
  EXPECT_EQ(same.end_time_s, coarse.end_time_s);
  EXPECT_EQ(same.end_reason, coarse.end_reason);
  EXPECT_EQ(same.tip_speed_max_m_per_s, coarse.tip_speed_max_m_per_s);
  EXPECT_EQ(same.crack_length_m, coarse.crack_length_m);

  post::CrackTracker fine_tracker = tracker_of(reference, kDx, horizon);
  const post::CrackFrameSource source =
      post::add_crack_path_frames(fine_tracker, *table, times.front(), times.back(), 1e-9);
  const post::CrackMetrics fine = fine_tracker.finish();
  expect_within_one_interval_before(fine.start_time_s, coarse.start_time_s, kSnapshotInterval, "start");
  expect_fine_frames_hold_the_snapshot_frames(fine, coarse);
  // The crack path changed between snapshots: frames at other times than theirs.
  EXPECT_TRUE(std::any_of(fine.frames.begin(), fine.frames.end(), [&](const post::CrackFrame& f) {
    return std::find(times.begin(), times.end(), f.time) == times.end();
  }));
  EXPECT_EQ(source.frames, fine.frames.size());
}

// The synthetic branching crack of test_post_crack (growth at 1000 m/s from a pre-crack, two
// branches at +-15 degrees from 25 us), on its plate: arrival times on a 50 ns step, snapshots
// every 0.25 us. The table's frames at the snapshot times give the snapshots' metrics; its fine
// frames date start and branching within one snapshot interval before them.
TEST(CrackPathTable, SyntheticBranchingCrackAgreesWithItsSnapshots) {
  constexpr double dx = 0.5e-3, horizon = 4.05 * dx, interval = 0.25e-6, step = 50e-9, end = 60e-6;
  const double v = 1000.0, ts = 10e-6, tb = 25e-6, angle = 15.0 * std::numbers::pi / 180.0;
  const double bx = 0.05 + v * (tb - ts), by = 0.02;
  std::vector<double> x, y, z;
  std::vector<char> body;
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 200; ++i) {
      x.push_back((i + 0.5) * dx);
      y.push_back((j + 0.5) * dx);
      z.push_back(0.0);
      body.push_back(1);
    }
  // On the crack path at time t: within dx of the pre-crack, the grown straight part or a branch.
  auto on_crack = [&](std::size_t i, double t) {
    auto near = [&](double x0, double y0, double x1, double y1) {
      const double ux = x1 - x0, uy = y1 - y0, length2 = ux * ux + uy * uy;
      const double s = length2 > 0 ? std::clamp(((x[i] - x0) * ux + (y[i] - y0) * uy) / length2, 0.0, 1.0) : 0.0;
      return std::hypot(x[i] - x0 - s * ux, y[i] - y0 - s * uy) <= dx * (1 + 1e-9);
    };
    if (near(0.0, by, 0.05, by)) return true;
    if (t > ts && near(0.05, by, std::min(bx, 0.05 + v * (t - ts)), by)) return true;
    const double length = t > tb ? v * (t - tb) : 0.0;
    return t > tb && (near(bx, by, bx + length * std::cos(angle), by + length * std::sin(angle)) ||
                      near(bx, by, bx + length * std::cos(angle), by - length * std::sin(angle)));
  };
  std::vector<CrackArrival> table;
  std::vector<char> arrived(x.size(), 0);
  for (long k = 0; k * step <= end * (1 + 1e-12); ++k)
    for (std::size_t i = 0; i < x.size(); ++i)
      if (!arrived[i] && on_crack(i, k * step)) {
        arrived[i] = 1;
        table.push_back({i, k * step});
      }
  post::CrackSettings settings;
  settings.spacing = dx;
  settings.horizon = horizon;
  post::CrackTracker from_snapshots(x, y, z, body, settings), at_snapshot_times(x, y, z, body, settings),
      fine_tracker(x, y, z, body, settings);
  std::vector<double> times;
  for (long k = 0; k * interval <= end * (1 + 1e-12); ++k) {
    // The snapshot's time is the step's, as in a run (the snapshot is written after its step).
    const double t = std::round(k * interval / step) * step;
    std::vector<double> damage(x.size(), 0.0);
    for (std::size_t i = 0; i < x.size(); ++i) damage[i] = on_crack(i, t) ? 0.5 : 0.1;
    from_snapshots.add_frame(t, damage);
    times.push_back(t);
  }
  post::add_table_frames(at_snapshot_times, table, times);
  const post::CrackMetrics coarse = from_snapshots.finish(), same = at_snapshot_times.finish();
  ASSERT_TRUE(coarse.start_time_s && coarse.branch_time_s);
  EXPECT_EQ(same.start_time_s, coarse.start_time_s);
  EXPECT_EQ(same.branch_time_s, coarse.branch_time_s);
  EXPECT_EQ(same.end_time_s, coarse.end_time_s);
  EXPECT_EQ(same.tip_speed_max_m_per_s, coarse.tip_speed_max_m_per_s);
  EXPECT_EQ(same.crack_length_m, coarse.crack_length_m);
  post::add_crack_path_frames(fine_tracker, table, times.front(), times.back(), step);
  const post::CrackMetrics fine = fine_tracker.finish();
  expect_within_one_interval_before(fine.start_time_s, coarse.start_time_s, interval, "start");
  expect_fine_frames_hold_the_snapshot_frames(fine, coarse);
  // On this lattice the two-tip state flickers as the branches separate (two tips at 31.85 us,
  // one at 32.0 us, two from 32.2 us on): the fine branching time is the first of these, where
  // the 0.25 us snapshots see the state from 32.25 us on.
  EXPECT_LT(*fine.branch_time_s, *coarse.branch_time_s);
}

// mppm-postprocess's summary: the table when the run has one, the snapshots without it.
TEST(CrackPathTable, SummarySaysWhichSourceTheMetricsCameFrom) {
  const std::string copy = fresh_directory("notched_bar_without_table");
  fs::copy(damage_run(), copy, fs::copy_options::recursive);
  fs::remove(fs::path(copy) / run_layout::crack_path);
  std::map<std::string, YAML::Node> summaries;
  for (const auto& [name, dir] : std::map<std::string, std::string>{{"table", damage_run()}, {"snapshots", copy}}) {
    post::PostprocessOptions o;
    o.run_directory = dir;
    o.output_directory = fresh_directory("post_" + name);
    o.quiet = true;
    o.plot_load_curve = false;
    post::postprocess_run(o);
    summaries[name] = YAML::LoadFile(o.output_directory + "/summary.json");
  }
  const YAML::Node table = summaries["table"], snapshots = summaries["snapshots"];
  EXPECT_EQ(table["crack_metrics_source"].as<std::string>(), "crack_path table");
  EXPECT_EQ(snapshots["crack_metrics_source"].as<std::string>(), "snapshots");
  EXPECT_DOUBLE_EQ(snapshots["crack_metrics_resolution_s"].as<double>(), kSnapshotInterval);
  const double dt = YAML::LoadFile(damage_run() + "/" + run_layout::run_info)["time_step_s"].as<double>();
  EXPECT_EQ(table["crack_metrics_resolution_s"].as<double>(), dt);
  EXPECT_EQ(snapshots["crack_metrics_frames"].as<std::size_t>(), snapshots_of(damage_run()).size());
  ASSERT_FALSE(snapshots["crack_start_time_s"].IsNull());
  expect_within_one_interval_before(table["crack_start_time_s"].as<double>(),
                                    snapshots["crack_start_time_s"].as<double>(), kSnapshotInterval, "start");
}

}  // namespace
}  // namespace mppm
