// The bond sums of the force kernel's pass 1 (docs/theory.md sections 2-3), over the bonds that act
// (BondFamilies::acting; a bond that reached its critical work in this step still acts until
// update_after_breakage breaks it): S = sum_j V_j U_ij (x) xi, Sk = sum_j V_j (w_j - w_i) (x) xi,
// and the first moments s = sum_j V_j U_ij, m = sum_j V_j xi, sw = sum_j V_j (w_j - w_i), with which
// pass 1 forms point i's tensors and its own share of its force and moment.
// Where the instruction set has vectors and fused multiply-adds (AVX2 and FMA), a bond's components
// go through one vector operation each (bond_sums_vector: 4 lanes in 3-D; bond_sums_vector_2d: 2
// lanes in 2-D, without which the 2-D plate's damage step was a fifth slower). Every lane
// does the scalar loop's operations in its order (the fusions are written in both), so the two
// give the same bits; `BondSumsPath` pins that (tests/unit/test_solver_bond_sums.cpp).
#pragma once
#include <cstddef>
#include <cstdint>

#include "solver/bond_families.hpp"
#include "solver/bond_kinematics.hpp"
#include "solver/compiled_effects.hpp"
#include "solver/multiply_add.hpp"
#include "solver/point_data.hpp"
#include "solver/vector_lanes.hpp"

namespace mppm::solver::kernel {

template <int D, int R>
struct BondSums {
  double S[D * D];
  double Sk[R * D];
  double s[D];
  double m[D];
  double sw[R];
  // The 3-D lanes store 4 doubles for each 3 (bond_sums_vector): each store's fourth lane lands on
  // the next member, which is stored after it, and the last one's here.
  double lane_spill;
};

// The bond sums one bond at a time, in plain doubles (any dimension, any instruction set).
template <int D, class Effects, bool StoredXi>
[[gnu::always_inline]] inline void bond_sums_scalar(const PointData& p, const BondFamilies& f, std::size_t i,
                                                    BondSums<D, rotation_components<D>>& out) {
  constexpr int R = rotation_components<D>;
  constexpr bool polar = Effects::micropolar;
  constexpr int DD = D * D, RD = R * D;
  const double zero_rotation[3] = {0.0, 0.0, 0.0};
  const double* __restrict u = p.displacement.data();
  const double* __restrict w = polar ? p.rotation.data() : zero_rotation;
  const double* __restrict vol = p.volume.data();
  const double* __restrict xis = f.xi.data();
  const double* __restrict pos = p.position.data();
  const std::int32_t* __restrict nb = f.neighbor.data();
  double pos_i[D], ui[D], wi[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < D; ++a) pos_i[a] = pos[i * D + a];
  for (int a = 0; a < D; ++a) ui[a] = u[i * D + a];
  if constexpr (polar)
    for (int a = 0; a < R; ++a) wi[a] = w[i * R + a];
  // Locals, not the output struct: the compiler keeps them in registers.
  double S[DD] = {}, s[D] = {}, m[D] = {}, Sk[RD > 0 ? RD : 1] = {}, sw[R > 0 ? R : 1] = {};
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    BondView<D> bond;
    if (!read_bond<D, R, polar, Effects::damage, StoredXi>(b, nb, xis, pos, pos_i, vol, w, bond)) continue;
    const double* xi = bond.xi;
    const double vj = bond.vj;
    const double* wj = bond.wj;
    double U[D];
    composite_state<D, R, polar>(ui, u + bond.j * D, wi, wj, xi, U);
    for (int r = 0; r < D; ++r) {
      const double vu = vj * U[r];
      for (int col = 0; col < D; ++col) S[r * D + col] = multiply_add(vu, xi[col], S[r * D + col]);
      s[r] += vu;
      m[r] = multiply_add(vj, xi[r], m[r]);
    }
    if constexpr (polar)
      for (int r = 0; r < R; ++r) {
        const double om = vj * (wj[r] - wi[r]);
        for (int col = 0; col < D; ++col) Sk[r * D + col] = multiply_add(om, xi[col], Sk[r * D + col]);
        sw[r] += om;
      }
  }
  for (int k = 0; k < DD; ++k) out.S[k] = S[k];
  for (int r = 0; r < D; ++r) out.s[r] = s[r];
  for (int r = 0; r < D; ++r) out.m[r] = m[r];
  for (int k = 0; k < RD; ++k) out.Sk[k] = Sk[k];
  for (int r = 0; r < R; ++r) out.sw[r] = sw[r];
}

#ifdef MPPM_VECTOR_LANES
// Lane k of v in every lane.
template <int K>
[[gnu::always_inline]] inline __m256d lane(__m256d v) {
  return _mm256_permute4x64_pd(v, K * 0x55);
}

