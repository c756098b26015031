// The products t = A xi + C U of a bond in the force kernel's pass 2 (docs/theory.md sections 4
// and 7), A a tensor in rows (row-major), C a symmetric one packed (symmetric_tensor.hpp):
//   - the neighbour's share of the force, A_j xi + C:K_j^-1 U, added to point i's force as V_j t
//     (the kernel also needs t itself for the moment's 1/2 xi x t): add_neighbour_share;
//   - the pair force of the bond work's increment, with both ends' tensors and both evaluations
//     summed, (A_i0 + A_i + A_j0 + A_j) xi + (Ck_i + Ck_j)(U0 + U): pair_force_sum.
// Per row r the scalar form sums fma(A[r][c], xi_c, .) then fma(C[r][c], U_c, .) for c = 0, 1, ...
// from zero (each entry of A or C, and each U_c, the sum of its two terms first in the pair form).
// In 2-D with vector lanes (vector_lanes.hpp) the two rows are the two lanes of one vector: the
// columns of A are two unpack operations of its rows, and the columns of a packed C are plain
// loads (its entries are 00, 01, 11). Each lane does its row's scalar operations in their order,
// so both forms give the same bits (`BondProducts`, tests/unit/test_solver_bond_sums.cpp). 3-D
// keeps the scalar form: its 3 rows in 4 lanes did not make pass 2 faster.
#pragma once

#include "solver/multiply_add.hpp"
#include "solver/symmetric_tensor.hpp"
#include "solver/vector_lanes.hpp"

namespace mppm::solver::kernel {

template <int D>
[[gnu::always_inline]] inline void neighbour_share_scalar(const double* aj, const double* ckj, const double* xi,
                                                          const double* U, double vj, double* t, double* force) {
  for (int r = 0; r < D; ++r) {
    double sum = 0.0;
    for (int col = 0; col < D; ++col) {
      sum = multiply_add(aj[r * D + col], xi[col], sum);
      sum = multiply_add(ckj[symmetric_index<D>(r, col)], U[col], sum);
    }
    t[r] = sum;
    force[r] = multiply_add(vj, sum, force[r]);
  }
}

template <int D>
[[gnu::always_inline]] inline void pair_force_sum_scalar(const double* ai, const double* aj, const double* cki,
                                                         const double* ckj, const double* xi, const double* U0,
                                                         const double* U, double* both) {
  for (int r = 0; r < D; ++r) {
    double sum = 0.0;
    for (int col = 0; col < D; ++col) {
      sum = multiply_add(ai[r * D + col] + aj[r * D + col], xi[col], sum);
      const int s = symmetric_index<D>(r, col);
      sum = multiply_add(cki[s] + ckj[s], U0[col] + U[col], sum);
    }
    both[r] = sum;
  }
}

#ifdef MPPM_VECTOR_LANES
// 2-D: t's two rows as lanes, from A's rows and C's packed entries 00 01 (ck_lo) and 01 11 (ck_hi).
[[gnu::always_inline]] inline __m128d bond_product_lanes_2d(__m128d a_row0, __m128d a_row1, __m128d ck_lo,
                                                            __m128d ck_hi, double xi0, double xi1, double U0,
                                                            double U1) {
  __m128d sum = _mm_fmadd_pd(_mm_unpacklo_pd(a_row0, a_row1), _mm_set1_pd(xi0), _mm_setzero_pd());
  sum = _mm_fmadd_pd(ck_lo, _mm_set1_pd(U0), sum);
  sum = _mm_fmadd_pd(_mm_unpackhi_pd(a_row0, a_row1), _mm_set1_pd(xi1), sum);
  return _mm_fmadd_pd(ck_hi, _mm_set1_pd(U1), sum);
}

[[gnu::always_inline]] inline void neighbour_share_vector_2d(const double* aj, const double* ckj, const double* xi,
                                                             const double* U, double vj, double* t, double* force) {
  const __m128d sum = bond_product_lanes_2d(_mm_loadu_pd(aj), _mm_loadu_pd(aj + 2), _mm_loadu_pd(ckj),
                                            _mm_loadu_pd(ckj + 1), xi[0], xi[1], U[0], U[1]);
  _mm_storeu_pd(t, sum);
  _mm_storeu_pd(force, _mm_fmadd_pd(_mm_set1_pd(vj), sum, _mm_loadu_pd(force)));
}

[[gnu::always_inline]] inline void pair_force_sum_vector_2d(const double* ai, const double* aj, const double* cki,
                                                            const double* ckj, const double* xi, const double* U0,
                                                            const double* U, double* both) {
  const __m128d a_row0 = _mm_add_pd(_mm_loadu_pd(ai), _mm_loadu_pd(aj));
  const __m128d a_row1 = _mm_add_pd(_mm_loadu_pd(ai + 2), _mm_loadu_pd(aj + 2));
  const __m128d ck_lo = _mm_add_pd(_mm_loadu_pd(cki), _mm_loadu_pd(ckj));
  const __m128d ck_hi = _mm_add_pd(_mm_loadu_pd(cki + 1), _mm_loadu_pd(ckj + 1));
  _mm_storeu_pd(both, bond_product_lanes_2d(a_row0, a_row1, ck_lo, ck_hi, xi[0], xi[1], U0[0] + U[0], U0[1] + U[1]));
}
#endif

// The kernel's forms: the 2-D lanes where the instruction set has them, else the scalar loops.
template <int D>
[[gnu::always_inline]] inline void add_neighbour_share(const double* aj, const double* ckj, const double* xi,
                                                       const double* U, double vj, double* t, double* force) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 2) {
    neighbour_share_vector_2d(aj, ckj, xi, U, vj, t, force);
    return;
  }
#endif
  neighbour_share_scalar<D>(aj, ckj, xi, U, vj, t, force);
}

template <int D>
[[gnu::always_inline]] inline void pair_force_sum(const double* ai, const double* aj, const double* cki,
                                                  const double* ckj, const double* xi, const double* U0,
                                                  const double* U, double* both) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 2) {
    pair_force_sum_vector_2d(ai, aj, cki, ckj, xi, U0, U, both);
    return;
  }
#endif
  pair_force_sum_scalar<D>(ai, aj, cki, ckj, xi, U0, U, both);
}

}  // namespace mppm::solver::kernel
