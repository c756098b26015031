// Whether the force kernel writes its own vector lanes: where the instruction set has vectors and
// fused multiply-adds (AVX2 and FMA; x86-64-v3 and above), MPPM_VECTOR_LANES is defined and the
// kernel's lane forms (bond_sums.hpp, neighbour_share.hpp) replace the scalar loops. Each lane does
// the scalar loop's operations in its order, so both forms give the same bits.
#pragma once

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define MPPM_VECTOR_LANES 1
#endif
