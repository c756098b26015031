// The per-point pieces of the viscoplastic force evaluation (docs/theory.md section 6): the stress of the
// elastic strain eps - eps_vp (in plane strain with the out-of-plane eps_e,zz = -eps_vp,zz),
// and the return-map step of one point with its dissipation. Called from pass 1 of the kernel;
// each point reads and writes only its own state, so the result is the same on any thread count.
#pragma once
#include <Eigen/Dense>

#include "solver/cosserat_material.hpp"
#include "solver/plasticity/cosserat_elasticity.hpp"
#include "solver/step_advance.hpp"

namespace mppm::solver::viscoplastic {

template <int D>
using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
template <int R, int D>
using RMat = Eigen::Matrix<double, R, D, Eigen::RowMajor>;
using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// The elastic constants in the form of the plasticity library.
inline plasticity::CosseratElasticity<2> elasticity_2d(const CosseratConstants& c) {
  return {c.lambda, c.mu, c.mu_c, c.bending_modulus};
}
inline plasticity::CosseratElasticity<3> elasticity_3d(const CosseratConstants& c) {
  return {c.lambda, c.mu, c.mu_c, c.a1, c.a2, c.a3};
}

// The in-plane (D x D) elastic strain, and in 2-D its out-of-plane normal part eps_e,zz (plane
// strain: the total eps_zz is 0). The other out-of-plane components of eps_vp stay 0 in plane
// strain (the flow direction has no xz / yz part when the stress has none).
template <int D>
struct ElasticStrain {
  Mat<D> in_plane;
  double zz = 0.0;  // 2-D only
};

template <int D>
inline ElasticStrain<D> elastic_strain(const Mat<D>& eps, const double* plastic_strain9) {
  ElasticStrain<D> e;
  for (int r = 0; r < D; ++r)
    for (int col = 0; col < D; ++col) e.in_plane(r, col) = eps(r, col) - plastic_strain9[r * 3 + col];
  if constexpr (D == 2) e.zz = 0.0 - plastic_strain9[8];
  return e;
}

// sigma (D x D block) of the elastic strain, plus sigma_zz in 2-D: the Cosserat law of the 3 x 3
// strain with the out-of-plane eps_e,zz. The in-plane block is summed as the law of the D x D
// strain plus lambda eps_e,zz on the diagonal, so that a point with eps_vp = 0 gives the elastic
// kernel's bits (the force kernel contracts multiply-adds by the shape of the code, so only the
// same expression is sure to give the same bits).
template <int D>
struct ElasticStress {
  Mat<D> in_plane;
  double zz = 0.0;  // 2-D only
};

template <int D>
[[gnu::always_inline]] inline ElasticStress<D> elastic_stress(const ElasticStrain<D>& e, const CosseratConstants& c) {
  ElasticStress<D> s;
  s.in_plane = cosserat_stress<D>(e.in_plane, c);
  if constexpr (D == 2) {
    s.in_plane.diagonal().array() += c.lambda * e.zz;
    s.zz = plasticity::plane_strain_normal_stress(e.in_plane.trace(), e.zz, c.lambda, c.mu + c.mu_c, c.mu - c.mu_c);
  }
  return s;
}

// 1/2 eps_e : sigma per unit volume, the out-of-plane term included (docs/theory.md section 9 energy).
template <int D>
inline double elastic_energy_density(const ElasticStrain<D>& e, const ElasticStress<D>& s) {
  double sum = e.in_plane.cwiseProduct(s.in_plane).sum();
  if constexpr (D == 2) sum += e.zz * s.zz;
  return 0.5 * sum;
}

// One backward-Euler step of point i: reads the state at the start of the step from the
// point's arrays, writes the state at its end, and returns the dissipation per unit volume
// 1/2 (sigma_n + sigma_{n+1}) : d eps_vp + 1/2 (m_n + m_{n+1}) : d kap_vp. The trapezoid rule
// is the one the integrator uses for the work of the loads, and the internal force is linear in
// the stresses, so with it kinetic + stored + dissipated - work is conserved to round-off.
// eps_start / kap_start: the strain of the previous evaluation (the start of the step).
template <int D, int R, bool Polar>
inline double advance_point(const Mat<D>& eps, const double* kap, const Mat<D>& eps_start, const double* kap_start,
                            double* plastic_strain9, double* plastic_wryness, double& ebar, const CosseratConstants& c,
                            const StepAdvance& step) {
  using Curvature = plasticity::Curvature<D>;
  constexpr int RD = R * D;
  Eigen::Matrix3d eps3 = Eigen::Matrix3d::Zero(), eps3_start = Eigen::Matrix3d::Zero();
  eps3.topLeftCorner<D, D>() = eps;
  eps3_start.topLeftCorner<D, D>() = eps_start;
  Curvature kap_c = Curvature::Zero(), kap_c_start = Curvature::Zero(), kap_vp = Curvature::Zero();
  if constexpr (Polar) {
    // Row-major R x D storage: 2-D (k_zx, k_zy), 3-D kap_kl = w_k,l, as the library expects.
    if constexpr (D == 2) {
      kap_c = Eigen::Map<const Eigen::Vector2d>(kap);
      kap_c_start = Eigen::Map<const Eigen::Vector2d>(kap_start);
      kap_vp = Eigen::Map<const Eigen::Vector2d>(plastic_wryness);
    } else {
      kap_c = Eigen::Map<const Mat3>(kap);
      kap_c_start = Eigen::Map<const Mat3>(kap_start);
      kap_vp = Eigen::Map<const Mat3>(plastic_wryness);
    }
  }
  plasticity::PlasticState<D> state;
  state.plastic_strain = Eigen::Map<const Mat3>(plastic_strain9);
  state.plastic_wryness = kap_vp;
  state.equivalent_plastic_strain = ebar;
  state.cohesion = step.plastic_model->cohesion_at(ebar);
  plasticity::PointUpdate<D> r;
  plasticity::CosseratElasticity<D> el;
  if constexpr (D == 2) {
    el = elasticity_2d(c);
  } else {
    el = elasticity_3d(c);
  }
  r = step.plastic_model->update(eps3, kap_c, state, el, step.dt);
  ebar = r.state.equivalent_plastic_strain;
  if (!r.plastic) return 0.0;  // elastic step: the plastic strains are untouched
  Eigen::Map<Mat3> plastic_strain_out(plastic_strain9);
  plastic_strain_out = r.state.plastic_strain;
  if constexpr (Polar) {
    if constexpr (D == 2) {
      for (int k = 0; k < RD; ++k) plastic_wryness[k] = r.state.plastic_wryness(k);
    } else {
      Eigen::Map<Mat3> plastic_wryness_out(plastic_wryness);
      plastic_wryness_out = r.state.plastic_wryness;
    }
  }
  const Eigen::Matrix3d d_strain = r.state.plastic_strain - state.plastic_strain;
  const Eigen::Matrix3d sigma_start = plasticity::cosserat_stress(eps3_start - state.plastic_strain, el);
  const Eigen::Matrix3d sigma_end = plasticity::cosserat_stress(eps3 - r.state.plastic_strain, el);
  double dissipation = 0.5 * plasticity::contract(sigma_start + sigma_end, d_strain);
  if constexpr (Polar) {
    const Curvature d_wryness = r.state.plastic_wryness - state.plastic_wryness;
    const Curvature m_start = plasticity::couple_stress(Curvature(kap_c_start - state.plastic_wryness), el);
    const Curvature m_end = plasticity::couple_stress(Curvature(kap_c - r.state.plastic_wryness), el);
    dissipation += 0.5 * plasticity::contract(m_start + m_end, d_wryness);
  }
  return dissipation;
}

}  // namespace mppm::solver::viscoplastic
