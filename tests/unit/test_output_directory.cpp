// prepare_output_directory (common/output_directory.hpp): create, refuse without --force,
// replace as a whole with it (the earlier output deleted beside the stage, EarlierOutputRemoval),
// and never delete a directory that is not an earlier output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "common/output_directory.hpp"

namespace mppm {
namespace {

namespace fs = std::filesystem;

const OutputDirectoryKind kRun{"run directory", "-o RUN_DIR", {"run_info.json", "snapshots"}};

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "test_scratch" / "output_directory" / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir.string();
}

void touch(const fs::path& path) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "x";
}

std::string message_of(const std::string& dir, bool force) {
  try {
    const EarlierOutputRemoval removal = prepare_output_directory(dir, force, kRun);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputDirectory, MissingOrEmptyDirectoryIsCreatedOrKept) {
  const std::string dir = scratch("fresh") + "/nested/run";
  EarlierOutputRemoval none = prepare_output_directory(dir, false, kRun);
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_EQ(none.wait(), "");
  const EarlierOutputRemoval still_none = prepare_output_directory(dir, false, kRun);  // empty: no --force needed
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputDirectory, NonEmptyDirectoryIsRefusedWithoutForceAndLeftAlone) {
  const std::string dir = scratch("refuse");
  touch(fs::path(dir) / "run_info.json");
  const std::string message = message_of(dir, false);
  EXPECT_EQ(message.rfind(dir + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("--force"), std::string::npos) << message;
  EXPECT_TRUE(fs::exists(fs::path(dir) / "run_info.json"));
}

TEST(OutputDirectory, ForceReplacesAnEarlierOutputAsAWhole) {
  for (const std::string suffix : {"", "/"}) {  // a trailing separator names the same directory
    const std::string dir = scratch("replace");
    touch(fs::path(dir) / "run_info.json");
    touch(fs::path(dir) / "snapshots" / "snapshot_000099.snap");
    touch(fs::path(dir) / "anything_else.txt");
    EarlierOutputRemoval removal = prepare_output_directory(dir + suffix, true, kRun);
    // Under its name at once: an empty directory (the earlier output moved aside) ...
    EXPECT_TRUE(fs::is_directory(dir)) << suffix;
    EXPECT_TRUE(fs::is_empty(dir)) << suffix;
    // ... and once the deletion beside the stage has ended, nothing of it anywhere.
    EXPECT_EQ(removal.wait(), "") << suffix;
    for (const auto& entry : fs::directory_iterator(fs::path(dir).parent_path()))
      EXPECT_EQ(entry.path().filename().string().find(".replaced-"), std::string::npos) << entry.path();
  }
}

TEST(OutputDirectory, ForceRefusesADirectoryWithoutTheStagesFiles) {
  const std::string dir = scratch("foreign");
  touch(fs::path(dir) / "thesis.tex");
  const std::string message = message_of(dir, true);
  EXPECT_NE(message.find("does not look like a run directory"), std::string::npos) << message;
  EXPECT_TRUE(fs::exists(fs::path(dir) / "thesis.tex"));
}

TEST(OutputDirectory, AFileInTheWayIsRefused) {
  const std::string path = scratch("file");
  touch(path);
  const std::string message = message_of(path, true);
  EXPECT_NE(message.find("is not a directory"), std::string::npos) << message;
  EXPECT_TRUE(fs::is_regular_file(path));
}

}  // namespace
}  // namespace mppm
