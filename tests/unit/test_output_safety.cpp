// Output safety of the stages as the user runs them:
//  - a run or post directory is never overwritten silently: without --force an existing
//    non-empty one is refused (exit 2, message naming it and --force) and left untouched; with
//    --force it is replaced as a whole, so no snapshot or frame of the older output survives;
//    --force never deletes a directory that is not an earlier output of the stage;
//  - a write failure (RLIMIT_FSIZE: write(2) fails with EFBIG, as on a full disk, also for
//    root) stops the stage with exit code 2 or 3 and a message naming the file, leaves the
//    previous complete file intact and no temporary behind.
// The case is the quickstart plate at a coarse 2 mm spacing (~1000 points, a few seconds).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/point_cloud.hpp"
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

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "test_scratch" / "output_safety" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// Every file below `dir` whose name marks an unfinished atomic write (".NAME.tmp-PID").
std::vector<std::string> temporaries(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(entry.path().string());
  return found;
}

std::vector<std::string> quickstart_overrides() {
  return {"--set", "geometry.spacing=2 mm", "--set", "time.end=6 us", "--set", "output.interval=2 us"};
}

StageOutcome preprocess(const std::string& points, std::optional<rlim_t> limit = std::nullopt) {
  std::vector<std::string> args{binary("mppm-preprocess"), kScene, "-o", points, "--quiet"};
  for (const auto& o : quickstart_overrides()) args.push_back(o);
  return run_stage_process(args, limit);
}

StageOutcome solve(const std::string& points, const std::string& run, std::vector<std::string> extra = {},
                   std::optional<rlim_t> limit = std::nullopt) {
  std::vector<std::string> args{binary("mppm-solve"), kScene, "--points", points, "-o", run, "--quiet",
                                "--threads",          "1"};
  for (const auto& o : quickstart_overrides()) args.push_back(o);
  for (const auto& e : extra) args.push_back(e);
  return run_stage_process(args, limit);
}

StageOutcome postprocess(const std::string& run, const std::string& post, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{binary("mppm-postprocess"), run, "-o", post, "--quiet", "--no-plot"};
  for (const auto& e : extra) args.push_back(e);
  return run_stage_process(args);
}

// The points file of the case, made once per process (CTest runs each test in a process of
// its own, in parallel: the folder is the process's).
const std::string& case_points() {
  static const std::string points = [] {
    const std::string dir = scratch("case_" + std::to_string(::getpid()));
    const std::string path = dir + "/points.vtp";
    const StageOutcome r = preprocess(path);
    if (r.code != 0) throw std::runtime_error("mppm-preprocess failed: " + r.err);
    return path;
  }();
  return points;
}

std::vector<std::string> snapshot_files(const std::string& run) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(run) / run_layout::snapshot_dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(OutputSafety, SolveRefusesAnExistingRunDirectoryAndForceReplacesItWhole) {
  const std::string dir = scratch("solve_force");
  const std::string run = dir + "/run";
  ASSERT_EQ(solve(case_points(), run).code, 0);
  const std::vector<std::string> first_snapshots = snapshot_files(run);
  ASSERT_GE(first_snapshots.size(), 2u);
  // What an older, longer run would have left: a later snapshot and a file of its own.
  const std::string stale_snapshot = run + "/snapshots/snapshot_999999.snap";
  fs::copy_file(run + "/snapshots/" + first_snapshots.back(), stale_snapshot);
  write_text(run + "/notes_of_the_old_run.txt", "old\n");
  const std::string info_before = contents(run + "/" + run_layout::run_info);

  const StageOutcome refused = solve(case_points(), run);
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find(run), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_TRUE(fs::exists(stale_snapshot)) << "the refusal touched the run directory";
  EXPECT_EQ(contents(run + "/" + run_layout::run_info), info_before);

  const StageOutcome forced = solve(case_points(), run, {"--force"});
  ASSERT_EQ(forced.code, 0) << forced.err;
  EXPECT_FALSE(fs::exists(stale_snapshot)) << "a snapshot of the older run survived --force";
  EXPECT_FALSE(fs::exists(run + "/notes_of_the_old_run.txt"));
  EXPECT_EQ(snapshot_files(run), first_snapshots);
  for (const auto& name : first_snapshots) EXPECT_NO_THROW(read_snapshot(run + "/snapshots/" + name)) << name;
  EXPECT_TRUE(temporaries(dir).empty());
}

