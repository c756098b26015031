// The run directory's checkpoint format (RUN_DIR/checkpoint/state.ckpt): the whole state a run
// needs to continue bit for bit, as named arrays, written atomically like every output file
// (temporary name, checked writes, fsync, rename: the previous checkpoint stays until the new one
// is complete). What the arrays are is the solver's business (solver/checkpoint.hpp); this file
// is the container: header, typed arrays, checksum.
//
// Layout (little-endian):
//   "MPPMCKPT" (8 bytes), u32 format version (1), u32 dimension, u64 point count,
//   u32 effect set (bits: 1 micropolar, 2 viscoplasticity, 4 damage, 8 gravity),
//   u64 scene fingerprint (FNV-1a of scene.resolved.yaml), u64 points fingerprint,
//   i64 step, f64 time, u32 array count,
//   per array: u32 name length, name bytes, u32 element type (CheckpointElement),
//              u64 element count, the elements,
//   u64 FNV-1a checksum of every preceding byte, "MPPMEND!" (8 bytes).
#pragma once
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/scene.hpp"

namespace mppm {

enum class CheckpointElement : std::uint32_t { f64 = 1, i64 = 2, i32 = 3, u8 = 4, u64 = 5, text = 6 };

template <class T>
constexpr CheckpointElement checkpoint_element_of();
template <>
constexpr CheckpointElement checkpoint_element_of<double>() {
  return CheckpointElement::f64;
}
template <>
constexpr CheckpointElement checkpoint_element_of<std::int64_t>() {
  return CheckpointElement::i64;
}
template <>
constexpr CheckpointElement checkpoint_element_of<std::int32_t>() {
  return CheckpointElement::i32;
}
template <>
constexpr CheckpointElement checkpoint_element_of<std::uint8_t>() {
  return CheckpointElement::u8;
}
template <>
constexpr CheckpointElement checkpoint_element_of<std::uint64_t>() {
  return CheckpointElement::u64;
}
template <>
constexpr CheckpointElement checkpoint_element_of<char>() {
  return CheckpointElement::text;
}

struct CheckpointHeader {
  int dimension = 2;
  std::uint64_t point_count = 0;
  std::uint32_t effects = 0;  // checkpoint_effect_bits
  std::uint64_t scene_fingerprint = 0;
  std::uint64_t points_fingerprint = 0;
  std::int64_t step = 0;
  double time = 0.0;
};

std::uint32_t checkpoint_effect_bits(const EffectSet& effects);

// An array to write: a view of data that must outlive write_checkpoint_file ...
struct CheckpointArrayView {
  std::string name;
  CheckpointElement element = CheckpointElement::f64;
  const void* data = nullptr;
  std::uint64_t count = 0;
  // ... or, for an array not held in one place (a distributed run's, gathered from its processes),
  // its rows of `components` values: rows [first, first + n) into `out`, asked for a chunk of rows
  // at a time (count = rows x components; data unused). An integer array's values come as doubles,
  // which hold them exactly, and are written in its element type (i32 or u8).
  int components = 1;
  std::function<void(std::uint64_t first, std::uint64_t n, double* out)> rows;
};
template <class T>
CheckpointArrayView checkpoint_array(std::string name, const std::vector<T>& values) {
  CheckpointArrayView v;
  v.name = std::move(name);
  v.element = checkpoint_element_of<T>();
  v.data = values.data();
  v.count = values.size();
  return v;
}
inline CheckpointArrayView checkpoint_text(std::string name, const std::string& text) {
  CheckpointArrayView v;
  v.name = std::move(name);
  v.element = CheckpointElement::text;
  v.data = text.data();
  v.count = text.size();
  return v;
}

// A checkpoint as read: the header and its arrays (checksum verified).
class CheckpointFile {
 public:
  CheckpointHeader header;
  std::string path;  // named in messages

  bool has(const std::string& name) const;
  // The array `name` as T; throws InputError (naming the file and the array) when it is missing
  // or of another type.
  template <class T>
  std::vector<T> array(const std::string& name) const {
    const Entry& e = find(name, checkpoint_element_of<T>());
    std::vector<T> out(e.count);
    if (e.count) std::memcpy(out.data(), data_.data() + e.offset, e.count * sizeof(T));
    return out;
  }
  std::string text(const std::string& name) const;
  // The array `name` into `out`, which must already have the size the run allocated (the file's
  // count must match: a checkpoint of another discretization is refused).
  template <class T>
  void restore(const std::string& name, std::vector<T>& out) const {
    const Entry& e = find(name, checkpoint_element_of<T>());
    if (e.count != out.size()) refuse_size(name, e.count, out.size());
    if (e.count) std::memcpy(out.data(), data_.data() + e.offset, e.count * sizeof(T));
  }
  // Rows of an array of `file_rows` rows of `width` values: row rows[k] of the file into row k of
  // `out` (a distributed run's process takes the rows of its own points; out has at least
  // rows.size() rows).
  template <class T>
  void restore_rows(const std::string& name, std::uint64_t file_rows, std::size_t width,
                    std::span<const std::int64_t> rows, std::vector<T>& out) const {
    const Entry& e = find(name, checkpoint_element_of<T>());
    if (e.count != file_rows * width) refuse_size(name, e.count, file_rows * width);
    for (std::size_t k = 0; k < rows.size(); ++k)
      std::memcpy(out.data() + k * width,
                  data_.data() + e.offset + static_cast<std::size_t>(rows[k]) * width * sizeof(T), width * sizeof(T));
  }

 private:
  friend CheckpointFile read_checkpoint_file(const std::string& path);
  struct Entry {
    std::string name;
    CheckpointElement element;
    std::uint64_t count;
    std::size_t offset;  // of the elements in data_
  };
  std::string data_;  // the whole file: arrays are copied out of it, not into separate buffers
  std::vector<Entry> entries_;
  const Entry& find(const std::string& name, CheckpointElement element) const;
  [[noreturn]] void refuse_size(const std::string& name, std::uint64_t stored, std::uint64_t expected) const;
};

// Writes atomically; throws InputError naming the file on a write error (the previous file at
// `path`, if any, is unchanged). `simulate_write_failure` (test hook): the write fails halfway
// through the arrays with ENOSPC, as on a full disk.
void write_checkpoint_file(const std::string& path, const CheckpointHeader& header,
                           const std::vector<CheckpointArrayView>& arrays, bool simulate_write_failure = false);

// Throws InputError naming the file and what is wrong (missing, truncated, bad checksum).
CheckpointFile read_checkpoint_file(const std::string& path);

}  // namespace mppm
