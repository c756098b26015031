// Snapshot files: round trip, and detection of truncation and corruption.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "common/snapshot_file.hpp"

using namespace mppm;
namespace fs = std::filesystem;

namespace {
Snapshot sample() {
  Snapshot s;
  s.dimension = 2;
  s.step = 42;
  s.time = 1.25e-6;
  s.point_count = 3;
  s.fields.push_back({"displacement", 2, {1, 2, 3, 4, 5, 6}});
  s.fields.push_back({"damage", 1, {0.0, 0.5, 1.0}});
  return s;
}
fs::path temp_dir() {
  auto d = fs::temp_directory_path() / ("mppm_snap_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(SnapshotFile, RoundTripIsExact) {
  const auto path = (temp_dir() / "a.snap").string();
  write_snapshot(sample(), path);
  const Snapshot r = read_snapshot(path);
  EXPECT_EQ(r.dimension, 2);
  EXPECT_EQ(r.step, 42);
  EXPECT_EQ(r.time, 1.25e-6);
  ASSERT_EQ(r.fields.size(), 2u);
  EXPECT_EQ(r.find("displacement")->data, sample().fields[0].data);
  EXPECT_EQ(r.find("damage")->data, sample().fields[1].data);
  EXPECT_EQ(r.find("rotation"), nullptr);
  // No temporary file is left behind.
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(path).parent_path())) files += e.path().filename() == "a.snap" ? 1 : 0;
  EXPECT_EQ(files, 1);
}

TEST(SnapshotFile, TruncationAndCorruptionAreReported) {
  const auto path = (temp_dir() / "b.snap").string();
  write_snapshot(sample(), path);
  const auto size = fs::file_size(path);
  for (std::uintmax_t keep : {std::uintmax_t{0}, std::uintmax_t{10}, size / 2, size - 1}) {
    fs::copy_file(path, path + ".cut", fs::copy_options::overwrite_existing);
    fs::resize_file(path + ".cut", keep);
    try {
      read_snapshot(path + ".cut");
      FAIL() << "a snapshot cut to " << keep << " bytes was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ".cut"), std::string::npos);
    }
  }
  // Flip one data byte: the checksum catches it.
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    char c;
    f.read(&c, 1);
    c = static_cast<char>(c ^ 0x40);
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.write(&c, 1);
  }
  EXPECT_THROW(read_snapshot(path), InputError);
  EXPECT_THROW(read_snapshot((temp_dir() / "missing.snap").string()), InputError);
}

TEST(SnapshotFile, RefusesInconsistentFields) {
  Snapshot s = sample();
  s.fields[1].data.pop_back();
  EXPECT_THROW(write_snapshot(s, (temp_dir() / "c.snap").string()), std::logic_error);
}
