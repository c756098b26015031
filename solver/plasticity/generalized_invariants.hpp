// Stress invariants of the micro-polar Drucker-Prager model: mean stress p, the generalized
// equivalent stress q = sqrt(3 J2) with couple stresses (de Borst 1991), and the yield and
// potential functions f = q + M_phi p - k(c), g = q + M_psi p (docs/theory.md section 6).
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "solver/plasticity/drucker_prager_perzyna.hpp"

namespace mppm::plasticity {

inline double mean_stress(const Eigen::Matrix3d& stress) { return stress.trace() / 3.0; }

// J2 = a1 s:s + a2 s:s^T + a3 m:m / l^2 (the couple term is dropped when l <= 0).
template <typename Couple>
inline double generalized_j2(const Eigen::Matrix3d& stress, const Couple& couple, const GeneralizedJ2Weights& w,
                             double length_scale) {
  const Eigen::Matrix3d s = stress - mean_stress(stress) * Eigen::Matrix3d::Identity();
  double j2 = w.a1 * contract(s, s) + w.a2 * contract(s, s.transpose());
  if (length_scale > 0.0) j2 += w.a3 * couple.squaredNorm() / (length_scale * length_scale);
  return j2;
}

template <typename Couple>
inline double equivalent_stress(const Eigen::Matrix3d& stress, const Couple& couple, const GeneralizedJ2Weights& w,
                                double length_scale) {
  return std::sqrt(std::max(0.0, 3.0 * generalized_j2(stress, couple, w, length_scale)));
}

// f(sigma, m, c) of a model; > 0 outside the cone.
template <typename Couple>
inline double yield_function(const DruckerPragerPerzyna& model, const Eigen::Matrix3d& stress, const Couple& couple,
                             double cohesion) {
  const auto& prm = model.parameters;
  return equivalent_stress(stress, couple, prm.j2, prm.length_scale) + model.cone.friction_slope * mean_stress(stress) -
         model.cone_strength(cohesion);
}

}  // namespace mppm::plasticity
