// Checkpoint and restart through the real executables, as a user meets them: mppm-solve killed
// with SIGKILL at a random moment after its first checkpoint (or stopped with SIGTERM), then
// `mppm-solve --restart RUN_DIR`, ends with the bytes of the uninterrupted run (snapshots,
// load.csv, energy.csv); a checkpoint write failure is exit 2 with a message; a corrupted
// checkpoint, a changed scene or a run without checkpoints is exit 2 with a message.
// The case is the quickstart plate at 2 mm (1000 points), 1910 steps (about 1-2 s).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "tests/unit/stage_process.hpp"

namespace mppm {
namespace {

namespace fs = std::filesystem;
using testing::binary;
using testing::run_stage_process;
using testing::StageOutcome;

const std::string kScene = std::string(MPPM_SOURCE_DIR) + "/workflows/quickstart/scene.yaml";

// One directory per test process: CTest runs the tests of this suite as parallel processes.
std::string scratch_root() {
  return (fs::path(MPPM_BINARY_DIR) / "test_scratch" / ("restart_process_" + std::to_string(::getpid()))).string();
}

std::string fresh(const std::string& name) {
  const fs::path dir = fs::path(scratch_root()) / name;
  fs::remove_all(dir);
  return dir.string();
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> overrides(bool checkpoints) {
  std::vector<std::string> o{"--set", "geometry.spacing=2 mm", "--set", "time.end=2 ms",
                             "--set", "output.interval=0.2 ms"};
  if (checkpoints) {
    o.push_back("--set");
    o.push_back("output.checkpoint_interval=0.15 ms");
  }
  return o;
}

std::vector<std::string> solve_args(const std::string& run, bool checkpoints, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{
      binary("mppm-solve"), kScene, "--points", scratch_root() + "/points.vtp", "-o", run, "--quiet", "--threads", "1"};
  for (const auto& o : overrides(checkpoints)) args.push_back(o);
  for (const auto& e : extra) args.push_back(e);
  return args;
}

StageOutcome restart(const std::string& run, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{binary("mppm-solve"), "--restart", run, "--quiet", "--threads", "2"};
  for (const auto& e : extra) args.push_back(e);
  return run_stage_process(args);
}

// Starts a stage without waiting for it (stdout and stderr to /dev/null).
pid_t spawn(const std::vector<std::string>& args) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

class RestartProcess : public ::testing::Test {
 protected:
  // The points and the uninterrupted run (no checkpoints), once for the suite.
  static void SetUpTestSuite() {
    fs::remove_all(scratch_root());
    fs::create_directories(scratch_root());
    std::vector<std::string> pre{binary("mppm-preprocess"), kScene, "-o", scratch_root() + "/points.vtp", "--quiet"};
    for (const auto& o : overrides(false)) pre.push_back(o);
    ASSERT_EQ(run_stage_process(pre).code, 0);
    ASSERT_EQ(run_stage_process(solve_args(reference(), false)).code, 0);
  }
  static void TearDownTestSuite() {
    const auto* suite = ::testing::UnitTest::GetInstance()->current_test_suite();
    if (suite && suite->Passed()) fs::remove_all(scratch_root());  // kept for a look when a test failed
  }
  static std::string reference() { return scratch_root() + "/reference"; }

  static void expect_same_results(const std::string& run) {
    EXPECT_EQ(contents(reference() + "/" + run_layout::load), contents(run + "/" + run_layout::load));
    EXPECT_EQ(contents(reference() + "/" + run_layout::energy), contents(run + "/" + run_layout::energy));
    auto names = [](const std::string& dir) {
      std::set<std::string> out;
      for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir))
        out.insert(e.path().filename().string());
      return out;
    };
    const auto expected = names(reference());
    ASSERT_EQ(expected, names(run));
    for (const auto& name : expected) {
      const std::string sub = std::string("/") + run_layout::snapshot_dir + "/" + name;
      EXPECT_EQ(contents(reference() + sub), contents(run + sub)) << name;
    }
  }

