// Cosserat (micro-polar) isotropic linear elasticity of docs/theory.md section 5, as the plasticity
// update needs it: stress from elastic strain, couple stress from elastic wryness, in 2-D
// (plane strain, 3x3 strain with the z components zero, wryness = grad w_z as a 2-vector)
// and 3-D. Plain inline functions on fixed-size Eigen types: no allocation.
#pragma once
#include <Eigen/Core>

namespace mppm::plasticity {

// The wryness and couple stress carried by a point: in 2-D the micro-rotation is the scalar
// w_z, so its gradient (k_zx, k_zy) and the couple stress (m_zx, m_zy) are 2-vectors.
template <int Dim>
struct CurvatureOf;
template <>
struct CurvatureOf<2> {
  using type = Eigen::Vector2d;
};
template <>
struct CurvatureOf<3> {
  using type = Eigen::Matrix3d;
};
template <int Dim>
using Curvature = typename CurvatureOf<Dim>::type;

template <int Dim>
struct CosseratElasticity;

// 3-D: sigma = lambda tr(e) 1 + (mu + mu_c) e + (mu - mu_c) e^T,
//      m     = a1 tr(k) 1 + a2 k + a3 k^T.
template <>
struct CosseratElasticity<3> {
  double lambda = 0.0;                  // [Pa]
  double mu = 0.0;                      // [Pa]
  double mu_c = 0.0;                    // Cosserat couple modulus [Pa]
  double a1 = 0.0, a2 = 0.0, a3 = 0.0;  // couple moduli [N]
};

// 2-D plane strain: the same stress law on the embedded 3x3 strain; one bending modulus acts
// on grad w_z (B_w = a3, docs/theory.md section 5).
template <>
struct CosseratElasticity<2> {
  double lambda = 0.0;           // [Pa]
  double mu = 0.0;               // [Pa]
  double mu_c = 0.0;             // [Pa]
  double bending_modulus = 0.0;  // B_w [N]
};

template <int Dim>
inline double bulk_modulus(const CosseratElasticity<Dim>& e) {
  // Plane strain keeps the full 3x3 stress (sigma_zz included), so the 3-D bulk modulus
  // relates p = tr(sigma)/3 to tr(eps) in both cases.
  return e.lambda + 2.0 * e.mu / 3.0;
}

template <int Dim>
inline Eigen::Matrix3d cosserat_stress(const Eigen::Matrix3d& elastic_strain, const CosseratElasticity<Dim>& e) {
  return e.lambda * elastic_strain.trace() * Eigen::Matrix3d::Identity() + (e.mu + e.mu_c) * elastic_strain +
         (e.mu - e.mu_c) * elastic_strain.transpose();
}

inline Eigen::Matrix3d couple_stress(const Eigen::Matrix3d& elastic_wryness, const CosseratElasticity<3>& e) {
  return e.a1 * elastic_wryness.trace() * Eigen::Matrix3d::Identity() + e.a2 * elastic_wryness +
         e.a3 * elastic_wryness.transpose();
}

inline Eigen::Vector2d couple_stress(const Eigen::Vector2d& elastic_wryness, const CosseratElasticity<2>& e) {
  return e.bending_modulus * elastic_wryness;
}

// a:b for the tensors and vectors above (full contraction, no symmetry assumed).
template <typename A, typename B>
inline double contract(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  return a.cwiseProduct(b).sum();
}

}  // namespace mppm::plasticity
