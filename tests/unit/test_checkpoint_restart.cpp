// Checkpoint and restart in-process (README "Checkpoints and restart"): a run stopped after a
// checkpoint and continued with restart() ends with the same bytes (every snapshot, load.csv,
// energy.csv) as the run that was never stopped, for an elastic micropolar case, a damage case
// with bonds breaking, a softening viscoplastic case, a saturated bar and a saturated column with
// a drained and a fed boundary, a 3-D damage run with its crack area, on 2 threads after 1; a failed checkpoint
// write leaves the previous checkpoint intact and readable; a corrupted checkpoint, a changed scene,
// changed points or changed tables are refused.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <climits>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "common/checkpoint_file.hpp"
#include "common/input_error.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "solver/checkpoint.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/solve_run.hpp"
#include "tests/verification/solver_fluid_column.hpp"
#include "tests/verification/solver_viscoplastic_cases.hpp"

namespace mppm::solver {
namespace {

namespace fs = std::filesystem;
using testing::add_end_layers;
using testing::kinematic_condition;
using testing::make_lattice;
using testing::make_scene;
using testing::read_csv_rows;
using testing::read_text;

constexpr double kDx = 1e-3;

std::string directory_of(const std::string& name) {
  return (fs::path(MPPM_BINARY_DIR) / "checkpoint-test-runs" / name).string();
}

std::string fresh_directory(const std::string& name) {
  fs::remove_all(directory_of(name));
  return directory_of(name);
}

struct Case {
  Scene scene;
  PointCloud cloud;
};

// The bar of test_solver_run: held on the left, pulled on the right, micropolar, 2-D.
Case elastic_bar() {
  Case c;
  constexpr std::array<int, 3> n{24, 6, 1};
  constexpr double horizon_factor = 3.05;
  c.scene = make_scene(2, true, kDx, horizon_factor);
  c.cloud = make_lattice(2, n, kDx, c.scene.thickness);
  c.cloud.horizon = horizon_factor * kDx;
  add_end_layers(c.cloud, n[0], 4, "displacement", "velocity");
  c.scene.boundary_conditions = {
      kinematic_condition("left", BoundaryType::displacement, {0.0}, {{0.0, 0.0}}),
      kinematic_condition("right", BoundaryType::velocity, {0.0, 20e-6}, {{0.0, 0.0}, {0.5, 0.0}})};
  c.scene.time.end = 40e-6;
  c.scene.output.interval = 10e-6;
  c.scene.output.fields = {"displacement", "velocity", "rotation", "stress", "damage"};
  return c;
}

// The bar torn apart: bonds break from step 13 to the end (351 pairs), so across both restart points.
Case damage_bar() {
  Case c = elastic_bar();
  c.scene.effects.damage = true;
  c.scene.material.damage = DamageParameters{20.0, 0.0, DamageCalibration::lattice, std::nullopt};
  c.scene.boundary_conditions[1] =
      kinematic_condition("right", BoundaryType::velocity, {0.0, 40e-6}, {{0.0, 0.0}, {6.0, 0.0}});
  c.scene.output.fields = {"displacement", "rotation", "damage", "detached"};
  return c;
}

// The bar saturated (docs/theory.md section 12): its pulled end draws fluid toward it, so the pressure
// and the fluid content change at every step (flow updates every step or few).
Case saturated_bar() {
  Case c = elastic_bar();
  c.scene.effects.pore_fluid = true;
  c.scene.material.pore_fluid = testing::water(1e-10, 0.9, 1e5);
  c.scene.output.fields = {"displacement", "pore_pressure", "fluid_content", "darcy_velocity"};
  return c;
}

// The bar unsaturated (docs/theory.md section 12, "Unsaturated (retention)"): under suction, its pulled
// end draws fluid; the stored fluid energy is booked per point (carried by the checkpoint).
Case unsaturated_bar() {
  Case c = saturated_bar();
  c.scene.material.pore_fluid->initial_pressure = -5e3;
  c.scene.material.pore_fluid->retention = RetentionParameters{"van_genuchten", 1e4, 2.0, 0.1};
  c.scene.output.fields = {"displacement", "pore_pressure", "saturation", "darcy_velocity"};
  return c;
}

// A 3-D bar (16 x 6 x 4 dx) with an edge pre-crack through its thickness at mid-length, torn apart,
// writing the crack_area field: its pre-crack cuts are kept aside for the field (solver/crack_area.hpp),
// rebuilt with the model on a restart.
Case damage_bar_3d() {
  Case c;
  constexpr std::array<int, 3> n{16, 6, 4};
  c.scene = make_scene(3, false, kDx, 2.05);
  c.cloud = make_lattice(3, n, kDx);
  c.cloud.horizon = 2.05 * kDx;
  add_end_layers(c.cloud, n[0], 3, "displacement", "velocity");
  const double x = 8 * kDx, y = 2.2 * kDx, z0 = -kDx, z1 = 5 * kDx;
  c.cloud.precrack_vertices = {x, -kDx, z0, x, y, z0, x, y, z1, x, -kDx, z0, x, y, z1, x, -kDx, z1};
  c.scene.boundary_conditions = {
      kinematic_condition("left", BoundaryType::displacement, {0.0}, {{0.0, 0.0, 0.0}}),
      kinematic_condition("right", BoundaryType::velocity, {0.0, 40e-6}, {{0.0, 0.0, 0.0}, {2.0, 0.0, 0.0}})};
  c.scene.effects.damage = true;
  c.scene.material.damage = DamageParameters{20.0, 0.0, DamageCalibration::lattice, std::nullopt};
  c.scene.time.end = 60e-6;
  c.scene.output.interval = 10e-6;
  c.scene.output.fields = {"displacement", "damage", "crack_area"};
  return c;
}

// A saturated column pressed on top and drained there, fed through its bottom row (docs/theory.md
// section 12): fluid leaves through the top layer and enters through the bottom at every step, so
// the volumes through both boundaries and their last rates are carried across the restart.
Case drained_column() {
  Case c;
  c.scene = testing::saturated_scene(kDx, 3.05, 1e-10, 2e9);
  c.scene.material.pore_fluid->initial_pressure = 1e5;
  const double area = 8 * kDx * c.scene.thickness;
  c.cloud = testing::column_cloud(8, 12, 3, kDx, c.scene.thickness, testing::ColumnTags{3, 2, 4});
  c.cloud.horizon = 3.05 * kDx;
  BoundaryCondition load = testing::condition("top", BoundaryType::traction, {0.0, -1e6}, "top", 10e-6);
  load.traction_depth = kDx;
  BoundaryCondition feed = testing::condition("feed", BoundaryType::fluid_flux, {1e-4}, "feed");
  feed.traction_depth = kDx;
  c.scene.boundary_conditions = {testing::condition("base", BoundaryType::velocity, {0.0, 0.0}, "base"), load,
                                 testing::condition("drain", BoundaryType::pore_pressure, {0.0}, "drain"), feed};
  const std::int64_t counts[] = {testing::count_tagged(c.cloud, 1, 0), testing::count_tagged(c.cloud, 0, 2),
                                 testing::count_tagged(c.cloud, 3, 0), testing::count_tagged(c.cloud, 0, 4)};
  const double depths[] = {c.cloud.horizon, kDx, c.cloud.horizon, kDx};
  for (std::size_t k = 0; k < 4; ++k)
    c.cloud.boundaries.push_back(BoundaryInfo{c.scene.boundary_conditions[k].name,
                                              to_string(c.scene.boundary_conditions[k].type), area, counts[k], "",
                                              depths[k]});
  c.scene.time.end = 40e-6;
  c.scene.output.interval = 10e-6;
  c.scene.output.fields = {"displacement", "pore_pressure", "darcy_velocity"};
  return c;
}

// The short, softening plane-strain compression of test_solver_viscoplastic_run.
Case softening_compression() {
  testing::CompressionCase k = testing::compression_case(10, 10, 1e-4, 100.0, 1e3);
  k.scene.output.interval = 2.5e-5;
  k.scene.material.viscoplasticity->hardening = -20e6;
  return {k.scene, k.cloud};
}

// A restart reads the scene back from scene.resolved.yaml, which must be a valid scene file: the
// scenes built in code get a real geometry file and their conditions a physical group by name
// (the solver reads neither: the points carry the boundaries).
Case with_geometry_file(Case c) {
  c.scene.geometry.file = std::string(MPPM_SOURCE_DIR) + "/geometry/branching_plate.geo";
  for (auto& bc : c.scene.boundary_conditions) bc.selector.physical_group = bc.name;
  return c;
}

SolveOptions options_for(const std::string& dir) {
  SolveOptions o;
  o.run_directory = dir;
  o.points_file = "case.vtp";
  return o;
}

// Same snapshot files (names and bytes), load.csv, energy.csv and, with damage, crack_path.csv.
void expect_same_results(const std::string& reference, const std::string& run) {
  EXPECT_EQ(read_text(reference + "/" + run_layout::load), read_text(run + "/" + run_layout::load));
  EXPECT_EQ(read_text(reference + "/" + run_layout::energy), read_text(run + "/" + run_layout::energy));
  EXPECT_EQ(fs::exists(reference + "/" + run_layout::crack_path), fs::exists(run + "/" + run_layout::crack_path));
  EXPECT_EQ(read_text(reference + "/" + run_layout::crack_path), read_text(run + "/" + run_layout::crack_path));
  auto names = [](const std::string& dir) {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir))
      out.insert(e.path().filename().string());
    return out;
  };
  const auto expected = names(reference);
  EXPECT_EQ(expected, names(run));
  EXPECT_GE(expected.size(), 3u);
  for (const auto& name : expected) {
    const std::string sub = std::string("/") + run_layout::snapshot_dir + "/" + name;
    EXPECT_EQ(read_text(reference + sub), read_text(run + sub)) << name;
  }
}

