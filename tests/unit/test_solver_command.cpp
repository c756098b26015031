// mppm-solve as the user runs it (docs/stages.md "Commands"): scene file + points file -> run
// directory, exit codes 0 / 2, the time-step refusal of the misprinted case-1 couple modulus
// named on stderr, refusal to overwrite a run, --set overrides.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

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
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "solver-test-runs" / "command";
  fs::create_directories(dir);
  return dir.string();
}

std::string block_points() { return testing::write_block_points(work_directory()); }

struct Outcome {
  int code;
  std::string err;
};

Outcome run(std::vector<std::string> args) {
  args.insert(args.begin(), "mppm-solve");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::stringstream captured;
  auto* old = std::cerr.rdbuf(captured.rdbuf());
  const int code = solve_command(static_cast<int>(args.size()), argv.data());
  std::cerr.rdbuf(old);
  return {code, captured.str()};
}

TEST(SolverCommand, CaseOneMaterialRunsAndTheMisprintIsRefused) {
  const std::string points = block_points();
  const std::string dir = work_directory() + "/case1";
  fs::remove_all(dir);
  const Outcome ok = run({kScenes + "solver_case1_block.yaml", "--points", points, "-o", dir, "--quiet"});
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(fs::path(dir) / run_layout::run_info));
  EXPECT_TRUE(fs::exists(fs::path(dir) / run_layout::snapshot_dir / run_layout::snapshot_name(10)));

  // Same run directory again: refused (exit 2) unless --force.
  const Outcome again = run({kScenes + "solver_case1_block.yaml", "--points", points, "-o", dir, "--quiet"});
  EXPECT_EQ(again.code, 2);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  EXPECT_EQ(run({kScenes + "solver_case1_block.yaml", "--points", points, "-o", dir, "--quiet", "--force"}).code, 0);

  // The printed a3 = 83.3 kN with dt = 7 us: refused, naming mode, value and parameter.
  const std::string bad_dir = work_directory() + "/misprint";
  fs::remove_all(bad_dir);
  const Outcome bad = run({kScenes + "solver_case1_misprint.yaml", "--points", points, "-o", bad_dir, "--quiet"});
  EXPECT_EQ(bad.code, 2);
  for (const char* word :
       {"solver_case1_misprint.yaml", "time.step", "rotational", "critical step", "couple_moduli", "a3"})
    EXPECT_NE(bad.err.find(word), std::string::npos) << word << " missing in: " << bad.err;
  EXPECT_FALSE(fs::exists(fs::path(bad_dir) / run_layout::run_info)) << "nothing is written for refused input";

  // ... and accepted with the step left to the solver.
  const Outcome automatic = run({kScenes + "solver_case1_misprint.yaml", "--points", points, "-o", bad_dir, "--quiet",
                                 "--set", "time.step=auto", "--set", "time.end=2us"});
  EXPECT_EQ(automatic.code, 0) << automatic.err;
}

TEST(SolverCommand, MissingOptionsAndBadPointsAreBadInput) {
  const std::string dir = work_directory() + "/bad";
  EXPECT_EQ(run({kScenes + "solver_case1_block.yaml", "-o", dir}).code, 2);
  const Outcome missing = run({kScenes + "solver_case1_block.yaml", "--points", dir + "/nope.vtp", "-o", dir});
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("nope.vtp"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace mppm::solver