// The fourth lanes of r0, r1, r2 in lanes 0-2 (lane 3: r2's again).
[[gnu::always_inline]] inline __m256d fourth_lanes(__m256d r0, __m256d r1, __m256d r2) {
  const __m256d high01 = _mm256_unpackhi_pd(r0, r1);  // r0_1 r1_1 r0_3 r1_3
  return _mm256_permute2f128_pd(high01, _mm256_permute4x64_pd(r2, 0xFF), 0x31);
}
// 3-D, a bond's components as vector lanes. The scalar loop's operations per component:
// xi = pos_j - pos_i (or stored), U = (u_j - u_i) - [wm_1 xi_2 - wm_2 xi_1, ...] with wm = 1/2 (w_i + w_j)
// (composite_state: fma(wm_1, xi_2, -(wm_2 xi_1)) and its cyclic permutations), vu = V_j U,
// row r of S: fma(vu_r, xi, S_r), s + vu, m: fma(V_j, xi, m); om = V_j (w_j - w_i), row r of Sk:
// fma(om_r, xi, Sk_r), sw + om.
template <class Effects, bool StoredXi>
[[gnu::always_inline]] inline void bond_sums_vector(const PointData& p, const BondFamilies& f, std::size_t i,
                                                    BondSums<3, 3>& out) {
  constexpr bool polar = Effects::micropolar;
  const double* __restrict u = p.displacement.data();
  const double* __restrict w = polar ? p.rotation.data() : nullptr;
  const double* __restrict vol = p.volume.data();
  const double* __restrict xis = f.xi.data();
  const double* __restrict pos = p.position.data();
  const std::int32_t* __restrict nb = f.neighbor.data();
  // xi's fourth lane is 1 (pos_i's is -1, a neighbour's position loads with 0 there), so that the
  // fourth lane of row r of S, fma(vu_r, 1, .), sums s_r exactly as s_r + vu_r does, and that of
  // row r of Sk sums sw_r: two accumulators fewer, which keeps the others in registers (with them
  // the compiler kept some on the stack, a store and a load per bond).
  const __m256d fourth_lane_one = _mm256_set_pd(1.0, 0.0, 0.0, 0.0);
  const __m256d pos_i = _mm256_blend_pd(load3(pos + i * 3), _mm256_set_pd(-1.0, 0.0, 0.0, 0.0), 0x8);
  const __m256d ui = load3(u + i * 3);
  const __m256d wi = polar ? load3(w + i * 3) : _mm256_setzero_pd();
  const __m256d half = _mm256_set1_pd(0.5);
  __m256d S0 = _mm256_setzero_pd(), S1 = S0, S2 = S0, m = S0;
  __m256d K0 = S0, K1 = S0, K2 = S0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    const std::int32_t entry = nb[b];
    if constexpr (Effects::damage)
      if (entry < 0) continue;  // broken (BondFamilies::kBrokenBit)
    const auto j = static_cast<std::size_t>(entry);
    const __m256d xi =
        StoredXi ? _mm256_blend_pd(load3(xis + b * 3), fourth_lane_one, 0x8) : _mm256_sub_pd(load3(pos + j * 3), pos_i);
    const __m256d vj = _mm256_broadcast_sd(vol + j);
    __m256d U = _mm256_sub_pd(load3(u + j * 3), ui);
    __m256d wj = _mm256_setzero_pd();
    if constexpr (polar) {
      wj = load3(w + j * 3);
      const __m256d wm = _mm256_mul_pd(half, _mm256_add_pd(wi, wj));
      U = _mm256_sub_pd(U, cross_lanes(wm, xi));
    }
    const __m256d vu = _mm256_mul_pd(vj, U);
    S0 = _mm256_fmadd_pd(lane<0>(vu), xi, S0);
    S1 = _mm256_fmadd_pd(lane<1>(vu), xi, S1);
    S2 = _mm256_fmadd_pd(lane<2>(vu), xi, S2);
    m = _mm256_fmadd_pd(vj, xi, m);
    if constexpr (polar) {
      const __m256d om = _mm256_mul_pd(vj, _mm256_sub_pd(wj, wi));
      K0 = _mm256_fmadd_pd(lane<0>(om), xi, K0);
      K1 = _mm256_fmadd_pd(lane<1>(om), xi, K1);
      K2 = _mm256_fmadd_pd(lane<2>(om), xi, K2);
    }
  }
  const __m256d s = fourth_lanes(S0, S1, S2), sw = fourth_lanes(K0, K1, K2);
  // Whole 4-lane stores in member order, each overwriting the previous one's fourth lane (a masked
  // store is slow on some processors, and a later load cannot take its value from it).
  static_assert(sizeof(BondSums<3, 3>) == 28 * sizeof(double), "BondSums<3, 3>: members packed in order");
  _mm256_storeu_pd(out.S, S0);
  _mm256_storeu_pd(out.S + 3, S1);
  _mm256_storeu_pd(out.S + 6, S2);
  _mm256_storeu_pd(out.Sk, K0);
  _mm256_storeu_pd(out.Sk + 3, K1);
  _mm256_storeu_pd(out.Sk + 6, K2);
  _mm256_storeu_pd(out.s, s);
  _mm256_storeu_pd(out.m, m);
  _mm256_storeu_pd(out.sw, sw);
}

