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

// The Cosserat law of the whole code (docs/theory.md section 5), written once: the elastic force
// kernel applies it to the D x D strain, the return map to the 3 x 3 strain (plane strain
// embedded, with its zz component), the energies, the stability check and the snapshots to
// either, and all of them sum its terms in this order:
//   sigma = [(mu + mu_c) e + (mu - mu_c) e^T] + lambda tr(e) 1,
//   m     = [a2 k + a3 k^T] + a1 tr(k) 1                          (3-D couple stress).
// Always inlined into its callers, which decide how many copies there are (the solver's
// cosserat_stress and couple_stress: one per source file, solver/cosserat_material.hpp).
template <typename Tensor>
[[gnu::always_inline]] inline typename Tensor::PlainObject isotropic_cosserat_law(const Eigen::MatrixBase<Tensor>& t,
                                                                                  double trace_modulus,
                                                                                  double symmetric_modulus,
                                                                                  double transpose_modulus) {
  // A plain matrix by reference (eval() of one is itself), not copied: the copy was one 64-byte
  // load of entries its caller had just stored one by one, which the processor cannot forward
  // from those stores (measured: half of the law's time in the 3-D force kernel). An expression
  // is evaluated once into a temporary.
  const auto& e = t.eval();
  typename Tensor::PlainObject s = symmetric_modulus * e + transpose_modulus * e.transpose();
  // The trace summed in index order (Eigen's trace of a 3 x 3 adds e_00 + (e_11 + e_22)), so that
  // the plane-strain zz entry can be formed from the in-plane trace (plane_strain_normal_stress).
  double trace = e(0, 0);
  for (int k = 1; k < e.rows(); ++k) trace += e(k, k);
  s.diagonal().array() += trace_modulus * trace;
  return s;
}

// The zz entry of isotropic_cosserat_law for a plane strain (e_xz = e_yz = 0), from the trace of
// its in-plane block and e_zz: the same terms in the same order.
[[gnu::always_inline]] inline double plane_strain_normal_stress(double in_plane_trace, double zz, double trace_modulus,
                                                                double symmetric_modulus, double transpose_modulus) {
  return (symmetric_modulus * zz + transpose_modulus * zz) + trace_modulus * (in_plane_trace + zz);
}

// sigma of a strain (any square size) with the moduli of either dimension.
template <typename Strain, int Dim>
[[gnu::always_inline]] inline typename Strain::PlainObject cosserat_stress(const Eigen::MatrixBase<Strain>& strain,
                                                                           const CosseratElasticity<Dim>& e) {
  return isotropic_cosserat_law(strain, e.lambda, e.mu + e.mu_c, e.mu - e.mu_c);
}

[[gnu::always_inline]] inline Eigen::Matrix3d couple_stress(const Eigen::Matrix3d& elastic_wryness,
                                                            const CosseratElasticity<3>& e) {
  return isotropic_cosserat_law(elastic_wryness, e.a1, e.a2, e.a3);
}

// 2-D: m = B_w grad w_z.
[[gnu::always_inline]] inline Eigen::Vector2d couple_stress(const Eigen::Vector2d& elastic_wryness,
                                                            const CosseratElasticity<2>& e) {
  return e.bending_modulus * elastic_wryness;
}

// a:b for the tensors and vectors above (full contraction, no symmetry assumed).
template <typename A, typename B>
inline double contract(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  return a.cwiseProduct(b).sum();
}

}  // namespace mppm::plasticity
