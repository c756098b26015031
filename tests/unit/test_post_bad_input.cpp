// Bad input to mppm-postprocess: exit code 2 with a message naming the file and the problem,
// no crash, and nothing half-written (a series stopped by a bad snapshot stays readable).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_post_command.hpp"
#include "test_post_run_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mppm::post::testing;

void expect_no_temporaries(const std::string& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
}

TEST(PostBadInput, MissingDirectory) {
  const std::string dir = scratch_directory("missing_dir");
  const auto r = run_command({postprocess_executable(), dir + "/nowhere", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(dir + "/nowhere"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no such run directory"), std::string::npos) << r.output;
}

TEST(PostBadInput, EmptyDirectory) {
  const std::string dir = scratch_directory("empty_dir");
  fs::create_directories(dir + "/run");
  const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("empty"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/post")) << "nothing is written for a bad run directory";
}

TEST(PostBadInput, NotARunDirectory) {
  const std::string dir = scratch_directory("not_a_run");
  fs::create_directories(dir + "/run");
  std::ofstream(dir + "/run/notes.txt") << "hello\n";
  auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run_info.json"), std::string::npos) << r.output;
  // A file, not a directory.
  r = run_command({postprocess_executable(), dir + "/run/notes.txt", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("not a directory"), std::string::npos) << r.output;
}

TEST(PostBadInput, MissingSnapshot) {
  const std::string dir = scratch_directory("missing_snapshot");
  const auto files = write_run_directory(dir + "/run", RunFixture{});
  fs::remove(files[2]);
  const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fs::path(files[2]).filename().string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/post/results.pvd")) << "checked before any output";
}

TEST(PostBadInput, TruncatedSnapshotLeavesTheGoodFramesReadable) {
  const std::string dir = scratch_directory("truncated_snapshot");
  const auto files = write_run_directory(dir + "/run", RunFixture{});
  fs::resize_file(files[2], fs::file_size(files[2]) / 2);
  const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fs::path(files[2]).filename().string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  // results.pvd lists exactly the frames written before the bad snapshot, all present.
  const std::string pvd = read_text(dir + "/post/results.pvd");
  EXPECT_NE(pvd.find("results/results_000000.vtu"), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("results/results_000040.vtu"), std::string::npos) << pvd;
  EXPECT_EQ(pvd.find("results/results_000080.vtu"), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/post/results/results_000040.vtu"));
  EXPECT_FALSE(fs::exists(dir + "/post/summary.json")) << "no summary of a series that could not be read";
  expect_no_temporaries(dir + "/post");
}

TEST(PostBadInput, CrashedRunNeedsPartial) {
  const std::string dir = scratch_directory("crashed_run");
  RunFixture fixture;
  fixture.status = "running";  // the solver never finalized run_info.json
  write_run_directory(dir + "/run", fixture);
  auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run_info.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did not finish"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--partial"), std::string::npos) << r.output;
  r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--partial", "--no-plot"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/post/summary.json"));
}

TEST(PostBadInput, CorruptRunInfo) {
  const std::string dir = scratch_directory("corrupt_run_info");
  write_run_directory(dir + "/run", RunFixture{});
  const std::string info = read_text(dir + "/run/run_info.json");
  std::ofstream(dir + "/run/run_info.json", std::ios::trunc) << info.substr(0, info.size() / 3);
  const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run_info.json"), std::string::npos) << r.output;
}

TEST(PostBadInput, SnapshotOfAnotherRun) {
  // A snapshot with a different point count (copied from another run) is refused by name.
  const std::string dir = scratch_directory("foreign_snapshot");
  const auto files = write_run_directory(dir + "/run", RunFixture{});
  RunFixture other;
  other.nx = 10;
  const auto other_files = write_run_directory(dir + "/other", other);
  fs::copy_file(other_files[1], files[1], fs::copy_options::overwrite_existing);
  const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--no-plot"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fs::path(files[1]).filename().string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("points"), std::string::npos) << r.output;
}

TEST(PostBadInput, SnapshotMissingAFieldOfTheFirst) {
  // Every frame of a series must hold the fields of the first (ParaView shows one array list).
  const std::string dir = scratch_directory("field_missing");
  const auto files = write_run_directory(dir + "/run", RunFixture{});
  RunFixture without_damage;
  without_damage.damage = false;
  const auto other_files = write_run_directory(dir + "/other", without_damage);
  fs::copy_file(other_files[2], files[2], fs::copy_options::overwrite_existing);
  const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--no-plot"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(fs::path(files[2]).filename().string() + ": field 'damage' is missing"), std::string::npos)
      << r.output;
}

TEST(PostBadInput, BadOptions) {
  const std::string dir = scratch_directory("bad_options");
  write_run_directory(dir + "/run", RunFixture{});
  auto r = run_command({postprocess_executable(), dir + "/run"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("-o"), std::string::npos) << r.output;
  r = run_command(
      {postprocess_executable(), dir + "/run", "-o", dir + "/post", "--figures", "--fields", "damage,temperature"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("temperature"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("plastic_shear_strain"), std::string::npos) << "lists what is available: " << r.output;
  r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--figures", "--times", "1 m"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--times"), std::string::npos) << r.output;
  r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--figures", "--times", "1 s"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no snapshot near"), std::string::npos) << r.output;
  r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--fields", "damage"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--figures"), std::string::npos) << r.output;
}

}  // namespace