TEST(OutputSafety, ForceNeverDeletesADirectoryThatIsNoRunDirectory) {
  const std::string dir = scratch("solve_foreign");
  const std::string foreign = dir + "/thesis";
  write_text(foreign + "/chapter1.tex", "precious\n");
  const StageOutcome r = solve(case_points(), foreign, {"--force"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(foreign), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("does not look like a run directory"), std::string::npos) << r.err;
  EXPECT_EQ(contents(foreign + "/chapter1.tex"), "precious\n");
}

TEST(OutputSafety, PostprocessRefusesAnExistingPostDirectoryAndForceReplacesItWhole) {
  const std::string dir = scratch("post_force");
  const std::string run = dir + "/run", post = dir + "/post";
  ASSERT_EQ(solve(case_points(), run).code, 0);
  const StageOutcome first = postprocess(run, post);
  ASSERT_EQ(first.code, 0) << first.err;
  const std::string stale_frame = post + "/results/frame_of_an_older_run.vtu";
  write_text(stale_frame, "<VTKFile/>\n");
  const std::string summary_before = contents(post + "/summary.json");

  const StageOutcome refused = postprocess(run, post);
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find(post), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_TRUE(fs::exists(stale_frame));
  EXPECT_EQ(contents(post + "/summary.json"), summary_before);

  const StageOutcome forced = postprocess(run, post, {"--force"});
  ASSERT_EQ(forced.code, 0) << forced.err;
  EXPECT_FALSE(fs::exists(stale_frame)) << "a frame of the older output survived --force";
  EXPECT_TRUE(fs::exists(post + "/results.pvd"));
  EXPECT_TRUE(fs::exists(post + "/summary.json"));

  // The run directory itself (or a folder holding it) is never a post directory to replace.
  const StageOutcome onto_run = postprocess(run, run, {"--force"});
  EXPECT_EQ(onto_run.code, 2) << onto_run.err;
  const StageOutcome onto_parent = postprocess(run, dir, {"--force"});
  EXPECT_EQ(onto_parent.code, 2) << onto_parent.err;
  EXPECT_TRUE(fs::exists(run + "/" + run_layout::run_info));
}

TEST(OutputSafety, PreprocessWriteFailureKeepsThePreviousPointsFile) {
  const std::string dir = scratch("preprocess_efbig");
  const std::string points = dir + "/points.vtp";
  ASSERT_EQ(preprocess(points).code, 0);
  const std::string previous = contents(points);
  ASSERT_GT(previous.size(), 8192u);
  // 4 KiB: the new points file (same size as the old one) cannot be written.
  const StageOutcome r = preprocess(points, 4096);
  EXPECT_TRUE(r.code == 2 || r.code == 3) << "exit code " << r.code << ": " << r.err;
  EXPECT_NE(r.err.find(points), std::string::npos) << r.err;
  EXPECT_EQ(contents(points), previous) << "the previous points file was damaged";
  EXPECT_NO_THROW(read_point_cloud(points));
  EXPECT_TRUE(temporaries(dir).empty());
}

TEST(OutputSafety, SolveWriteFailureMidRunKeepsTheLastCompleteFiles) {
  const std::string dir = scratch("solve_efbig");
  // ~950 steps with a row each, so that load.csv (~120 KB) outgrows every other file (the
  // reference snapshot, ~48 KB, is the largest of those); one small snapshot field.
  const std::vector<std::string> extra{
      "--set", "time.end=1 ms",           "--set", "output.interval=200 us", "--set", "output.load_interval=0 s",
      "--set", "output.fields=[rotation]"};
  const std::string complete = dir + "/complete";
  ASSERT_EQ(solve(case_points(), complete, extra).code, 0);
  std::uintmax_t largest_other = 0;
  for (const auto& entry : fs::recursive_directory_iterator(complete))
    if (entry.is_regular_file() && entry.path().filename() != run_layout::load &&
        entry.path().filename() != run_layout::energy && entry.path().filename() != run_layout::log)
      largest_other = std::max(largest_other, entry.file_size());
  const std::uintmax_t final_load = fs::file_size(fs::path(complete) / run_layout::load);
  ASSERT_GT(final_load, largest_other + 1024) << "the set-up does not make load.csv the file that outgrows the limit";

  // Half-way between: the early files fit, the tables stop fitting during the run.
  const auto limit = static_cast<rlim_t>((largest_other + final_load) / 2);
  const std::string run = dir + "/run";
  const StageOutcome r = solve(case_points(), run, extra, limit);
  EXPECT_TRUE(r.code == 2 || r.code == 3) << "exit code " << r.code << ": " << r.err;
  EXPECT_NE(r.err.find(run), std::string::npos) << r.err;
  EXPECT_TRUE(r.err.find("File too large") != std::string::npos) << r.err;  // strerror(EFBIG)
  EXPECT_TRUE(temporaries(run).empty());

  // What is there is complete: run_info.json of the last good flush lists snapshots that all
  // read back, and load.csv is a prefix of the complete run's table ending at a full row.
  const std::string info = contents(run + "/" + run_layout::run_info);
  ASSERT_FALSE(info.empty());
  EXPECT_EQ(info.back(), '\n');
  EXPECT_NE(info.find("\"snapshots\""), std::string::npos) << info;
  std::size_t listed = 0;
  for (std::size_t at = info.find("\"file\": \""); at != std::string::npos; at = info.find("\"file\": \"", at + 1)) {
    const std::size_t begin = at + 9, end = info.find('"', begin);
    EXPECT_NO_THROW(read_snapshot(run + "/" + info.substr(begin, end - begin)));
    ++listed;
  }
  EXPECT_GE(listed, 1u);
  const std::string load = contents(run + "/" + run_layout::load);
  const std::string complete_load = contents(complete + "/" + run_layout::load);
  ASSERT_FALSE(load.empty());
  EXPECT_LT(load.size(), complete_load.size());
  EXPECT_EQ(complete_load.compare(0, load.size(), load), 0) << "load.csv is not a prefix of the complete run's";
  EXPECT_EQ(load.back(), '\n');
}

}  // namespace
}  // namespace mppm
