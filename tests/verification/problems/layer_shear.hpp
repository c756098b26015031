// Static shear of a Cosserat layer of height h with the micro-rotation held at 0 on both faces
// (a verification case):
//   lam^2 = 4 mu mu_c / (B (mu + mu_c)),
//   tau / (U / h) = mu / [1 - 2 mu_c tanh(lam h / 2) / ((mu + mu_c) lam h)]
// (mu for the classical, non-polar layer). The layer is periodic along x; fictitious layers
// below and above it, a horizon deep as the preprocessor makes them, hold the bottom and move
// the top by U. The static response is solved from the discrete operator itself (no damping,
// no loading rate), and the shear force is the reaction of the top layer as mppm-solve reports
// it (-sum f V over its points).
#pragma once
#include <cstddef>
#include <cstdint>

#include "common/scene.hpp"

namespace mppm::verification {

enum class StaticSolver {
  // Stiffness columns from the force kernel and a dense Cholesky factorization: checks that the
  // operator is symmetric and positive definite, cost O(n^3) (tests only).
  dense_cholesky,
  // Matrix-free conjugate gradients preconditioned by the mass matrix (rho V, I V): one force
  // evaluation per iteration, the cost of the model's own operator.
  conjugate_gradient,
};

struct LayerShearResult {
  double stiffness = 0.0;         // tau / (U / h) of the discrete model [Pa]
  double analytic = 0.0;          // the formula above at the given h [Pa]
  double classical = 0.0;         // mu [Pa]
  double symmetry_defect = 0.0;   // |K - K^T| / |K| (dense solver only)
  bool positive_definite = true;  // Cholesky succeeded (dense solver only)
  bool converged = true;          // conjugate gradients reached their tolerance
  double residual = 0.0;          // max |f V| over the free points / max |right-hand side|
  int iterations = 0;             // conjugate-gradient iterations
  std::int64_t force_evaluations = 0;
  std::size_t points = 0;
  std::size_t bonds = 0;
  double solve_seconds = 0.0;  // wall time of the solve (model built before)
};

// 2-D layer of `body_rows` rows of the scene's spacing and horizon factor, with the scene's
// material (micropolar or not); `height` is the h of the analytic formula and of U / h.
LayerShearResult shear_layer(const Scene& scene, int body_rows, double height, StaticSolver solver);

// The bending modulus B for which lam h = lam_h.
double bending_for(double lam_h, double h, double mu, double mu_c);

}  // namespace mppm::verification
