// The run directory's binary snapshot format, shared by the solver (writer), the
// postprocessor and restart (readers). One file per snapshot, written atomically.
//
// Layout (little-endian):
//   "MPPMSNAP" (8 bytes), u32 format version (2), u32 dimension,
//   i64 step, f64 time, u64 point count, u32 field count,
//   per field: u32 name length, name bytes, u32 components, f64 data[points*components]
//              (point-major: value of point i, component c at [i*components + c]),
//   u64 checksum of every preceding byte, "MPPMEND!" (8 bytes): zlib's CRC-32 in format 2, FNV-1a 64
//   in format 1 (written before 2026-12-02; still read).
// A truncated or corrupted file fails the checksum or the end marker and is reported.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace mppm {

struct SnapshotField {
  std::string name;  // in words: "displacement", "rotation", "damage", ...
  int components = 1;
  std::vector<double> data;
};

struct Snapshot {
  int dimension = 2;
  std::int64_t step = 0;
  double time = 0.0;
  std::uint64_t point_count = 0;
  std::vector<SnapshotField> fields;

  const SnapshotField* find(const std::string& name) const;
};

// Throws InputError on write failure; never leaves a partial file under `path`.
void write_snapshot(const Snapshot& snapshot, const std::string& path);

// A field produced while it is written: values(first, count, out) writes the components of points
// first .. first + count - 1 into out (count * components values, point-major).
struct SnapshotFieldSource {
  std::string name;
  int components = 1;
  std::function<void(std::uint64_t first, std::uint64_t count, double* out)> values;
};

// Points a streamed field is produced and written at a time.
inline constexpr std::uint64_t kSnapshotPointsPerChunk = 4096;

// The bytes write_snapshot writes for the snapshot of these fields, without the snapshot in memory:
// the values are produced and written a few thousand points at a time, so that writing a snapshot
// of a large run does not need a copy of its fields (which would add to the run's peak memory).
void write_snapshot(int dimension, std::int64_t step, double time, std::uint64_t point_count,
                    const std::vector<SnapshotFieldSource>& fields, const std::string& path);
// The same bytes written to a temporary next to `path`, whose name it returns: commit_temporary
// (common/atomic_file.hpp) makes it `path`, possibly later and on another thread.
std::string write_snapshot_temporary(int dimension, std::int64_t step, double time, std::uint64_t point_count,
                                     const std::vector<SnapshotFieldSource>& fields, const std::string& path);

// Throws InputError naming the file and what is wrong (missing, truncated, bad checksum).
Snapshot read_snapshot(const std::string& path);

// Run directory layout (docs/stages.md):
//   scene.resolved.yaml, log.txt, load.csv, energy.csv, run_info.json,
//   reference.snap   (fields: position(3), volume, region, boundary_id: the points as run)
//   snapshots/snapshot_000000.snap, ...   (step number in the name, 6+ digits)
//   checkpoint/state.ckpt   (with output.checkpoint_interval; common/checkpoint_file.hpp)
namespace run_layout {
inline constexpr const char* resolved_scene = "scene.resolved.yaml";
inline constexpr const char* log = "log.txt";
inline constexpr const char* load = "load.csv";
inline constexpr const char* energy = "energy.csv";
inline constexpr const char* crack_path = "crack_path.csv";  // damage runs (common/crack_path.hpp)
inline constexpr const char* run_info = "run_info.json";
inline constexpr const char* reference = "reference.snap";
inline constexpr const char* snapshot_dir = "snapshots";
inline constexpr const char* checkpoint_dir = "checkpoint";
inline constexpr const char* checkpoint = "checkpoint/state.ckpt";
std::string snapshot_name(std::int64_t index);  // "snapshot_000012.snap"
}  // namespace run_layout

}  // namespace mppm