SolveResult restart_run(const Case& c, const std::string& dir, int threads = 2) {
  const ParallelThresholds saved_thresholds = parallel_thresholds();
  parallel_thresholds() = ParallelThresholds{1, 1, 1};  // every loop threaded, even on these lattices
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  SolveResult r;
  try {
    r = restart(c.cloud, read_checkpoint_file(checkpoint_path(dir)), options_for(dir));
  } catch (...) {
    omp_set_num_threads(saved);
    parallel_thresholds() = saved_thresholds;
    throw;
  }
  omp_set_num_threads(saved);
  parallel_thresholds() = saved_thresholds;
  return r;
}

// The uninterrupted run (no checkpoints at all) against: a run stopped by the interruption hook
// near the middle (its checkpoint is the one written on the signal) and continued; and a run that
// completed with checkpoints and is continued from its last one, as after a kill after that
// checkpoint (the rows and snapshots after it are on disk and must be dropped, then written again).
void check_restart_is_bit_for_bit(const Case& c_in, const std::string& name) {
  const Case c = with_geometry_file(c_in);
  omp_set_num_threads(1);
  const std::string reference = fresh_directory(name + "_reference");
  const SolveResult whole = solve(c.scene, c.cloud, options_for(reference));
  ASSERT_GT(whole.steps, 20);

  Case checkpointed = c;
  checkpointed.scene.output.checkpoint_interval = 0.3 * c.scene.time.end;
  const std::string stopped = fresh_directory(name + "_stopped");
  SolveOptions stop = options_for(stopped);
  stop.test_hooks.interrupt_after_step = whole.steps / 2 + 1;
  const SolveResult first = solve(checkpointed.scene, checkpointed.cloud, stop);
  ASSERT_TRUE(first.interrupted);
  EXPECT_EQ(read_checkpoint_file(checkpoint_path(stopped)).header.step, stop.test_hooks.interrupt_after_step);
  const SolveResult rest = restart_run(checkpointed, stopped);
  EXPECT_FALSE(rest.interrupted);
  EXPECT_EQ(rest.steps, whole.steps);
  expect_same_results(reference, stopped);
  EXPECT_NE(read_text(stopped + "/" + run_layout::run_info).find("\"status\": \"completed\""), std::string::npos);

  const std::string completed = fresh_directory(name + "_completed");
  solve(checkpointed.scene, checkpointed.cloud, options_for(completed));
  const std::int64_t last = read_checkpoint_file(checkpoint_path(completed)).header.step;
  EXPECT_GT(last, whole.steps / 2);
  EXPECT_LT(last, whole.steps);
  restart_run(checkpointed, completed);
  expect_same_results(reference, completed);
}

