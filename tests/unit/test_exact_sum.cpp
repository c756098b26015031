// The exact accumulator (solver/exact_sum.hpp): exact over the whole double range, rounded once to
// nearest (ties to even), and independent of the order of the terms and of how they were split and
// merged.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "solver/exact_sum.hpp"

namespace {

using mppm::solver::ExactSum;

double sum_of(const std::vector<double>& terms) {
  ExactSum s;
  for (const double x : terms) s += x;
  return s.value();
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Terms m 2^(e - 52) with |m| < 2^53 and e in [-20, 20]: their exact sum is an integer in units of
// 2^-72 far inside 128 bits, and the compiler's int128 -> double conversion rounds it to nearest,
// ties to even: an independent reference.
__extension__ typedef __int128 Int128;
struct ReferenceTerms {
  std::vector<double> terms;
  Int128 exact = 0;  // in units of 2^-72
};
ReferenceTerms reference_terms(std::mt19937_64& rng, int count) {
  std::uniform_int_distribution<std::int64_t> significand(-(std::int64_t{1} << 53) + 1, (std::int64_t{1} << 53) - 1);
  std::uniform_int_distribution<int> exponent(-20, 20);
  ReferenceTerms r;
  for (int k = 0; k < count; ++k) {
    const std::int64_t m = significand(rng);
    const int e = exponent(rng);
    r.terms.push_back(std::ldexp(static_cast<double>(m), e - 52));
    r.exact += static_cast<Int128>(m) << (e + 20);
  }
  return r;
}
double reference_value(Int128 exact) { return std::ldexp(static_cast<double>(exact), -72); }

TEST(ExactSum, RoundsRandomSumsAsTheExactIntegerSum) {
  std::mt19937_64 rng(12345);
  for (int trial = 0; trial < 2000; ++trial) {
    const ReferenceTerms r = reference_terms(rng, 1 + trial % 40);
    EXPECT_EQ(bits(sum_of(r.terms)), bits(reference_value(r.exact))) << "trial " << trial;
  }
}

// Terms that cancel exactly, and a remainder 60 binary orders below them: the remainder, exactly.
TEST(ExactSum, RecoversASmallRemainderAfterCancellation) {
  std::mt19937_64 rng(777);
  for (int trial = 0; trial < 2000; ++trial) {
    ReferenceTerms r = reference_terms(rng, 10);
    const std::vector<double> first = r.terms;
    for (const double x : first) r.terms.push_back(-x);  // cancels exactly
    std::uniform_int_distribution<std::int64_t> small(-1000, 1000);
    const std::int64_t extra = small(rng);
    r.terms.push_back(std::ldexp(static_cast<double>(extra), -72));
    r.exact = extra;
    std::shuffle(r.terms.begin(), r.terms.end(), rng);
    EXPECT_EQ(bits(sum_of(r.terms)), bits(reference_value(r.exact))) << "trial " << trial;
  }
}

TEST(ExactSum, RoundsHalfwayCasesToEven) {
  const double ulp_half = std::ldexp(1.0, -53);                                   // half an ulp of 1
  EXPECT_EQ(sum_of({1.0, ulp_half}), 1.0);                                        // tie, 1 is even
  EXPECT_EQ(sum_of({1.0, ulp_half, std::ldexp(1.0, -200)}), 1.0 + 2 * ulp_half);  // above the tie
  EXPECT_EQ(sum_of({1.0, ulp_half, -std::ldexp(1.0, -200)}), 1.0);                // below the tie
  const double odd = 1.0 + 2 * ulp_half;                                          // last bit set
  EXPECT_EQ(sum_of({odd, ulp_half}), 1.0 + 4 * ulp_half);                         // tie, rounds up to even
  EXPECT_EQ(sum_of({-odd, -ulp_half}), -(1.0 + 4 * ulp_half));                    // the same, negative
}

TEST(ExactSum, KeepsTheWholeRangeWhereDoublesLoseIt) {
  EXPECT_EQ(sum_of({1e308, 1.0, -1e308}), 1.0);
  EXPECT_EQ(sum_of({DBL_MAX, DBL_MAX, -DBL_MAX}), DBL_MAX);  // the running double sum overflows
  EXPECT_EQ(sum_of({DBL_MAX, DBL_MAX}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(sum_of({-DBL_MAX, -DBL_MAX}), -std::numeric_limits<double>::infinity());
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(sum_of({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(sum_of({DBL_MIN, -tiny}), DBL_MIN - tiny);  // normal minus subnormal: exact
  EXPECT_EQ(sum_of({1e300, tiny, -1e300}), tiny);
  EXPECT_EQ(sum_of({}), 0.0);
  EXPECT_EQ(sum_of({0.0, -0.0}), 0.0);
}

TEST(ExactSum, PropagatesNaNAndInfinitiesAsIEEEAdditionDoes) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(sum_of({1.0, inf, 2.0}), inf);
  EXPECT_EQ(sum_of({-inf, DBL_MAX}), -inf);
  EXPECT_TRUE(std::isnan(sum_of({inf, -inf})));
  EXPECT_TRUE(std::isnan(sum_of({1.0, std::numeric_limits<double>::quiet_NaN()})));
}

// Any order, any split into parts merged in any order: the same bits. Terms over 600 binary
// orders of magnitude, so that a running double sum would depend on the order.
TEST(ExactSum, DoesNotDependOnOrderSplitOrMerge) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<double> terms(5000);
  for (double& x : terms) x = std::ldexp(unit(rng), exponent(rng));
  const std::uint64_t expected = bits(sum_of(terms));
  for (int trial = 0; trial < 20; ++trial) {
    std::shuffle(terms.begin(), terms.end(), rng);
    std::uniform_int_distribution<int> part_count(1, 50);
    std::vector<ExactSum> parts(static_cast<std::size_t>(part_count(rng)));
    std::uniform_int_distribution<std::size_t> which(0, parts.size() - 1);
    for (const double x : terms) parts[which(rng)] += x;
    std::shuffle(parts.begin(), parts.end(), rng);
    ExactSum merged;
    for (const ExactSum& part : parts) merged += part;
    EXPECT_EQ(bits(merged.value()), expected) << "trial " << trial;
  }
}

// The wire form summed as integers (what MPI_SUM on int64 does) is the merged accumulator.
TEST(ExactSum, WiresSummedAsIntegersMergeExactly) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-1074, 1000);
  std::vector<ExactSum> parts(7);
  ExactSum all;
  for (int k = 0; k < 3000; ++k) {
    const double x = std::ldexp(unit(rng), exponent(rng));
    parts[static_cast<std::size_t>(k) % parts.size()] += x;
    all += x;
  }
  parts[3] += std::numeric_limits<double>::infinity();
  ExactSum::Wire total{};
  for (const ExactSum& part : parts) {
    const ExactSum::Wire w = part.wire();
    for (int i = 0; i < ExactSum::kWireWords; ++i) total[static_cast<std::size_t>(i)] += w[static_cast<std::size_t>(i)];
  }
  EXPECT_EQ(ExactSum::from_wire(total).value(), std::numeric_limits<double>::infinity());
  parts[3] = ExactSum{};
  all = ExactSum{};
  total = {};
  for (int k = 0; k < 3000; ++k) {
    const double x = std::ldexp(unit(rng), exponent(rng) / 4);
    parts[static_cast<std::size_t>(k) % parts.size()] += x;
    all += x;
  }
  for (const ExactSum& part : parts) {
    const ExactSum::Wire w = part.wire();
    for (int i = 0; i < ExactSum::kWireWords; ++i) total[static_cast<std::size_t>(i)] += w[static_cast<std::size_t>(i)];
  }
  ExactSum merged;
  for (const ExactSum& part : parts) merged += part;
  EXPECT_EQ(bits(ExactSum::from_wire(total).value()), bits(merged.value()));
}

// Many terms whose digits carry at every addition (all bits of the significand set).
TEST(ExactSum, CarriesAcrossDigitsExactly) {
  const double ones = std::ldexp(static_cast<double>((std::int64_t{1} << 53) - 1), -20);  // 2^33 - 2^-20
  ExactSum s;
  const int count = 1 << 20;
  for (int k = 0; k < count; ++k) s += ones;
  // count * ones = 2^20 (2^53 - 1) 2^-20 = 2^53 - 1: exact in a double.
  EXPECT_EQ(s.value(), static_cast<double>((std::int64_t{1} << 53) - 1));
  for (int k = 0; k < count; ++k) s -= ones;
  s += std::ldexp(1.0, -1074);
  EXPECT_EQ(s.value(), std::ldexp(1.0, -1074));
}

}  // namespace
