// Write-failure safety of common/atomic_file: a write that fails, for whatever
// reason, throws an InputError naming the file, leaves the previous complete file byte for byte
// and leaves no temporary behind. The OS failure is real: RLIMIT_FSIZE makes write(2) fail with
// EFBIG exactly as a full disk fails with ENOSPC, also for root (a chmod-500 directory does not
// stop root, and /dev/full cannot hold the temporary that is renamed).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"

namespace mppm {
namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "test_scratch" / "atomic_file" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Files in `dir` other than `keep`: a leftover temporary would show up here.
std::vector<std::string> other_files(const std::string& dir, const std::string& keep) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename() != keep) names.push_back(entry.path().filename().string());
  return names;
}

// Limits the size of any file this process writes while it lives; SIGXFSZ is ignored so that
// the write fails with EFBIG instead of killing the test.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) throw std::runtime_error("setrlimit failed");
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

TEST(AtomicFile, ReplacesTheFileAndLeavesNoTemporary) {
  const std::string dir = scratch("replace");
  const std::string path = dir + "/table.csv";
  write_file_atomically(path, [](std::ostream& out) { out << "first\n"; });
  write_file_atomically(path, [](std::ostream& out) { out << "second\n"; });
  EXPECT_EQ(contents(path), "second\n");
  EXPECT_TRUE(other_files(dir, "table.csv").empty());
}

TEST(AtomicFile, OperatingSystemWriteFailureKeepsThePreviousFile) {
  const std::string dir = scratch("efbig");
  const std::string path = dir + "/snapshot.snap";
  const std::string previous(10000, 'p');
  write_file_atomically(path, [&](std::ostream& out) { out << previous; });
  // 1 MiB against a 64 KiB limit: the failure comes from write(2) itself, mid-file, after
  // the stream buffer has been flushed many times (what a disk filling up looks like).
  const std::string next(1 << 20, 'n');
  std::string message;
  {
    FileSizeLimit limit(64 * 1024);
    try {
      write_file_atomically(path, [&](std::ostream& out) { out << next; });
    } catch (const InputError& e) {
      message = e.what();
    }
  }
  ASSERT_FALSE(message.empty()) << "the failed write was not reported";
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;  // strerror(EFBIG)
  EXPECT_EQ(contents(path), previous);
  EXPECT_TRUE(other_files(dir, "snapshot.snap").empty());
}

TEST(AtomicFile, FailureInTheLastBufferAtCloseIsReported) {
  // Smaller than the stream buffer: nothing reaches the file before close() flushes, so only
  // a checked close() sees the failure.
  const std::string dir = scratch("close");
  const std::string path = dir + "/run_info.json";
  write_file_atomically(path, [](std::ostream& out) { out << "{\"status\": \"running\"}\n"; });
  std::string message;
  {
    FileSizeLimit limit(8);
    try {
      write_file_atomically(path, [](std::ostream& out) { out << "{\"status\": \"completed\"}\n"; });
    } catch (const InputError& e) {
      message = e.what();
    }
  }
  ASSERT_FALSE(message.empty()) << "a failure at close() went unnoticed";
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_EQ(contents(path), "{\"status\": \"running\"}\n");
  EXPECT_TRUE(other_files(dir, "run_info.json").empty());
}

TEST(AtomicFile, WriterThatFailsOrThrowsKeepsThePreviousFile) {
  const std::string dir = scratch("writer");
  const std::string path = dir + "/load.csv";
  write_file_atomically(path, [](std::ostream& out) { out << "complete\n"; });
  // A stream error flagged by the writer (what a failed write inside a library does).
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& out) {
                                       out << "half";
                                       out.setstate(std::ios::badbit);
                                     }),
               InputError);
  // An exception of the writer itself passes through unchanged.
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& out) {
                                       out << "half";
                                       throw std::runtime_error("encoder failed");
                                     }),
               std::runtime_error);
  EXPECT_EQ(contents(path), "complete\n");
  EXPECT_TRUE(other_files(dir, "load.csv").empty());
}

TEST(AtomicFile, MissingDirectoryIsAnInputErrorNamingTheFile) {
  const std::string path = scratch("missing") + "/no/such/dir/points.vtp";
  try {
    write_file_atomically(path, [](std::ostream& out) { out << "x"; });
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// The run files after a snapshot are rewritten as one batch: all complete under their names
// after commit, none changed when any of them fails, and no temporary left either way.
TEST(StagedFiles, CommitRenamesEveryFileAndLeavesNoTemporary) {
  const std::string dir = scratch("staged");
  const std::vector<std::string> names{"load.csv", "log.txt", "run_info.json"};
  for (int round = 0; round < 2; ++round) {
    StagedFiles files;
    for (const std::string& name : names)
      files.stage(dir + "/" + name, [&](std::ostream& out) { out << name << ' ' << round << '\n'; });
    for (const std::string& name : names)  // staged, not yet renamed: the previous round's files
      EXPECT_EQ(contents(dir + "/" + name), round ? name + " 0\n" : "") << name;
    files.commit();
  }
  for (const std::string& name : names) EXPECT_EQ(contents(dir + "/" + name), name + " 1\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
}

TEST(StagedFiles, AFailedWriteChangesNoFileOfTheBatch) {
  const std::string dir = scratch("staged_failure");
  const std::string table = dir + "/load.csv", info = dir + "/run_info.json";
  write_file_atomically(table, [](std::ostream& out) { out << "old table\n"; });
  write_file_atomically(info, [](std::ostream& out) { out << "old info\n"; });
  std::string message;
  {
    StagedFiles files;
    files.stage(table, [](std::ostream& out) { out << "new table\n"; });
    FileSizeLimit limit(64 * 1024);
    try {
      files.stage(info, [](std::ostream& out) { out << std::string(1 << 20, 'n'); });
    } catch (const InputError& e) {
      message = e.what();
    }
  }  // the batch ends uncommitted: its first temporary is removed
  EXPECT_NE(message.find(info), std::string::npos) << message;
  EXPECT_EQ(contents(table), "old table\n");
  EXPECT_EQ(contents(info), "old info\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(StagedFiles, AFileThatCannotBeMadeDurableStopsTheCommitBeforeAnyRename) {
  const std::string dir = scratch("staged_missing");
  const std::string info = dir + "/run_info.json", gone = dir + "/snapshot_000010.snap";
  std::string message;
  {
    StagedFiles files;
    files.stage(info, [](std::ostream& out) { out << "lists the snapshot\n"; });
    try {
      files.commit({gone});
    } catch (const InputError& e) {
      message = e.what();
    }
  }
  EXPECT_NE(message.find(gone), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(info)) << "run_info.json names a snapshot that is not on disk";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
}

}  // namespace
}  // namespace mppm
