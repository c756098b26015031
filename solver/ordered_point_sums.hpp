// Sums over the owned points whose rounding does not depend on the thread count: the points are
// cut into kOrderedSumChunks contiguous chunks fixed by the point count alone, each chunk is
// summed in index order (the chunks in parallel), and the chunk sums are added in chunk order.
// The energy rows use it: summed serially, their per-point work (a stress evaluation per point)
// ran on one thread while the others waited at the next barrier.
#pragma once
#include <array>
#include <cstddef>

namespace mppm::solver {

// Enough chunks for every thread of a large machine to get several; few enough that the partial
// sums live on the stack (no allocation on the steps that report energies).
inline constexpr std::size_t kOrderedSumChunks = 64;

// add_range(lo, hi, acc) adds the K terms of the points lo..hi-1, in index order, to acc[0..K)
// (a range, so that a caller can walk a sorted list alongside). Returns the K sums.
template <int K, class AddRange>
std::array<double, K> ordered_point_sums(std::size_t n, bool threaded, AddRange&& add_range) {
  std::array<std::array<double, K>, kOrderedSumChunks> partial{};
  const auto chunks = static_cast<std::ptrdiff_t>(kOrderedSumChunks);
#pragma omp parallel for schedule(static) if (threaded)
  for (std::ptrdiff_t chunk = 0; chunk < chunks; ++chunk) {
    const std::size_t lo = n * static_cast<std::size_t>(chunk) / kOrderedSumChunks;
    const std::size_t hi = n * static_cast<std::size_t>(chunk + 1) / kOrderedSumChunks;
    std::array<double, K> acc{};
    add_range(lo, hi, acc);
    partial[static_cast<std::size_t>(chunk)] = acc;
  }
  std::array<double, K> sum{};
  for (const auto& chunk : partial)
    for (int k = 0; k < K; ++k) sum[k] += chunk[k];
  return sum;
}

}  // namespace mppm::solver