TEST(CheckpointRestart, ElasticMicropolarRunContinuesBitForBit) {
  check_restart_is_bit_for_bit(elastic_bar(), "elastic");
}

TEST(CheckpointRestart, DamageRunContinuesBitForBit) {
  const Case c = damage_bar();
  check_restart_is_bit_for_bit(c, "damage");
  // The comparison is on a run that did break bonds, and put points on the crack path before and
  // after the interruption near the middle (crack_path.csv: point, x, y, z, time).
  const auto energy = read_csv_rows(directory_of("damage_reference") + "/" + run_layout::energy);
  ASSERT_FALSE(energy.empty());
  EXPECT_GT(energy.back()[6], 0.0);  // fracture_dissipation_J
  const auto arrivals = read_csv_rows(directory_of("damage_reference") + "/" + run_layout::crack_path);
  ASSERT_FALSE(arrivals.empty());
  const double end = c.scene.time.end;
  EXPECT_LT(arrivals.front()[4], 0.5 * end);
  EXPECT_GT(arrivals.back()[4], 0.6 * end);
}

TEST(CheckpointRestart, SaturatedRunContinuesBitForBit) {
  check_restart_is_bit_for_bit(saturated_bar(), "saturated");
  // The comparison is on a run whose fluid moved: the flow removed stored energy, and the fluid
  // stayed in the sealed bar (energy.csv: ..., fluid_stored_J, flow_dissipation_J, fluid_mass_balance).
  const auto energy = read_csv_rows(directory_of("saturated_reference") + "/" + run_layout::energy);
  ASSERT_FALSE(energy.empty());
  ASSERT_EQ(energy.back().size(), run_files::energy_columns(true).size());
  EXPECT_GT(energy.back()[10], 0.0);
  EXPECT_LT(std::abs(energy.back()[11]), 1e-12);
}

