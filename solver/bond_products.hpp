// The products t = A xi + C U of a bond in the force kernel's pass 2 (docs/theory.md sections 4
// and 7), A a tensor stored by columns (point_data.hpp), C a symmetric one packed
// (symmetric_tensor.hpp):
//   - the neighbour's share of the force, A_j xi + C:K_j^-1 U, added to point i's force as V_j t
//     (the kernel also needs t itself for the moment's 1/2 xi x t): add_neighbour_share;
//   - the pair force of the bond work's increment, with both ends' tensors and both evaluations
//     summed, (A_i0 + A_i + A_j0 + A_j) xi + (Ck_i + Ck_j)(U0 + U): pair_force_sum;
// and their micro-polar counterparts, the neighbour's share of the moment, V_j [Q_j xi + g_j Om +
// 1/2 xi x t] (add_neighbour_moment), and the pair moment of the bond work,
// (Q_i0 + Q_i + Q_j0 + Q_j) xi + (g_i + g_j)(Om0 + Om) with Om - Om0 (pair_moment_sum).
// Per row r the scalar form sums fma(A[r][c], xi_c, .) then fma(C[r][c], U_c, .) for c = 0, 1, ...
// from zero (each entry of A or C, and each U_c, the sum of its two terms first in the pair form).
// With vector lanes (vector_lanes.hpp) the rows are the lanes of one vector, and each lane does its
// row's scalar operations in their order, so both forms give the same bits (`BondProducts`,
// tests/unit/test_solver_bond_products.cpp). A column of A or Q is one load, as they are stored by
// columns; in 2-D those of a packed C (entries 00 01 11) are plain loads too; in 3-D, lanes 0-2 of
// 4, the columns of C come from two loads of its packed entries (00 01 02 11 and 02 11 12 22), and
// the moments' rows are lanes 0-2 too (in 2-D the moment has one component, and stays scalar).
// The 3-D forms write 4 doubles to t, force, moment and the pair force and moment (the fourth is
// not used): their arrays are lane_slots long (vector_lanes.hpp).
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
      sum = multiply_add(aj[col * D + r], xi[col], sum);
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
      sum = multiply_add(ai[col * D + r] + aj[col * D + r], xi[col], sum);
      const int s = symmetric_index<D>(r, col);
      sum = multiply_add(cki[s] + ckj[s], U0[col] + U[col], sum);
    }
    both[r] = sum;
  }
}

// xi x t (its z component in 2-D), added with a factor: fma(factor, fma(xi_b, t_c, -xi_c t_b), .).
template <int D>
[[gnu::always_inline]] inline void add_cross(const double* xi, const double* t, double factor, double* out) {
  if constexpr (D == 2) {
    out[0] = multiply_add(factor, multiply_add(xi[0], t[1], -xi[1] * t[0]), out[0]);
  } else {
    out[0] = multiply_add(factor, multiply_add(xi[1], t[2], -xi[2] * t[1]), out[0]);
    out[1] = multiply_add(factor, multiply_add(xi[2], t[0], -xi[0] * t[2]), out[1]);
    out[2] = multiply_add(factor, multiply_add(xi[0], t[1], -xi[1] * t[0]), out[2]);
  }
}

// Per rotation component r: fma(V_j, g_j (w_j - w_i)_r + sum_c Q_j[r][c] xi_c, moment_r) (the Q
// terms fused in column order), then the cross product with t.
template <int D, int R>
[[gnu::always_inline]] inline void neighbour_moment_scalar(const double* qj, double gj, const double* wi,
                                                           const double* wj, const double* xi, const double* t,
                                                           double vj, double* moment) {
  for (int r = 0; r < R; ++r) {
    double sum = gj * (wj[r] - wi[r]);
    for (int col = 0; col < D; ++col) sum = multiply_add(qj[col * R + r], xi[col], sum);
    moment[r] = multiply_add(vj, sum, moment[r]);
  }
  add_cross<D>(xi, t, 0.5 * vj, moment);
}

// Per rotation component r: Om_r = (w_j - w_i)_r, Om0_r as Om_r of the previous state; the pair
// moment g (Om0 + Om)_r + sum_c (Q_i[r][c] + Q_j[r][c]) xi_c (fused in column order), and Om - Om0.
template <int D, int R>
[[gnu::always_inline]] inline void pair_moment_sum_scalar(const double* qi, const double* qj, double g,
                                                          const double* wi, const double* wj, const double* wi0,
                                                          const double* wj0, const double* xi, double* both,
                                                          double* change) {
  for (int r = 0; r < R; ++r) {
    const double om = wj[r] - wi[r], om0 = wj0[r] - wi0[r];
    double sum = g * (om0 + om);
    for (int col = 0; col < D; ++col) sum = multiply_add(qi[col * R + r] + qj[col * R + r], xi[col], sum);
    both[r] = sum;
    change[r] = om - om0;
  }
}

