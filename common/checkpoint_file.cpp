// Checkpoint files (layout in checkpoint_file.hpp): checksummed, written atomically.
#include "common/checkpoint_file.hpp"

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/checksummed_binary.hpp"
#include "common/input_error.hpp"

namespace mppm {
namespace {

constexpr char kMagic[8] = {'M', 'P', 'P', 'M', 'C', 'K', 'P', 'T'};
constexpr char kEnd[8] = {'M', 'P', 'P', 'M', 'E', 'N', 'D', '!'};
constexpr std::uint32_t kVersion = 1;

std::size_t element_size(CheckpointElement e) {
  switch (e) {
    case CheckpointElement::f64:
    case CheckpointElement::i64:
    case CheckpointElement::u64:
      return 8;
    case CheckpointElement::i32:
      return 4;
    case CheckpointElement::u8:
    case CheckpointElement::text:
      return 1;
  }
  return 0;
}

const char* element_name(CheckpointElement e) {
  switch (e) {
    case CheckpointElement::f64:
      return "f64";
    case CheckpointElement::i64:
      return "i64";
    case CheckpointElement::u64:
      return "u64";
    case CheckpointElement::i32:
      return "i32";
    case CheckpointElement::u8:
      return "u8";
    case CheckpointElement::text:
      return "text";
  }
  return "?";
}

// A chunk of values of an integer array, delivered as doubles (exact: CheckpointArrayView::rows), in
// the array's element type.
template <class T>
void write_as(ChecksummedWriter& w, const std::vector<double>& chunk, std::size_t n, std::vector<T>& converted) {
  converted.resize(n);
  for (std::size_t k = 0; k < n; ++k) converted[k] = static_cast<T>(chunk[k]);
  w.bytes(converted.data(), n * sizeof(T));
}

// The rows of an array given by its `rows` function, a chunk of rows at a time.
void write_rows(ChecksummedWriter& w, const CheckpointArrayView& a) {
  constexpr std::uint64_t kChunkRows = 4096;
  const auto width = static_cast<std::uint64_t>(a.components);
  const std::uint64_t rows = a.count / width;
  std::vector<double> chunk(std::min(rows, kChunkRows) * width);
  std::vector<std::int32_t> i32;
  std::vector<std::uint8_t> u8;
  for (std::uint64_t first = 0; first < rows; first += kChunkRows) {
    const std::uint64_t n = std::min(kChunkRows, rows - first);
    a.rows(first, n, chunk.data());
    const std::size_t values = n * width;
    switch (a.element) {
      case CheckpointElement::f64:
        w.bytes(chunk.data(), values * sizeof(double));
        break;
      case CheckpointElement::i32:
        write_as(w, chunk, values, i32);
        break;
      case CheckpointElement::u8:
        write_as(w, chunk, values, u8);
        break;
      default:
        throw std::logic_error("checkpoint array '" + a.name + "': rows of this element type cannot be written");
    }
  }
}

}  // namespace

std::uint32_t checkpoint_effect_bits(const EffectSet& effects) {
  return (effects.micropolar ? 1u : 0u) | (effects.viscoplasticity ? 2u : 0u) | (effects.damage ? 4u : 0u) |
         (effects.gravity ? 8u : 0u) | (effects.pore_fluid ? 16u : 0u);
}

bool CheckpointFile::has(const std::string& name) const {
  for (const auto& e : entries_)
    if (e.name == name) return true;
  return false;
}

const CheckpointFile::Entry& CheckpointFile::find(const std::string& name, CheckpointElement element) const {
  for (const auto& e : entries_) {
    if (e.name != name) continue;
    if (e.element != element)
      throw InputError(path + ": checkpoint array '" + name + "' holds " + element_name(e.element) + ", expected " +
                       element_name(element) + " (written by another mppm version?)");
    return e;
  }
  throw InputError(path + ": the checkpoint has no '" + name +
                   "' (written by another mppm version, or for other effects?)");
}

void CheckpointFile::refuse_size(const std::string& name, std::uint64_t stored, std::uint64_t expected) const {
  throw InputError(path + ": checkpoint array '" + name + "' has " + std::to_string(stored) + " values, the run has " +
                   std::to_string(expected) + " (the points or the scene are not those of the checkpoint)");
}

std::string CheckpointFile::text(const std::string& name) const {
  const Entry& e = find(name, CheckpointElement::text);
  return data_.substr(e.offset, e.count);
}

void write_checkpoint_file(const std::string& path, const CheckpointHeader& h,
                           const std::vector<CheckpointArrayView>& arrays, bool simulate_write_failure) {
  write_file_atomically(path, [&](std::ostream& out) {
    ChecksummedWriter w(out);
    w.bytes(kMagic, sizeof kMagic);
    w.value<std::uint32_t>(kVersion);
    w.value<std::uint32_t>(static_cast<std::uint32_t>(h.dimension));
    w.value<std::uint64_t>(h.point_count);
    w.value<std::uint32_t>(h.effects);
    w.value<std::uint64_t>(h.scene_fingerprint);
    w.value<std::uint64_t>(h.points_fingerprint);
    w.value<std::int64_t>(h.step);
    w.value<double>(h.time);
    w.value<std::uint32_t>(static_cast<std::uint32_t>(arrays.size()));
    for (std::size_t k = 0; k < arrays.size(); ++k) {
      const CheckpointArrayView& a = arrays[k];
      if (simulate_write_failure && 2 * k >= arrays.size()) {
        // As a full disk would: the stream fails with errno set, and write_file_atomically
        // reports it and removes the temporary.
        errno = ENOSPC;
        out.setstate(std::ios::badbit);
        return;
      }
      w.value<std::uint32_t>(static_cast<std::uint32_t>(a.name.size()));
      w.bytes(a.name.data(), a.name.size());
      w.value<std::uint32_t>(static_cast<std::uint32_t>(a.element));
      w.value<std::uint64_t>(a.count);
      if (a.rows)
        write_rows(w, a);
      else
        w.bytes(a.data, a.count * element_size(a.element));
    }
    w.finish(kEnd);
  });
}

CheckpointFile read_checkpoint_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path +
                     ": no checkpoint (not found or not readable; a run writes checkpoints only when its scene sets "
                     "output.checkpoint_interval)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  CheckpointFile f;
  f.path = path;
  f.data_ = buffer.str();
  // The reader hashes as it goes; the arrays stay in data_, located by their offsets.
  ChecksummedReader r(path, f.data_, "checkpoint");
  auto read = [&](void* out, std::size_t n, const char* what) { r.bytes(out, n, what); };
  auto u32 = [&](const char* what) { return r.value<std::uint32_t>(what); };
  auto u64 = [&](const char* what) { return r.value<std::uint64_t>(what); };
  char magic[8];
  read(magic, sizeof magic, "the header");
  if (std::memcmp(magic, kMagic, sizeof magic) != 0)
    throw InputError(path + ": not an mppm checkpoint (bad magic bytes)");
  const auto version = u32("the header");
  if (version != kVersion)
    throw InputError(path + ": checkpoint format version " + std::to_string(version) +
                     " is not supported (this mppm reads 1)");
  f.header.dimension = static_cast<int>(u32("the header"));
  if (f.header.dimension != 2 && f.header.dimension != 3)
    throw InputError(path + ": corrupted checkpoint (dimension " + std::to_string(f.header.dimension) + ")");
  f.header.point_count = u64("the header");
  f.header.effects = u32("the header");
  f.header.scene_fingerprint = u64("the header");
  f.header.points_fingerprint = u64("the header");
  read(&f.header.step, sizeof f.header.step, "the header");
  read(&f.header.time, sizeof f.header.time, "the header");
  const auto count = u32("the header");
  if (count > 10000) throw InputError(path + ": corrupted checkpoint (" + std::to_string(count) + " arrays)");
  for (std::uint32_t k = 0; k < count; ++k) {
    CheckpointFile::Entry e;
    const auto name_length = u32("an array name");
    if (name_length == 0 || name_length > 256)
      throw InputError(path + ": corrupted checkpoint (array name of length " + std::to_string(name_length) + ")");
    e.name.resize(name_length);
    read(e.name.data(), name_length, "an array name");
    e.element = static_cast<CheckpointElement>(u32("an array header"));
    const std::size_t size = element_size(e.element);
    if (size == 0)
      throw InputError(path + ": corrupted checkpoint (array '" + e.name + "' has an unknown element type)");
    e.count = u64("an array header");
    if (e.count > r.remaining() / size)
      throw InputError(path + ": truncated checkpoint (array '" + e.name + "' needs " + std::to_string(e.count) +
                       " values; was the run killed while writing?)");
    e.offset = r.position();
    r.skip(e.count * size, "array data");
    f.entries_.push_back(std::move(e));
  }
  r.finish(kEnd);
  return f;
}

}  // namespace mppm