TEST(CheckpointRestart, UnsaturatedRunContinuesBitForBit) {
  check_restart_is_bit_for_bit(unsaturated_bar(), "unsaturated");
  // The fluid moved and the skeleton did work on it (energy.csv: fluid_stored_J, the work the fluid
  // received since the start, is not zero), and the books balance.
  const auto energy = read_csv_rows(directory_of("unsaturated_reference") + "/" + run_layout::energy);
  ASSERT_FALSE(energy.empty());
  EXPECT_NE(energy.back()[9], 0.0);
  EXPECT_GT(energy.back()[10], 0.0);
  EXPECT_LT(std::abs(energy.back()[11]), 1e-12);
}

TEST(CheckpointRestart, ThreeDimensionalDamageRunWithCrackAreaContinuesBitForBit) {
  check_restart_is_bit_for_bit(damage_bar_3d(), "damage_3d");
  // The comparison is on a crack area that grew before and after the interruption near the middle.
  const std::string dir = directory_of("damage_3d_reference") + "/" + run_layout::snapshot_dir;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<double> totals;
  for (const auto& file : files) {
    const auto& area = read_snapshot(file).find("crack_area")->data;
    totals.push_back(std::accumulate(area.begin(), area.end(), 0.0));
  }
  ASSERT_GE(totals.size(), 4u);
  EXPECT_GT(totals.front(), 0.0);  // the pre-crack
  EXPECT_GT(totals[totals.size() / 2], totals.front());
  EXPECT_GT(totals.back(), totals[totals.size() / 2]);
}

TEST(CheckpointRestart, DrainedRunContinuesBitForBit) {
  check_restart_is_bit_for_bit(drained_column(), "drained");
  // The comparison is on a run whose fluid crossed both boundaries before and after the stop near
  // the middle (load.csv: ..., drain_outflow_m3_per_s, drain_outflow_m3, feed_inflow_m3_per_s,
  // feed_inflow_m3), and whose books balance (energy.csv: fluid_mass_balance).
  const auto load = read_csv_rows(directory_of("drained_reference") + "/" + run_layout::load);
  ASSERT_GT(load.size(), 4u);
  const auto& middle = load[load.size() / 2];
  const auto& last = load.back();
  ASSERT_EQ(last.size(), 1u + 4u + 4u + 2u + 2u);
  EXPECT_NE(middle[9], 0.0);
  EXPECT_NE(last[9], 0.0);
  EXPECT_GT(std::abs(last[10] - middle[10]), 1e-3 * std::abs(last[10]));
  EXPECT_GT(middle[12], 0.0);  // a constant inflow: q A t
  EXPECT_NEAR(last[12], 1e-4 * 8 * kDx * 1e-3 * 40e-6, 1e-9 * last[12]);
  const auto energy = read_csv_rows(directory_of("drained_reference") + "/" + run_layout::energy);
  EXPECT_LT(std::abs(energy.back()[11]), 1e-12);
}

TEST(CheckpointRestart, ViscoplasticRunContinuesBitForBit) {
  check_restart_is_bit_for_bit(softening_compression(), "viscoplastic");
  const auto energy = read_csv_rows(directory_of("viscoplastic_reference") + "/" + run_layout::energy);
  ASSERT_FALSE(energy.empty());
  EXPECT_GT(energy.back()[5], 0.0);  // plastic_dissipation_J
}

