// Whether the force kernel writes its own vector lanes: where the instruction set has vectors and
// fused multiply-adds (AVX2 and FMA; x86-64-v3 and above), MPPM_VECTOR_LANES is defined and the
// kernel's lane forms (bond_sums.hpp, bond_products.hpp) replace the scalar loops. Each lane does
// the scalar loop's operations in its order, so both forms give the same bits. The primitives both
// files use are here.
#pragma once

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define MPPM_VECTOR_LANES 1
#endif

namespace mppm::solver::kernel {

// How many doubles a D-component result of the kernel's lane forms occupies: a 3-D form writes a
// whole 4-lane vector (the fourth lane not used).
template <int D>
constexpr int lane_slots = D == 3 ? 4 : D;

#ifdef MPPM_VECTOR_LANES
// Three doubles into the low lanes of a vector (lane 3 zero); masked, so the last point's values
// are read without touching memory past them.
[[gnu::always_inline]] inline __m256d load3(const double* v) {
  return _mm256_maskload_pd(v, _mm256_set_epi64x(0, -1, -1, -1));
}

// a x b in lanes 0-2 with the scalar cross product's operations per component, fma(a_1, b_2,
// -(a_2 b_1)) and its cyclic permutations: (a_1, a_2, a_0) (b_2, b_0, b_1) less (a_2, a_0, a_1)
// (b_1, b_2, b_0), the product negated by its sign bit, as the scalar negation rounds it (0 - x
// would turn -0 into +0).
[[gnu::always_inline]] inline __m256d cross_lanes(__m256d a, __m256d b) {
  const __m256d a120 = _mm256_permute4x64_pd(a, 0xC9), a201 = _mm256_permute4x64_pd(a, 0xD2);
  const __m256d b201 = _mm256_permute4x64_pd(b, 0xD2), b120 = _mm256_permute4x64_pd(b, 0xC9);
  const __m256d minus = _mm256_xor_pd(_mm256_mul_pd(a201, b120), _mm256_set1_pd(-0.0));
  return _mm256_fmadd_pd(a120, b201, minus);
}
#endif

}  // namespace mppm::solver::kernel