  // Starts a run with checkpoints, waits for its first checkpoint, then waits `delay` and sends
  // `signal`. Returns the exit code (0 if the run was done before the signal).
  static int stop_after_first_checkpoint(const std::string& run, int signal, std::chrono::milliseconds delay) {
    const pid_t pid = spawn(solve_args(run, true));
    const fs::path checkpoint = fs::path(run) / run_layout::checkpoint;
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(checkpoint) && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    std::this_thread::sleep_for(delay);
    ::kill(pid, signal);
    return wait_for(pid);
  }
};

// SIGKILL at a random moment after the first checkpoint exists (the seed is printed to reproduce a
// failure): the run may die while it steps, while it writes a snapshot, the tables or a checkpoint.
TEST_F(RestartProcess, KilledRunContinuesBitForBit) {
  const unsigned seed = std::random_device{}();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> delay_ms(0, 700);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int delay = delay_ms(rng);
    std::cout << "seed " << seed << ": SIGKILL " << delay << " ms after the first checkpoint\n";
    const std::string run = fresh("killed_" + std::to_string(attempt));
    const int code = stop_after_first_checkpoint(run, SIGKILL, std::chrono::milliseconds(delay));
    EXPECT_TRUE(code == 128 + SIGKILL || code == 0) << code;
    const StageOutcome continued = restart(run);
    ASSERT_EQ(continued.code, 0) << continued.err;
    expect_same_results(run);
    // No temporary of the killed run is left behind.
    for (const auto& e : fs::recursive_directory_iterator(run))
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  }
}

// SIGTERM: the run stops cleanly (exit 1, status interrupted) with a checkpoint of its last step;
// the interruption's extra snapshot is removed by the restart.
TEST_F(RestartProcess, TerminatedRunContinuesBitForBit) {
  const std::string run = fresh("terminated");
  const int code = stop_after_first_checkpoint(run, SIGTERM, std::chrono::milliseconds(100));
  if (code == 0) GTEST_SKIP() << "the run ended before SIGTERM arrived (machine too fast for this case)";
  EXPECT_EQ(code, 1);
  EXPECT_NE(contents(run + "/" + run_layout::run_info).find("\"status\": \"interrupted\""), std::string::npos);
  const StageOutcome continued = restart(run);
  ASSERT_EQ(continued.code, 0) << continued.err;
  expect_same_results(run);
}

TEST_F(RestartProcess, CheckpointWriteFailureIsExitTwoWithTheFileAndThePreviousCheckpoint) {
  const std::string run = fresh("write_failure");
  const StageOutcome failed = run_stage_process(solve_args(run, true, {"--fail-checkpoint-write", "3"}));
  EXPECT_EQ(failed.code, 2) << failed.err;
  EXPECT_NE(failed.err.find("checkpoint/state.ckpt: writing failed (No space left on device"), std::string::npos)
      << failed.err;
  EXPECT_NE(failed.err.find("the previous checkpoint (step"), std::string::npos) << failed.err;
  const StageOutcome continued = restart(run);
  ASSERT_EQ(continued.code, 0) << continued.err;
  expect_same_results(run);
}

TEST_F(RestartProcess, BadRestartsAreExitTwoWithAMessage) {
  // No checkpoint: the reference run had none.
  const std::string plain = fresh("no_checkpoint");
  fs::copy(reference(), plain, fs::copy_options::recursive);
  StageOutcome r = restart(plain);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no checkpoint"), std::string::npos) << r.err;

  const std::string run = fresh("refusals");
  ASSERT_EQ(run_stage_process(solve_args(run, true, {"--set", "time.end=0.5 ms"})).code, 0);
  const std::string checkpoint = run + "/" + run_layout::checkpoint;
  const std::string good = contents(checkpoint);
  std::string bad = good;
  bad[bad.size() / 2] ^= 0x01;
  std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << bad;
  r = restart(run);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("corrupted checkpoint (checksum mismatch)"), std::string::npos) << r.err;
  std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << good;

  const std::string scene = run + "/" + run_layout::resolved_scene;
  const std::string original = contents(scene);
  std::ofstream(scene, std::ios::binary | std::ios::app) << "# edited\n";
  r = restart(run);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("changed since the checkpoint"), std::string::npos) << r.err;
  std::ofstream(scene, std::ios::binary | std::ios::trunc) << original;

  // Other points than the run's.
  std::vector<std::string> pre{binary("mppm-preprocess"), kScene, "-o", run + "_other.vtp", "--quiet", "--set",
                               "geometry.spacing=2.5 mm"};
  ASSERT_EQ(run_stage_process(pre).code, 0);
  r = restart(run, {"--points", run + "_other.vtp"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("not the points the run"), std::string::npos) << r.err;

  // A scene or -o with --restart.
  r = run_stage_process({binary("mppm-solve"), "--restart", run, "-o", run + "_x"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--restart"), std::string::npos) << r.err;
  // The test hooks a restart cannot take.
  for (const std::vector<std::string>& hook :
       {std::vector<std::string>{"--inject-nan", "3:1"}, std::vector<std::string>{"--inject-kick", "3:1:0:5"}}) {
    r = run_stage_process({binary("mppm-solve"), "--restart", run, hook[0], hook[1]});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find(hook[0] + " cannot be combined with --restart"), std::string::npos) << r.err;
  }
  // What is left is still a good checkpoint: the run continues.
  r = restart(run);
  EXPECT_EQ(r.code, 0) << r.err;
}

}  // namespace
}  // namespace mppm