// Without output.checkpoint_interval nothing is written (and an interruption writes none either).
TEST(CheckpointRestart, NoCheckpointWithoutTheInterval) {
  const Case c = elastic_bar();
  const std::string dir = fresh_directory("none");
  SolveOptions o = options_for(dir);
  o.test_hooks.interrupt_after_step = 5;
  EXPECT_TRUE(solve(c.scene, c.cloud, o).interrupted);
  EXPECT_FALSE(fs::exists(fs::path(dir) / run_layout::checkpoint_dir));
  try {
    read_checkpoint_file(checkpoint_path(dir));
    FAIL() << "no checkpoint was expected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no checkpoint"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("output.checkpoint_interval"), std::string::npos) << e.what();
  }
}

// The second checkpoint fails halfway (as on a full disk): the run stops with an InputError (exit
// 2) naming the file, the OS error and the intact previous checkpoint; that checkpoint is still
// readable, no temporary is left, and the run continues from it to the uninterrupted result.
TEST(CheckpointRestart, FailedCheckpointWriteKeepsThePreviousOne) {
  Case c = with_geometry_file(elastic_bar());
  omp_set_num_threads(1);
  const std::string reference = fresh_directory("write_failure_reference");
  solve(c.scene, c.cloud, options_for(reference));
  c.scene.output.checkpoint_interval = 0.2 * c.scene.time.end;
  const std::string dir = fresh_directory("write_failure");
  SolveOptions o = options_for(dir);
  o.test_hooks.fail_checkpoint_write = 2;
  try {
    solve(c.scene, c.cloud, o);
    FAIL() << "the run should stop on the failed checkpoint write";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(checkpoint_path(dir)), std::string::npos) << m;
    EXPECT_NE(m.find("No space left on device"), std::string::npos) << m;
    EXPECT_NE(m.find("the previous checkpoint (step"), std::string::npos) << m;
  }
  const CheckpointFile kept = read_checkpoint_file(checkpoint_path(dir));
  EXPECT_GT(kept.header.step, 0);
  EXPECT_LE(kept.header.time, 0.2 * c.scene.time.end * 1.5);
  for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::checkpoint_dir))
    EXPECT_EQ(e.path().filename().string(), "state.ckpt") << "left behind: " << e.path();
  EXPECT_NE(read_text(dir + "/" + run_layout::run_info).find("\"status\": \"write_error\""), std::string::npos);
  restart_run(c, dir);
  expect_same_results(reference, dir);
}

// A run stopped midway with a checkpoint, for the refusals below.
std::string stopped_run(const Case& c, const std::string& name) {
  Case k = with_geometry_file(c);
  k.scene.output.checkpoint_interval = 0.25 * c.scene.time.end;
  const std::string dir = fresh_directory(name);
  SolveOptions o = options_for(dir);
  o.test_hooks.interrupt_after_step = 10;
  EXPECT_TRUE(solve(k.scene, k.cloud, o).interrupted);
  return dir;
}

void expect_refused(const Case& c, const std::string& dir, const std::string& expected) {
  try {
    restart_run(c, dir, 1);
    FAIL() << "restart should be refused with '" << expected << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(CheckpointRestart, CorruptedOrTruncatedCheckpointIsRefused) {
  const Case c = elastic_bar();
  const std::string dir = stopped_run(c, "corrupted");
  const std::string file = checkpoint_path(dir);
  std::string bytes = read_text(file);
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x40;
  std::ofstream(file, std::ios::binary | std::ios::trunc) << flipped;
  expect_refused(c, dir, "corrupted checkpoint (checksum mismatch)");
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 3);
  expect_refused(c, dir, "truncated checkpoint");
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_NO_THROW(restart_run(c, dir, 1));
}

TEST(CheckpointRestart, ChangedSceneIsRefused) {
  const Case c = elastic_bar();
  const std::string dir = stopped_run(c, "changed_scene");
  const std::string scene = dir + "/" + run_layout::resolved_scene;
  std::string text = read_text(scene);
  const auto at = text.find("interval: ");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 10, "2");  // another snapshot interval
  std::ofstream(scene, std::ios::binary | std::ios::trunc) << text;
  expect_refused(c, dir, "changed since the checkpoint");
}

TEST(CheckpointRestart, ChangedPointsAreRefused) {
  const Case c = elastic_bar();
  const std::string dir = stopped_run(c, "changed_points");
  Case other = c;
  other.cloud.volume[3] *= 1.01;
  expect_refused(other, dir, "not the points the run");
}

