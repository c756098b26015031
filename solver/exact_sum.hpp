// An exact sum of doubles, rounded once (a long fixed-point "Kulisch" accumulator; docs/theory.md
// section 13, "Sums that do not depend on the order"). Every finite double is an integer multiple
// of 2^-1074, so the accumulator holds the sum exactly as such an integer, in 32-bit digits kept in
// 64-bit words (carries are deferred: up to 2^30 terms between carry propagations). The rounded
// value therefore does not depend on the order of the terms, nor on how they were split among
// threads or processes and merged: the energies, work, reactions and the critical step's inner
// products come out with the same bits for any thread count and any partition of the points.
//
// Written by hand: no Debian package offers one (ExBLAS and ReproBLAS are not packaged).
#pragma once
#include <array>
#include <cstdint>
#include <span>

namespace mppm::solver {

class ExactSum {
 public:
  static constexpr int kDigitBits = 32;
  // Bits 0 .. 2097 hold every finite double (2^-1074 .. below 2^1024, in units of 2^-1074); the
  // last digit keeps the sign and the carries of sums beyond the double range, which can come back
  // into it (DBL_MAX + DBL_MAX - DBL_MAX).
  static constexpr int kDigits = 67;
  // The accumulator as integers, for a sum across processes by integer addition (MPI_SUM on
  // int64 is exact and order-independent): the digits, then the counts of NaNs, +inf and -inf.
  static constexpr int kWireWords = kDigits + 3;
  using Wire = std::array<std::int64_t, kWireWords>;

  ExactSum() = default;
  explicit ExactSum(double x) { add(x); }

  void add(double x);
  ExactSum& operator+=(double x) {
    add(x);
    return *this;
  }
  ExactSum& operator-=(double x) {
    add(-x);
    return *this;
  }
  // Merges another accumulator (the sum of both term lists).
  ExactSum& operator+=(const ExactSum& other);

  // The sum rounded to the nearest double, ties to even; +inf or -inf beyond the double range;
  // NaN if a term was NaN or both infinities were added (as IEEE addition gives).
  double value() const;

  Wire wire() const;
  // An accumulator from a wire, or from the integer sum of at most 2^30 wires.
  static ExactSum from_wire(std::span<const std::int64_t, kWireWords> wire);

 private:
  // Propagates the deferred carries: digits 0 .. kDigits-2 in [0, 2^32), the sign in the last.
  void propagate_carries();
  void count_pending(std::int64_t terms);

  std::array<std::int64_t, kDigits> digit_{};
  // Terms added since the carries were last propagated: each adds less than 2^32 to a digit, so
  // 2^30 of them keep every digit far inside the int64 range.
  std::int64_t pending_ = 0;
  std::int64_t nans_ = 0, positive_infinities_ = 0, negative_infinities_ = 0;
};

}  // namespace mppm::solver
