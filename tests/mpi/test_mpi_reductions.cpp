// Run under mpirun with 1 to 4 processes (tests/mpi.cmake): the global sums of a distributed run
// (solver/process_group.hpp) give every process the bits of the one-process sum, however the terms
// are split among the processes and their threads; every process computes the same partition, and
// the parts with their ghosts cover the lattice.
#include <gtest/gtest.h>
#include <mpi.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "solver/coordinate_bisection.hpp"
#include "solver/exact_sum.hpp"
#include "solver/halo_points.hpp"
#include "solver/process_group.hpp"

namespace {

using namespace mppm::solver;

// The same terms on every process: 20 000 doubles over 800 binary orders of magnitude, so that a
// double sum would round differently for every split.
std::vector<double> shared_terms() {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-400, 400);
  std::vector<double> terms(20000);
  for (double& x : terms) x = std::ldexp(unit(rng), exponent(rng));
  return terms;
}

// Process r of n takes an uneven contiguous block (as a partition would), summed on the threads.
ExactSum local_sum(const std::vector<double>& terms, int rank, int size) {
  auto edge = [&](int r) {
    return terms.size() * static_cast<std::size_t>(r) * static_cast<std::size_t>(r) /
           (static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  };
  const auto lo = static_cast<std::int64_t>(edge(rank)), hi = static_cast<std::int64_t>(edge(rank + 1));
  ExactSum total;
#pragma omp parallel
  {
    ExactSum mine;
#pragma omp for schedule(dynamic, 97)
    for (std::int64_t k = lo; k < hi; ++k) mine += terms[static_cast<std::size_t>(k)];
#pragma omp critical
    total += mine;
  }
  return total;
}

TEST(MpiReductions, ExactSumsGiveEveryProcessTheOneProcessBits) {
  const ProcessGroup group = ProcessGroup::world();
  const std::vector<double> terms = shared_terms();
  ExactSum serial;
  for (const double x : terms) serial += x;
  const ExactSum local = local_sum(terms, group.rank(), group.size());
  const std::vector<ExactSum> pair{local, ExactSum(1.0)};
  const std::vector<double> global = group.sum(pair);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(global[0]), std::bit_cast<std::uint64_t>(serial.value()))
      << "rank " << group.rank() << " of " << group.size();
  EXPECT_EQ(global[1], static_cast<double>(group.size()));
  // Non-finite terms on one process reach all.
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(group.sum(ExactSum(group.rank() == group.size() - 1 ? inf : 1.0)), inf);
}

TEST(MpiReductions, AnyAgreesOnEveryProcess) {
  const ProcessGroup group = ProcessGroup::world();
  EXPECT_FALSE(group.any(false));
  EXPECT_TRUE(group.any(group.rank() == group.size() - 1));
}

TEST(MpiReductions, EveryProcessComputesThePartitionAndItsGhostsCoverTheLattice) {
  const ProcessGroup group = ProcessGroup::world();
  const int D = 3, n_side = 9;
  std::vector<double> position;
  std::vector<std::int64_t> id, weight;
  for (int z = 0; z < n_side; ++z)
    for (int y = 0; y < n_side; ++y)
      for (int x = 0; x < n_side; ++x) {
        position.insert(position.end(), {double(x), double(y), double(z)});
        id.push_back(static_cast<std::int64_t>(id.size()));
        weight.push_back(1 + (x + y + z) % 3);
      }
  const auto part = coordinate_bisection({D, position, weight, id}, group.size());
  // The same partition everywhere: its parts summed with weights by position agree exactly.
  ExactSum signature;
  for (std::size_t i = 0; i < part.size(); ++i)
    signature += std::ldexp(static_cast<double>(part[i]), static_cast<int>(i % 50));
  const double mine = signature.value();
  double lowest = 0.0, highest = 0.0;
  MPI_Allreduce(&mine, &lowest, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&mine, &highest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(lowest, highest);
  // Each process owns its part; the owned points add up to the lattice, and every ghost is another's.
  ExactSum owned;
  for (const std::int32_t p : part) owned += p == group.rank() ? 1.0 : 0.0;
  EXPECT_EQ(group.sum(owned), static_cast<double>(part.size()));
  const auto halo = halo_points({D, position.data(), part.size()}, part, group.rank(), 3.05, 1.0);
  for (const std::size_t j : halo) EXPECT_NE(part[j], group.rank());
  if (group.size() > 1) {
    EXPECT_FALSE(halo.empty());
  }
}

}  // namespace