TEST(CheckpointRestart, TablesWithoutTheCheckpointRowsAreRefused) {
  const Case c = elastic_bar();
  const std::string dir = stopped_run(c, "changed_table");
  const std::string load = dir + "/" + run_layout::load;
  const std::string text = read_text(load);
  std::ofstream(load, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() / 2);
  expect_refused(c, dir, "does not hold the rows the run had written at its checkpoint");
}

// What a checkpoint holds follows the effects: the damage arrays only with damage, the plastic ones
// only with viscoplasticity, and the elastic case stores only what the integrator carries.
TEST(CheckpointRestart, CheckpointHoldsTheStateOfTheEffectsOnly) {
  const CheckpointFile elastic = read_checkpoint_file(checkpoint_path(stopped_run(elastic_bar(), "contents_elastic")));
  for (const char* name : {"displacement", "velocity", "rotation", "rotation_rate", "force", "moment", "body_force",
                           "energy", "schedule", "energy_guard", "tables", "points_file"})
    EXPECT_TRUE(elastic.has(name)) << name;
  for (const char* name : {"bond_neighbor", "bond_work", "plastic_strain", "strain", "shape_inverse"})
    EXPECT_FALSE(elastic.has(name)) << name;
  EXPECT_EQ(elastic.header.effects, checkpoint_effect_bits(elastic_bar().scene.effects));
  EXPECT_EQ(elastic.header.step, 10);
  const CheckpointFile damage = read_checkpoint_file(checkpoint_path(stopped_run(damage_bar(), "contents_damage")));
  for (const char* name : {"bond_neighbor", "bond_work", "shape_inverse", "detached", "previous_displacement",
                           "force_tensor_by_columns", "moment_tensor_by_columns"})
    EXPECT_TRUE(damage.has(name)) << name;
  // The tensors were stored by rows under these names once: such a file must not be read as columns.
  for (const char* name : {"force_tensor", "moment_tensor"}) EXPECT_FALSE(damage.has(name)) << name;
  const CheckpointFile plastic =
      read_checkpoint_file(checkpoint_path(stopped_run(softening_compression(), "contents_plastic")));
  for (const char* name : {"plastic_strain", "plastic_wryness", "equivalent_plastic_strain", "strain"})
    EXPECT_TRUE(plastic.has(name)) << name;
}

// The container writes an array given by rows (a distributed run's, gathered a chunk at a time) in
// its element type: integer values come as doubles and are stored as the integers they are, over
// more rows than one chunk (4096), negative ones (a broken bond's mark) and 0/1 flags included.
TEST(CheckpointFileRows, IntegerArraysGivenByRowsAreStoredInTheirType) {
  const std::uint64_t rows = 10000;
  auto value = [](std::uint64_t k) { return static_cast<std::int32_t>(k * 7919 % 100003) - 50000; };
  CheckpointArrayView marks;
  marks.name = "marks";
  marks.element = CheckpointElement::i32;
  marks.count = rows;
  marks.rows = [&](std::uint64_t first, std::uint64_t n, double* out) {
    for (std::uint64_t k = 0; k < n; ++k) out[k] = value(first + k) | ((first + k) % 3 == 0 ? INT32_MIN : 0);
  };
  CheckpointArrayView flags;
  flags.name = "flags";
  flags.element = CheckpointElement::u8;
  flags.components = 2;
  flags.count = 2 * rows;
  flags.rows = [](std::uint64_t first, std::uint64_t n, double* out) {
    for (std::uint64_t k = 0; k < 2 * n; ++k) out[k] = static_cast<double>((2 * first + k) % 2);
  };
  const std::string dir = fresh_directory("container_rows");
  fs::create_directories(dir);
  const std::string path = dir + "/rows.ckpt";
  write_checkpoint_file(path, CheckpointHeader{}, {marks, flags});
  const CheckpointFile file = read_checkpoint_file(path);
  const std::vector<std::int32_t> read_marks = file.array<std::int32_t>("marks");
  const std::vector<std::uint8_t> read_flags = file.array<std::uint8_t>("flags");
  ASSERT_EQ(read_marks.size(), rows);
  ASSERT_EQ(read_flags.size(), 2 * rows);
  std::size_t wrong = 0;
  for (std::uint64_t k = 0; k < rows; ++k) {
    wrong += read_marks[k] != (value(k) | (k % 3 == 0 ? INT32_MIN : 0));
    wrong += read_flags[2 * k] != 0 || read_flags[2 * k + 1] != 1;
  }
  EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace mppm::solver
