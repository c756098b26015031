// The exact accumulator (exact_sum.hpp): a double m 2^(e-1075) with a 53-bit significand m is
// added as the integer m 2^(e-1) in units of 2^-1074, which spans at most three 32-bit digits.
#include "solver/exact_sum.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace mppm::solver {

namespace {

constexpr std::int64_t kCarryLimit = std::int64_t{1} << 30;
constexpr std::uint64_t kDigitMask = (std::uint64_t{1} << ExactSum::kDigitBits) - 1;

}  // namespace

void ExactSum::count_pending(std::int64_t terms) {
  pending_ += terms;
  if (pending_ >= kCarryLimit) propagate_carries();
}

void ExactSum::add(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto exponent = static_cast<int>((bits >> 52) & 0x7ff);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  const bool negative = (bits >> 63) != 0;
  if (exponent == 0x7ff) {
    if (fraction != 0)
      ++nans_;
    else
      ++(negative ? negative_infinities_ : positive_infinities_);
    return;
  }
  if (exponent == 0 && fraction == 0) return;  // +-0 adds nothing
  // Subnormals: fraction 2^-1074; normals: (2^52 + fraction) 2^(exponent - 1075).
  const std::uint64_t significand = exponent == 0 ? fraction : fraction | (std::uint64_t{1} << 52);
  const int shift = exponent == 0 ? 0 : exponent - 1;
  const int k = shift / kDigitBits;
  const int offset = shift % kDigitBits;
  const std::uint64_t pieces[3] = {
      (significand << offset) & kDigitMask,
      (significand >> (kDigitBits - offset)) & kDigitMask,
      offset == 0 ? 0 : significand >> (2 * kDigitBits - offset),
  };
  for (int d = 0; d < 3; ++d) {
    const auto piece = static_cast<std::int64_t>(pieces[d]);
    digit_[static_cast<std::size_t>(k + d)] += negative ? -piece : piece;
  }
  count_pending(1);
}

ExactSum& ExactSum::operator+=(const ExactSum& other) {
  for (int d = 0; d < kDigits; ++d) digit_[static_cast<std::size_t>(d)] += other.digit_[static_cast<std::size_t>(d)];
  nans_ += other.nans_;
  positive_infinities_ += other.positive_infinities_;
  negative_infinities_ += other.negative_infinities_;
  // Each side's digits are bounded by (its pending terms + 1) 2^32.
  count_pending(other.pending_ + 1);
  return *this;
}

void ExactSum::propagate_carries() {
  for (int d = 0; d + 1 < kDigits; ++d) {
    auto& here = digit_[static_cast<std::size_t>(d)];
    const std::int64_t carry = here >> kDigitBits;  // floor division by 2^32 (arithmetic shift)
    here -= carry * (std::int64_t{1} << kDigitBits);
    digit_[static_cast<std::size_t>(d + 1)] += carry;
  }
  pending_ = 0;
}

namespace {

// Reads the non-negative integer of normalized digits (all in [0, 2^32) but the last, which is
// >= 0 and may be wider) bit by bit.
struct Magnitude {
  const std::array<std::int64_t, ExactSum::kDigits>& digit;

  int digit_of(int bit) const { return std::min(bit / ExactSum::kDigitBits, ExactSum::kDigits - 1); }
  bool bit(int b) const {
    const int d = digit_of(b);
    return ((static_cast<std::uint64_t>(digit[static_cast<std::size_t>(d)]) >> (b - d * ExactSum::kDigitBits)) & 1u) !=
           0;
  }
  bool any_bit_below(int b) const {
    if (b <= 0) return false;
    const int d = digit_of(b);
    for (int k = 0; k < d; ++k)
      if (digit[static_cast<std::size_t>(k)] != 0) return true;
    const int within = b - d * ExactSum::kDigitBits;
    return (static_cast<std::uint64_t>(digit[static_cast<std::size_t>(d)]) & ((std::uint64_t{1} << within) - 1)) != 0;
  }
  // The index of the highest set bit, -1 for zero.
  int highest_bit() const {
    for (int d = ExactSum::kDigits - 1; d >= 0; --d) {
      const auto v = static_cast<std::uint64_t>(digit[static_cast<std::size_t>(d)]);
      if (v != 0) return d * ExactSum::kDigitBits + 63 - std::countl_zero(v);
    }
    return -1;
  }
};

}  // namespace

double ExactSum::value() const {
  if (nans_ > 0 || (positive_infinities_ > 0 && negative_infinities_ > 0))
    return std::numeric_limits<double>::quiet_NaN();
  if (positive_infinities_ > 0) return std::numeric_limits<double>::infinity();
  if (negative_infinities_ > 0) return -std::numeric_limits<double>::infinity();
  ExactSum m = *this;
  m.propagate_carries();
  const bool negative = m.digit_[kDigits - 1] < 0;
  if (negative) {
    for (auto& d : m.digit_) d = -d;
    m.propagate_carries();
  }
  const Magnitude magnitude{m.digit_};
  const int top = magnitude.highest_bit();
  if (top < 0) return 0.0;
  // The 53 bits from the top, rounded to nearest, ties to even, by the next bit and those below.
  const int low = std::max(0, top - 52);
  std::uint64_t significand = 0;
  for (int b = top; b >= low; --b) significand = (significand << 1) | (magnitude.bit(b) ? 1u : 0u);
  if (low > 0 && magnitude.bit(low - 1) && (magnitude.any_bit_below(low - 1) || (significand & 1u) != 0))
    ++significand;  // may reach 2^53: still exact, and ldexp gives inf past the largest double
  // significand 2^(low - 1074): a normal double when low > 0 (top >= 53), else the exact integer
  // multiple of 2^-1074 (a subnormal or small normal).
  const double rounded = std::ldexp(static_cast<double>(significand), low - 1074);
  return negative ? -rounded : rounded;
}

ExactSum::Wire ExactSum::wire() const {
  ExactSum m = *this;
  m.propagate_carries();
  Wire w{};
  std::copy(m.digit_.begin(), m.digit_.end(), w.begin());
  w[kDigits] = nans_;
  w[kDigits + 1] = positive_infinities_;
  w[kDigits + 2] = negative_infinities_;
  return w;
}

ExactSum ExactSum::from_wire(std::span<const std::int64_t, kWireWords> wire) {
  ExactSum s;
  std::copy(wire.begin(), wire.begin() + kDigits, s.digit_.begin());
  s.nans_ = wire[kDigits];
  s.positive_infinities_ = wire[kDigits + 1];
  s.negative_infinities_ = wire[kDigits + 2];
  s.propagate_carries();
  return s;
}

}  // namespace mppm::solver
