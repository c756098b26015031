// Snapshot files: round trip, and detection of truncation and corruption.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/checksummed_binary.hpp"
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
  auto d = fs::temp_directory_path() /
           ("mppm_snap_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
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
  for (const auto& e : fs::directory_iterator(fs::path(path).parent_path()))
    files += e.path().filename() == "a.snap" ? 1 : 0;
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

namespace {
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream b;
  b << in.rdbuf();
  return b.str();
}
void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}
std::uint32_t stored_version(const std::string& bytes) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + 8, sizeof v);
  return v;
}
}  // namespace

// Format 2 as snapshot_file.hpp documents it: the u64 before the end marker is zlib's CRC-32 of
// every byte before it, computed here independently of the writer.
TEST(SnapshotFile, FormatTwoEndsWithTheCrc32OfItsBytes) {
  const auto path = (temp_dir() / "crc.snap").string();
  write_snapshot(sample(), path);
  const std::string bytes = file_bytes(path);
  ASSERT_GT(bytes.size(), 16u);
  EXPECT_EQ(stored_version(bytes), 2u);
  const std::size_t body = bytes.size() - 16;
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + body, sizeof stored);
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(body));
  EXPECT_EQ(stored, static_cast<std::uint64_t>(crc));
  EXPECT_EQ(bytes.substr(body + 8), "MPPMEND!");
}

// Runs written before format 2 (FNV-1a 64 checksum, version 1) are still read, and checked.
TEST(SnapshotFile, FormatOneIsStillReadAndChecked) {
  const auto path = (temp_dir() / "v1.snap").string();
  write_snapshot(sample(), path);
  std::string bytes = file_bytes(path);
  const std::size_t body = bytes.size() - 16;
  const std::uint32_t one = 1;
  std::memcpy(bytes.data() + 8, &one, sizeof one);
  Fnv1a fnv;
  fnv.add(bytes.data(), body);
  std::memcpy(bytes.data() + body, &fnv.h, sizeof fnv.h);
  write_bytes(path, bytes);
  const Snapshot r = read_snapshot(path);
  EXPECT_EQ(r.step, 42);
  EXPECT_EQ(r.find("displacement")->data, sample().fields[0].data);
  // The same file with a CRC-32 where format 1 has its FNV-1a: refused.
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(body));
  const auto crc64 = static_cast<std::uint64_t>(crc);
  std::memcpy(bytes.data() + body, &crc64, sizeof crc64);
  write_bytes(path, bytes);
  EXPECT_THROW(read_snapshot(path), InputError);
}

TEST(SnapshotFile, UnknownFormatVersionIsNamed) {
  const auto path = (temp_dir() / "v3.snap").string();
  write_snapshot(sample(), path);
  std::string bytes = file_bytes(path);
  const std::uint32_t three = 3;
  std::memcpy(bytes.data() + 8, &three, sizeof three);
  write_bytes(path, bytes);
  try {
    read_snapshot(path);
    FAIL() << "a snapshot of format version 3 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("format version 3 is not supported (this mppm reads 1 and 2)"),
              std::string::npos)
        << e.what();
  }
}

TEST(SnapshotFile, RefusesInconsistentFields) {
  Snapshot s = sample();
  s.fields[1].data.pop_back();
  EXPECT_THROW(write_snapshot(s, (temp_dir() / "c.snap").string()), std::logic_error);
}
