// The start-up of mppm-solve phase by phase (docs/stages.md "run_info.json"): run_info.json's
// start_up_seconds (the phases in their order) and start_up_total_seconds, the "start-up:" line of
// log.txt, for a new run and for a restart (mppm-solve --restart). No absolute time is asserted:
// the phases are non-negative, add up to the total, and the total is the part of the wall time
// before the time loop.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "solver/solve_command.hpp"
#include "tests/unit/solver_block_points.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(MPPM_SOURCE_DIR) + "/tests/data/scenes/";

std::string work_directory() {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "solver-test-runs" / "start-up";
  fs::create_directories(dir);
  return dir.string();
}

std::string block_points() { return testing::write_block_points(work_directory()); }

int run(std::vector<std::string> args) {
  args.insert(args.begin(), "mppm-solve");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return solve_command(static_cast<int>(args.size()), argv.data());
}

std::string contents(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The number after "KEY": in run_info.json.
double number(const std::string& json, const std::string& key) {
  const std::string tag = "\"" + key + "\": ";
  const auto at = json.find(tag);
  if (at == std::string::npos) ADD_FAILURE() << key << " missing in run_info.json";
  return at == std::string::npos ? -1.0 : std::strtod(json.c_str() + at + tag.size(), nullptr);
}

// The entries of the object "start_up_seconds": {"name": seconds, ...}, in their order.
std::vector<std::pair<std::string, double>> start_up_phases(const std::string& json) {
  std::vector<std::pair<std::string, double>> phases;
  const std::string tag = "\"start_up_seconds\": {";
  const auto begin = json.find(tag);
  if (begin == std::string::npos) {
    ADD_FAILURE() << "start_up_seconds missing in run_info.json";
    return phases;
  }
  std::string object = json.substr(begin + tag.size(), json.find('}', begin) - begin - tag.size());
  std::istringstream entries(object);
  std::string entry;
  while (std::getline(entries, entry, ',')) {
    const auto open = entry.find('"'), close = entry.find('"', open + 1);
    phases.emplace_back(entry.substr(open + 1, close - open - 1), std::strtod(entry.c_str() + close + 2, nullptr));
  }
  return phases;
}

std::vector<std::string> names(const std::vector<std::pair<std::string, double>>& phases) {
  std::vector<std::string> n;
  for (const auto& p : phases) n.push_back(p.first);
  return n;
}

// Every phase >= 0, their sum the total, the total the wall time before the time loop. The total
// is written as the sum of the phases in this order, so the sum here is the same double (the
// numbers are written in the shortest form that reads back exactly); 1e-12 s only absorbs a
// different summation. wall_seconds - loop_wall_seconds is the same span (the run's start to the
// start of the loop, both read from one clock at one instant), only rounded differently: each
// duration is a whole number of nanoseconds converted to double, so the two differ by far less
// than the 1 ns slack.
void check_start_up(const std::string& run_info) {
  const auto phases = start_up_phases(run_info);
  double sum = 0.0;
  for (const auto& [name, seconds] : phases) {
    EXPECT_GE(seconds, 0.0) << name;
    sum += seconds;
  }
  const double total = number(run_info, "start_up_total_seconds");
  EXPECT_NEAR(sum, total, 1e-12);
  const double outside_loop = number(run_info, "wall_seconds") - number(run_info, "loop_wall_seconds");
  EXPECT_LE(total, outside_loop + 1e-9);
  EXPECT_GE(total, outside_loop - 1e-9) << "the start-up is all of the wall time before the loop";
}

// The last line of log.txt that starts with "start-up: ".
std::string last_start_up_line(const std::string& log) {
  std::istringstream lines(log);
  std::string line, found;
  while (std::getline(lines, line))
    if (line.rfind("start-up: ", 0) == 0) found = line;
  return found;
}

TEST(SolverStartUp, NewRunAndRestartReportTheirPhasesInOrder) {
  const std::string points = block_points();
  const std::string dir = work_directory() + "/run";
  fs::remove_all(dir);
  ASSERT_EQ(run({kScenes + "solver_case1_block.yaml", "--points", points, "-o", dir, "--quiet", "--set",
                 "output.checkpoint_interval=35us"}),
            0);
  const std::string info = contents(dir + "/" + run_layout::run_info);
  const std::vector<std::string> new_run{
      "read_scene",         "read_points",     "memory_estimate",   "boundary_conditions", "point_data",
      "bond_families",      "pre_crack_cuts",  "damage_set_up",     "shape_tensors",       "stiffest_points",
      "critical_time_step", "mode_naming",     "damage_step_limit", "run_directory",       "reference_snapshot",
      "initial_forces",     "initial_snapshot"};
  EXPECT_EQ(names(start_up_phases(info)), new_run);
  check_start_up(info);
  const std::string line = last_start_up_line(contents(dir + "/" + run_layout::log));
  EXPECT_EQ(line.rfind("start-up: read scene ", 0), 0u) << line;
  EXPECT_NE(line.find(", critical time step "), std::string::npos) << line;
  EXPECT_NE(line.find(" s (total "), std::string::npos) << line;
  // Where the step was estimated, in run_info.json and in the log's critical-step line, which says
  // why when it is the whole model (this block is too small for the patches).
  const bool on_patch = info.find("\"critical_step_estimate\": \"patch\"") != std::string::npos;
  EXPECT_TRUE(on_patch || info.find("\"critical_step_estimate\": \"whole_model\"") != std::string::npos) << info;
  const std::string log = contents(dir + "/" + run_layout::log);
  EXPECT_NE(log.find(on_patch ? "estimated on the patch of " : " Lanczos iterations on the whole model (the patch "),
            std::string::npos)
      << log;

  // Continued from the checkpoint at 35 us: the checkpoint is read first, no reference is written,
  // the state is restored instead of the first snapshot.
  ASSERT_EQ(run({"--restart", dir, "--quiet"}), 0);
  const std::string restarted = contents(dir + "/" + run_layout::run_info);
  const std::vector<std::string> restart{
      "read_checkpoint",     "read_points",     "checkpoint_identity", "read_scene",     "memory_estimate",
      "boundary_conditions", "point_data",      "bond_families",       "pre_crack_cuts", "damage_set_up",
      "shape_tensors",       "stiffest_points", "critical_time_step",  "mode_naming",    "damage_step_limit",
      "run_directory",       "initial_forces",  "restore_state"};
  EXPECT_EQ(names(start_up_phases(restarted)), restart);
  check_start_up(restarted);
  const std::string restart_line = last_start_up_line(contents(dir + "/" + run_layout::log));
  EXPECT_EQ(restart_line.rfind("start-up: read checkpoint ", 0), 0u) << restart_line;
}

}  // namespace
}  // namespace mppm::solver
