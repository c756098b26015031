// Scalar measures of the accumulated plastic deformation for output (snapshot fields
// plastic_shear_strain and the volumetric part of eps_vp, docs/theory.md section 6).
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "solver/plasticity/drucker_prager_perzyna.hpp"

namespace mppm::plasticity {

// tr(eps_vp): > 0 for dilation (tension positive).
inline double volumetric_plastic_strain(const Eigen::Matrix3d& plastic_strain) { return plastic_strain.trace(); }

// Equivalent plastic shear strain of the accumulated tensors, with the weights of ebar:
// sqrt(b1 e:e + b2 e:e^T + b3 l^2 kap_vp:kap_vp), e = dev(eps_vp). Unlike ebar (the integral
// of the rate), it does not grow under cyclic flow; for proportional non-polar flow both agree.
template <typename Couple>
inline double equivalent_plastic_shear_strain(const Eigen::Matrix3d& plastic_strain, const Couple& plastic_wryness,
                                              const EquivalentStrainWeights& w, double length_scale) {
  const Eigen::Matrix3d e = plastic_strain - (plastic_strain.trace() / 3.0) * Eigen::Matrix3d::Identity();
  double sum = w.b1 * contract(e, e) + w.b2 * contract(e, e.transpose());
  if (length_scale > 0.0) sum += w.b3 * length_scale * length_scale * plastic_wryness.squaredNorm();
  return std::sqrt(std::max(0.0, sum));
}

}  // namespace mppm::plasticity
