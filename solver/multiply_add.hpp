// a * b + c for the force kernel (docs/theory.md section 13, "Rounding"): rounded once, by the
// processor's fused multiply-add, where the instruction set has one, else a product and a sum.
// The solver is compiled without the compiler's own contractions (-ffp-contract=off), so where a
// kernel fuses is written here, in the source, and not chosen by the compiler's inlining: a point's
// arithmetic is then the same whichever loop, effect set or process count evaluates it.
#pragma once

namespace mppm::solver::kernel {

[[gnu::always_inline]] inline double multiply_add(double a, double b, double c) {
#if defined(__FMA__)
  return __builtin_fma(a, b, c);
#else
  return a * b + c;
#endif
}

}  // namespace mppm::solver::kernel
