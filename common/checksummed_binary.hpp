// Little-endian binary records with a running checksum, shared by the run directory's binary
// files (snapshots, checkpoints): the writer hashes every byte it writes, the reader every byte it
// reads, so a file ends with the checksum of everything before it and a reader can tell a
// truncated or corrupted file from a good one.
#pragma once
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>

#include "common/input_error.hpp"

namespace mppm {

// FNV-1a 64-bit: cheap, detects truncation and corruption (not a cryptographic hash).
struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
  void add(const std::string& s) { add(s.data(), s.size()); }
};

inline std::uint64_t fnv1a(const std::string& bytes) {
  Fnv1a f;
  f.add(bytes);
  return f.h;
}

// The checksum of a binary file: FNV-1a 64 byte by byte (checkpoints, snapshot format 1), or
// zlib's CRC-32 (snapshot format 2), stored as a u64. FNV-1a is one multiply per byte in a chain
// (0.6 ms per 512 KB snapshot on the development VM, on the run's thread); zlib's CRC-32 takes
// 0.09 ms for the same bytes and detects every burst error up to 32 bits.
class RunningChecksum {
 public:
  enum class Kind { fnv1a, crc32 };
  explicit RunningChecksum(Kind kind = Kind::fnv1a) : kind_(kind) {}
  void add(const void* data, std::size_t n) {
    if (kind_ == Kind::fnv1a) {
      fnv_.add(data, n);
      return;
    }
    const auto* p = static_cast<const Bytef*>(data);
    while (n > 0) {  // zlib takes a uInt length
      const std::size_t piece = n < (1u << 30) ? n : (1u << 30);
      crc_ = crc32(crc_, p, static_cast<uInt>(piece));
      p += piece;
      n -= piece;
    }
  }
  std::uint64_t value() const { return kind_ == Kind::fnv1a ? fnv_.h : static_cast<std::uint64_t>(crc_); }

 private:
  Kind kind_;
  Fnv1a fnv_;
  uLong crc_ = crc32(0L, Z_NULL, 0);
};

class ChecksummedWriter {
 public:
  explicit ChecksummedWriter(std::ostream& out, RunningChecksum::Kind kind = RunningChecksum::Kind::fnv1a)
      : out_(out), hash_(kind) {}
  void bytes(const void* data, std::size_t n) {
    out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
    hash_.add(data, n);
  }
  template <class T>
  void value(T v) {
    bytes(&v, sizeof v);
  }
  std::uint64_t checksum() const { return hash_.value(); }
  // The checksum of every byte so far, then the end marker (neither is hashed).
  void finish(const char (&end_marker)[8]) {
    const std::uint64_t sum = hash_.value();
    out_.write(reinterpret_cast<const char*>(&sum), sizeof sum);
    out_.write(end_marker, sizeof end_marker);
  }

 private:
  std::ostream& out_;
  RunningChecksum hash_;
};

// Reads from the whole file held in memory (`data` must outlive the reader); `kind`
// ("snapshot", "checkpoint") names the file in messages.
class ChecksummedReader {
 public:
  ChecksummedReader(const std::string& path, std::string_view data, std::string kind)
      : path_(path), data_(data), kind_(std::move(kind)) {}
  void bytes(void* out, std::size_t n, const char* what) {
    require(n, what);
    if (n == 0) return;  // an empty field's data() may be null: memcpy(nullptr, ..., 0) is UB
    std::memcpy(out, data_.data() + pos_, n);
    skip(n, what);
  }
  // Hashes the next n bytes in place (a large array is then copied once, by its user).
  void skip(std::size_t n, const char* what) {
    require(n, what);
    hash_.add(data_.data() + pos_, n);
    pos_ += n;
  }
  std::size_t position() const { return pos_; }
  // From now on the checksum is of `kind`, over every byte read so far too (a format's version,
  // read from its header, decides the kind).
  void use_checksum(RunningChecksum::Kind kind) {
    hash_ = RunningChecksum(kind);
    hash_.add(data_.data(), pos_);
  }
  template <class T>
  T value(const char* what) {
    T v;
    bytes(&v, sizeof v, what);
    return v;
  }
  std::uint64_t checksum() const { return hash_.value(); }
  std::size_t remaining() const { return data_.size() - pos_; }
  // Reads the stored checksum and the end marker and compares them with what was read; throws
  // "corrupted KIND (checksum mismatch)" or "(trailing bytes ...)".
  void finish(const char (&end_marker)[8]) {
    const std::uint64_t expected = hash_.value();
    const auto stored = value<std::uint64_t>("the checksum");
    char end[8];
    bytes(end, sizeof end, "the end marker");
    if (stored != expected || std::memcmp(end, end_marker, sizeof end) != 0)
      throw InputError(path_ + ": corrupted " + kind_ + " (checksum mismatch)");
    if (remaining() != 0) throw InputError(path_ + ": corrupted " + kind_ + " (trailing bytes after the end marker)");
  }

 private:
  void require(std::size_t n, const char* what) const {
    if (n > data_.size() - pos_) {
      throw InputError(path_ + ": truncated " + kind_ + " (ends inside " + std::string(what) +
                       "; was the run killed while writing?)");
    }
  }
  std::string path_;
  std::string_view data_;
  std::string kind_;
  std::size_t pos_ = 0;
  RunningChecksum hash_;
};

}  // namespace mppm
