// When a loop is worth running on several threads. Small lattices are faster on one thread (a
// parallel region costs microseconds, and far more on an oversubscribed machine); the results
// are the same bits either way, since every loop writes per-point data only.
#pragma once
#include <cstddef>

namespace mppm::solver {

struct ParallelThresholds {
  std::size_t bonds = 100000;  // loops over bonds (force kernel, families, shape tensors, cuts)
  std::size_t points = 4096;   // loops doing a few operations per point (integrator)
  std::size_t blocks = 64;     // loops of per-point stiffness blocks (an eigenvalue problem over
                               // the point's bonds each: the breakage update's stability check)
};

// Process-wide thresholds; tests lower them to exercise the threaded paths on small lattices.
inline ParallelThresholds& parallel_thresholds() {
  static ParallelThresholds thresholds;
  return thresholds;
}

inline bool thread_bond_loop(std::size_t bonds) { return bonds >= parallel_thresholds().bonds; }
inline bool thread_point_loop(std::size_t points) { return points >= parallel_thresholds().points; }
inline bool thread_block_loop(std::size_t blocks) { return blocks >= parallel_thresholds().blocks; }

}  // namespace mppm::solver