#ifdef MPPM_VECTOR_LANES
// 2-D: t's two rows as lanes, from A's columns and C's packed entries 00 01 (ck_lo) and 01 11 (ck_hi).
[[gnu::always_inline]] inline __m128d bond_product_lanes_2d(__m128d a_col0, __m128d a_col1, __m128d ck_lo,
                                                            __m128d ck_hi, double xi0, double xi1, double U0,
                                                            double U1) {
  __m128d sum = _mm_fmadd_pd(a_col0, _mm_set1_pd(xi0), _mm_setzero_pd());
  sum = _mm_fmadd_pd(ck_lo, _mm_set1_pd(U0), sum);
  sum = _mm_fmadd_pd(a_col1, _mm_set1_pd(xi1), sum);
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
  const __m128d a_col0 = _mm_add_pd(_mm_loadu_pd(ai), _mm_loadu_pd(aj));
  const __m128d a_col1 = _mm_add_pd(_mm_loadu_pd(ai + 2), _mm_loadu_pd(aj + 2));
  const __m128d ck_lo = _mm_add_pd(_mm_loadu_pd(cki), _mm_loadu_pd(ckj));
  const __m128d ck_hi = _mm_add_pd(_mm_loadu_pd(cki + 1), _mm_loadu_pd(ckj + 1));
  _mm_storeu_pd(both, bond_product_lanes_2d(a_col0, a_col1, ck_lo, ck_hi, xi[0], xi[1], U0[0] + U[0], U0[1] + U[1]));
}

// 3-D: the columns of A or Q (lanes 0-2), each read as 4 doubles from the tensor stored by columns
// (lane 3 holds the next column's first entry, or 0: it is not used), the third masked, so that
// the last point's tensor is read without touching memory past it.
struct Columns3 {
  __m256d c0, c1, c2;
};
[[gnu::always_inline]] inline Columns3 load_columns(const double* a) {
  return {_mm256_loadu_pd(a), _mm256_loadu_pd(a + 3), load3(a + 6)};
}
// The columns of the sum of two tensors stored by columns.
[[gnu::always_inline]] inline Columns3 load_column_sums(const double* a, const double* b) {
  return {_mm256_add_pd(_mm256_loadu_pd(a), _mm256_loadu_pd(b)),
          _mm256_add_pd(_mm256_loadu_pd(a + 3), _mm256_loadu_pd(b + 3)), _mm256_add_pd(load3(a + 6), load3(b + 6))};
}
// The columns of a packed symmetric C from lo = (00 01 02 11) and hi = (02 11 12 22): lo itself,
// (01 11 12) and (02 12 22).
[[gnu::always_inline]] inline Columns3 columns_of_packed(__m256d lo, __m256d hi) {
  return {lo, _mm256_blend_pd(_mm256_permute4x64_pd(lo, 0xFD), hi, 0x4), _mm256_permute4x64_pd(hi, 0xF8)};
}
[[gnu::always_inline]] inline __m256d bond_product_lanes_3d(const Columns3& a, const Columns3& c, const double* xi,
                                                            double U0, double U1, double U2) {
  __m256d sum = _mm256_fmadd_pd(a.c0, _mm256_set1_pd(xi[0]), _mm256_setzero_pd());
  sum = _mm256_fmadd_pd(c.c0, _mm256_set1_pd(U0), sum);
  sum = _mm256_fmadd_pd(a.c1, _mm256_set1_pd(xi[1]), sum);
  sum = _mm256_fmadd_pd(c.c1, _mm256_set1_pd(U1), sum);
  sum = _mm256_fmadd_pd(a.c2, _mm256_set1_pd(xi[2]), sum);
  return _mm256_fmadd_pd(c.c2, _mm256_set1_pd(U2), sum);
}

[[gnu::always_inline]] inline void neighbour_share_vector_3d(const double* aj, const double* ckj, const double* xi,
                                                             const double* U, double vj, double* t, double* force) {
  const Columns3 a = load_columns(aj);
  const Columns3 c = columns_of_packed(_mm256_loadu_pd(ckj), _mm256_loadu_pd(ckj + 2));
  const __m256d sum = bond_product_lanes_3d(a, c, xi, U[0], U[1], U[2]);
  _mm256_storeu_pd(t, sum);
  _mm256_storeu_pd(force, _mm256_fmadd_pd(_mm256_set1_pd(vj), sum, _mm256_loadu_pd(force)));
}

[[gnu::always_inline]] inline void pair_force_sum_vector_3d(const double* ai, const double* aj, const double* cki,
                                                            const double* ckj, const double* xi, const double* U0,
                                                            const double* U, double* both) {
  const Columns3 a = load_column_sums(ai, aj);
  const Columns3 c = columns_of_packed(_mm256_add_pd(_mm256_loadu_pd(cki), _mm256_loadu_pd(ckj)),
                                       _mm256_add_pd(_mm256_loadu_pd(cki + 2), _mm256_loadu_pd(ckj + 2)));
  _mm256_storeu_pd(both, bond_product_lanes_3d(a, c, xi, U0[0] + U[0], U0[1] + U[1], U0[2] + U[2]));
}