// 2-D, a bond's two components as the lanes of a 2-lane vector, with the scalar loop's operations
// per component: U = (u_j - u_i) + (wm xi_1, -wm xi_0) fused (composite_state: fma(wm, xi_1, U_0),
// fma(-wm, xi_0, U_1)), vu = V_j U, row r of S: fma(vu_r, xi, S_r), s + vu, m: fma(V_j, xi, m);
// om = V_j (w_j - w_i) and the row of Sk: fma(om, xi, Sk), sw + om.
template <class Effects, bool StoredXi>
[[gnu::always_inline]] inline void bond_sums_vector_2d(const PointData& p, const BondFamilies& f, std::size_t i,
                                                       BondSums<2, 1>& out) {
  constexpr bool polar = Effects::micropolar;
  const double* __restrict u = p.displacement.data();
  const double* __restrict w = polar ? p.rotation.data() : nullptr;
  const double* __restrict vol = p.volume.data();
  const double* __restrict xis = f.xi.data();
  const double* __restrict pos = p.position.data();
  const std::int32_t* __restrict nb = f.neighbor.data();
  const __m128d pos_i = _mm_loadu_pd(pos + i * 2), ui = _mm_loadu_pd(u + i * 2);
  const double wi = polar ? w[i] : 0.0;
  const __m128d negate_lane_1 = _mm_set_pd(-0.0, 0.0);
  __m128d S0 = _mm_setzero_pd(), S1 = S0, s = S0, m = S0, Sk = S0;
  double sw = 0.0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    const std::int32_t entry = nb[b];
    if constexpr (Effects::damage)
      if (entry < 0) continue;  // broken (BondFamilies::kBrokenBit)
    const auto j = static_cast<std::size_t>(entry);
    const __m128d xi = StoredXi ? _mm_loadu_pd(xis + b * 2) : _mm_sub_pd(_mm_loadu_pd(pos + j * 2), pos_i);
    const __m128d vj = _mm_set1_pd(vol[j]);
    __m128d U = _mm_sub_pd(_mm_loadu_pd(u + j * 2), ui);
    double wj = 0.0;
    if constexpr (polar) {
      wj = w[j];
      // (wm, -wm) (xi_1, xi_0) + U; -wm by the sign bit, as the scalar negation rounds it.
      const __m128d wm = _mm_xor_pd(_mm_set1_pd(0.5 * (wi + wj)), negate_lane_1);
      U = _mm_fmadd_pd(wm, _mm_shuffle_pd(xi, xi, 1), U);
    }
    const __m128d vu = _mm_mul_pd(vj, U);
    S0 = _mm_fmadd_pd(_mm_unpacklo_pd(vu, vu), xi, S0);
    S1 = _mm_fmadd_pd(_mm_unpackhi_pd(vu, vu), xi, S1);
    s = _mm_add_pd(s, vu);
    m = _mm_fmadd_pd(vj, xi, m);
    if constexpr (polar) {
      const double om = vol[j] * (wj - wi);
      Sk = _mm_fmadd_pd(_mm_set1_pd(om), xi, Sk);
      sw += om;
    }
  }
  _mm_storeu_pd(out.S, S0);
  _mm_storeu_pd(out.S + 2, S1);
  _mm_storeu_pd(out.s, s);
  _mm_storeu_pd(out.m, m);
  _mm_storeu_pd(out.Sk, Sk);
  out.sw[0] = sw;
}
#endif

// The kernel's bond sums: the vector forms where the instruction set has them, else the scalar.
template <int D, class Effects, bool StoredXi>
[[gnu::always_inline]] inline void bond_sums(const PointData& p, const BondFamilies& f, std::size_t i,
                                             BondSums<D, rotation_components<D>>& out) {
#ifdef MPPM_VECTOR_LANES
  if constexpr (D == 3)
    bond_sums_vector<Effects, StoredXi>(p, f, i, out);
  else
    bond_sums_vector_2d<Effects, StoredXi>(p, f, i, out);
#else
  bond_sums_scalar<D, Effects, StoredXi>(p, f, i, out);
#endif
}

}  // namespace mppm::solver::kernel
