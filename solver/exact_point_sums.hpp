// Sums over the owned points that do not depend on the thread count nor, in a distributed run, on
// the partition: each thread adds its points' terms to exact accumulators (exact_sum.hpp), which
// are merged (across processes too) and rounded once. The energy rows, the fluid's energy and
// volume and the critical step's inner products use it.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "solver/exact_sum.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/point_data.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

// Enough chunks for every thread of a large machine to get several (the points' costs differ:
// a chunk of crack tips costs more than one of intact lattice).
inline constexpr std::size_t kPointSumChunks = 64;

template <int K>
using ExactSums = std::array<ExactSum, K>;

// add_range(lo, hi, acc) adds the K terms of the owned points lo..hi-1 of `p` to acc[0..K)
// (acc[k] += term; a range, so that a caller can walk a sorted list alongside), on every thread when
// they are many. Returns the K sums, rounded once, in a distributed run over all processes
// (PointData::processes): the same bits on every process.
template <int K, class AddRange>
std::array<double, K> exact_point_sums(const PointData& p, AddRange&& add_range) {
  const std::size_t n = p.owned;
  const ProcessGroup* processes = p.processes;
  ExactSums<K> total;
  const auto chunks = static_cast<std::ptrdiff_t>(kPointSumChunks);
#pragma omp parallel if (thread_point_loop(n))
  {
    ExactSums<K> acc;
#pragma omp for schedule(dynamic) nowait
    for (std::ptrdiff_t chunk = 0; chunk < chunks; ++chunk) {
      const std::size_t lo = n * static_cast<std::size_t>(chunk) / kPointSumChunks;
      const std::size_t hi = n * static_cast<std::size_t>(chunk + 1) / kPointSumChunks;
      add_range(lo, hi, acc);
    }
#pragma omp critical(mppm_exact_point_sums)
    for (int k = 0; k < K; ++k) total[k] += acc[k];  // exact: the merge order does not matter
  }
  std::array<double, K> sum{};
  if (processes) {
    const std::vector<double> global = processes->sum(total);
    std::copy(global.begin(), global.end(), sum.begin());
    return sum;
  }
  for (int k = 0; k < K; ++k) sum[k] = total[k].value();
  return sum;
}

}  // namespace mppm::solver