[[gnu::always_inline]] inline void neighbour_moment_vector_3d(const double* qj, double gj, const double* wi,
                                                              const double* wj, const double* xi, const double* t,
                                                              double vj, double* moment) {
  const Columns3 q = load_columns(qj);
  __m256d sum = _mm256_mul_pd(_mm256_set1_pd(gj), _mm256_sub_pd(load3(wj), load3(wi)));
  sum = _mm256_fmadd_pd(q.c0, _mm256_set1_pd(xi[0]), sum);
  sum = _mm256_fmadd_pd(q.c1, _mm256_set1_pd(xi[1]), sum);
  sum = _mm256_fmadd_pd(q.c2, _mm256_set1_pd(xi[2]), sum);
  const __m256d out = _mm256_fmadd_pd(_mm256_set1_pd(vj), sum, _mm256_loadu_pd(moment));
  // xi from the bond's scalars (just computed: a vector load would wait for their stores). The
  // scalar's (-xi_c) t_b and cross_lanes's -(xi_c t_b) are the same number.
  const __m256d x = _mm256_setr_pd(xi[0], xi[1], xi[2], 0.0);
  _mm256_storeu_pd(moment, _mm256_fmadd_pd(_mm256_set1_pd(0.5 * vj), cross_lanes(x, _mm256_loadu_pd(t)), out));
}

[[gnu::always_inline]] inline void pair_moment_sum_vector_3d(const double* qi, const double* qj, double g,
                                                             const double* wi, const double* wj, const double* wi0,
                                                             const double* wj0, const double* xi, double* both,
                                                             double* change) {
  const __m256d om = _mm256_sub_pd(load3(wj), load3(wi));
  const __m256d om0 = _mm256_sub_pd(load3(wj0), load3(wi0));
  const Columns3 q = load_column_sums(qi, qj);
  __m256d sum = _mm256_mul_pd(_mm256_set1_pd(g), _mm256_add_pd(om0, om));
  sum = _mm256_fmadd_pd(q.c0, _mm256_set1_pd(xi[0]), sum);
  sum = _mm256_fmadd_pd(q.c1, _mm256_set1_pd(xi[1]), sum);
  sum = _mm256_fmadd_pd(q.c2, _mm256_set1_pd(xi[2]), sum);
  _mm256_storeu_pd(both, sum);
  _mm256_storeu_pd(change, _mm256_sub_pd(om, om0));
}
#endif

// The kernel's forms: the lanes where the instruction set has them, else the scalar loops. t, force
// and both hold lane_slots<D> doubles.
template <int D>
[[gnu::always_inline]] inline void add_neighbour_share(const double* aj, const double* ckj, const double* xi,
                                                       const double* U, double vj, double* t, double* force) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 2)
    neighbour_share_vector_2d(aj, ckj, xi, U, vj, t, force);
  else
    neighbour_share_vector_3d(aj, ckj, xi, U, vj, t, force);
#else
  neighbour_share_scalar<D>(aj, ckj, xi, U, vj, t, force);
#endif
}

template <int D>
[[gnu::always_inline]] inline void pair_force_sum(const double* ai, const double* aj, const double* cki,
                                                  const double* ckj, const double* xi, const double* U0,
                                                  const double* U, double* both) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 2)
    pair_force_sum_vector_2d(ai, aj, cki, ckj, xi, U0, U, both);
  else
    pair_force_sum_vector_3d(ai, aj, cki, ckj, xi, U0, U, both);
#else
  pair_force_sum_scalar<D>(ai, aj, cki, ckj, xi, U0, U, both);
#endif
}

// The moment forms: the 3-D lanes where the instruction set has them, else the scalar loops (2-D: one
// rotation component). moment, both and change hold lane_slots<R> doubles.
template <int D, int R>
[[gnu::always_inline]] inline void add_neighbour_moment(const double* qj, double gj, const double* wi, const double* wj,
                                                        const double* xi, const double* t, double vj, double* moment) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 3) {
    neighbour_moment_vector_3d(qj, gj, wi, wj, xi, t, vj, moment);
    return;
  }
#endif
  neighbour_moment_scalar<D, R>(qj, gj, wi, wj, xi, t, vj, moment);
}

template <int D, int R>
[[gnu::always_inline]] inline void pair_moment_sum(const double* qi, const double* qj, double g, const double* wi,
                                                   const double* wj, const double* wi0, const double* wj0,
                                                   const double* xi, double* both, double* change) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 3) {
    pair_moment_sum_vector_3d(qi, qj, g, wi, wj, wi0, wj0, xi, both, change);
    return;
  }
#endif
  pair_moment_sum_scalar<D, R>(qi, qj, g, wi, wj, wi0, wj0, xi, both, change);
}

}  // namespace mppm::solver::kernel
