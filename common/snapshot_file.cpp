// Binary snapshot files (layout in snapshot_file.hpp): checksummed, written atomically.
#include "common/snapshot_file.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/checksummed_binary.hpp"
#include "common/input_error.hpp"

namespace mppm {
namespace {

constexpr char kMagic[8] = {'M', 'P', 'P', 'M', 'S', 'N', 'A', 'P'};
constexpr char kEnd[8] = {'M', 'P', 'P', 'M', 'E', 'N', 'D', '!'};
// Format 2 (CRC-32) is written; 1 (FNV-1a, runs of mppm before 2026-12-02) is still read.
constexpr std::uint32_t kVersion = 2;
RunningChecksum::Kind checksum_kind(std::uint32_t version) {
  return version == 1 ? RunningChecksum::Kind::fnv1a : RunningChecksum::Kind::crc32;
}

}  // namespace

const SnapshotField* Snapshot::find(const std::string& name) const {
  for (const auto& f : fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

void write_snapshot(const Snapshot& s, const std::string& path) {
  std::vector<SnapshotFieldSource> sources;
  for (const auto& f : s.fields) {
    if (f.components <= 0 || f.data.size() != s.point_count * static_cast<std::uint64_t>(f.components)) {
      throw std::logic_error("snapshot field '" + f.name + "' has " + std::to_string(f.data.size()) + " values for " +
                             std::to_string(s.point_count) + " points");
    }
    sources.push_back({f.name, f.components, [&f](std::uint64_t first, std::uint64_t count, double* out) {
                         const auto c = static_cast<std::uint64_t>(f.components);
                         std::memcpy(out, f.data.data() + first * c, count * c * sizeof(double));
                       }});
  }
  write_snapshot(s.dimension, s.step, s.time, s.point_count, sources, path);
}

void write_snapshot(int dimension, std::int64_t step, double time, std::uint64_t point_count,
                    const std::vector<SnapshotFieldSource>& fields, const std::string& path) {
  commit_temporary(write_snapshot_temporary(dimension, step, time, point_count, fields, path), path);
}

std::string write_snapshot_temporary(int dimension, std::int64_t step, double time, std::uint64_t point_count,
                                     const std::vector<SnapshotFieldSource>& fields, const std::string& path) {
  constexpr std::uint64_t kPointsPerChunk = kSnapshotPointsPerChunk;
  std::vector<double> chunk;
  return write_temporary(path, [&](std::ostream& out) {
    ChecksummedWriter w(out, checksum_kind(kVersion));
    w.bytes(kMagic, sizeof kMagic);
    w.value<std::uint32_t>(kVersion);
    w.value<std::uint32_t>(static_cast<std::uint32_t>(dimension));
    w.value<std::int64_t>(step);
    w.value<double>(time);
    w.value<std::uint64_t>(point_count);
    w.value<std::uint32_t>(static_cast<std::uint32_t>(fields.size()));
    for (const auto& f : fields) {
      w.value<std::uint32_t>(static_cast<std::uint32_t>(f.name.size()));
      w.bytes(f.name.data(), f.name.size());
      w.value<std::uint32_t>(static_cast<std::uint32_t>(f.components));
      const auto c = static_cast<std::uint64_t>(f.components);
      chunk.resize(std::min(point_count, kPointsPerChunk) * c);
      // The checksum runs over the bytes in order, so writing them in chunks changes nothing.
      for (std::uint64_t first = 0; first < point_count; first += kPointsPerChunk) {
        const std::uint64_t count = std::min(kPointsPerChunk, point_count - first);
        f.values(first, count, chunk.data());
        w.bytes(chunk.data(), count * c * sizeof(double));
      }
    }
    w.finish(kEnd);
  });
}

Snapshot read_snapshot(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": snapshot not found or not readable");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string data = buffer.str();
  ChecksummedReader r(path, data, "snapshot");
  char magic[8];
  r.bytes(magic, sizeof magic, "the header");
  if (std::memcmp(magic, kMagic, sizeof magic) != 0)
    throw InputError(path + ": not an mppm snapshot (bad magic bytes)");
  const auto version = r.value<std::uint32_t>("the header");
  if (version != 1 && version != 2)
    throw InputError(path + ": snapshot format version " + std::to_string(version) +
                     " is not supported (this mppm reads 1 and 2)");
  r.use_checksum(checksum_kind(version));
  Snapshot s;
  s.dimension = static_cast<int>(r.value<std::uint32_t>("the header"));
  if (s.dimension != 2 && s.dimension != 3)
    throw InputError(path + ": corrupted snapshot (dimension " + std::to_string(s.dimension) + ")");
  s.step = r.value<std::int64_t>("the header");
  s.time = r.value<double>("the header");
  s.point_count = r.value<std::uint64_t>("the header");
  const auto field_count = r.value<std::uint32_t>("the header");
  if (field_count > 1000) throw InputError(path + ": corrupted snapshot (" + std::to_string(field_count) + " fields)");
  for (std::uint32_t k = 0; k < field_count; ++k) {
    SnapshotField f;
    const auto name_length = r.value<std::uint32_t>("a field name");
    if (name_length == 0 || name_length > 256)
      throw InputError(path + ": corrupted snapshot (field name of length " + std::to_string(name_length) + ")");
    f.name.resize(name_length);
    r.bytes(f.name.data(), name_length, "a field name");
    f.components = static_cast<int>(r.value<std::uint32_t>("a field header"));
    if (f.components <= 0 || f.components > 64)
      throw InputError(path + ": corrupted snapshot (field '" + f.name + "' has " + std::to_string(f.components) +
                       " components)");
    // Compare by division first so a corrupted point count cannot overflow the product.
    if (s.point_count > r.remaining() / sizeof(double) / static_cast<std::uint64_t>(f.components)) {
      throw InputError(path + ": truncated snapshot (field '" + f.name + "' needs " + std::to_string(s.point_count) +
                       " points x " + std::to_string(f.components) + " values; was the run killed while writing?)");
    }
    const std::uint64_t count = s.point_count * static_cast<std::uint64_t>(f.components);
    if (count * sizeof(double) > r.remaining()) {
      throw InputError(path + ": truncated snapshot (field '" + f.name + "' needs " + std::to_string(count) +
                       " values; was the run killed while writing?)");
    }
    f.data.resize(count);
    r.bytes(f.data.data(), count * sizeof(double), "field data");
    s.fields.push_back(std::move(f));
  }
  r.finish(kEnd);
  return s;
}

namespace run_layout {
std::string snapshot_name(std::int64_t index) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "snapshot_%06lld.snap", static_cast<long long>(index));
  return buf;
}
}  // namespace run_layout

}  // namespace mppm
