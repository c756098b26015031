// Material constants of the elastic Cosserat solid as the kernels use them (docs/theory.md sections 3-5),
// derived once from the scene, plus the constitutive laws sigma(eps) and m(kap).
#pragma once
#include <Eigen/Dense>
#include <string>

#include "common/scene.hpp"

namespace mppm::solver {

struct CosseratConstants {
  int dimension = 2;
  bool micropolar = true;
  double lambda = 0.0;
  double mu = 0.0;
  double mu_c = 0.0;  // 0 when micropolar is off (classical symmetric stress)
  double a1 = 0.0, a2 = 0.0, a3 = 0.0;
  // Effective bending modulus B_w: 2-D a3 (docs/theory.md section 5 convention); 3-D a2, the coefficient
  // of kap:kap, which is what a plane wryness field w_z,x sees in the 3-D law.
  double bending_modulus = 0.0;
  double density = 0.0;             // rho = solid_fraction * material.density [kg/m^3]
  double micro_inertia = 0.0;       // I = 1/2 pi rho l^2 [kg/m]
  double stabilization = 0.0;       // G_s
  double solid_fraction = 1.0;      // phi0 (porosity output n = 1 - phi0 / J)
  double length_scale = 0.0;        // l [m]
  double critical_bond_work = 0.0;  // w_cr [J/m^6] from G_cr (damage effect; 0 otherwise)
  // Damage thresholds from the scene's numerics block (docs/scene.md), defaults as there.
  double detach_energy_rise = Numerics{}.detach_energy_rise;            // bond_breakage.cpp
  double overload_factor = Numerics{}.overload_factor;                  // bond_breakage.cpp
  double damaged_frequency_ratio = Numerics{}.damaged_frequency_ratio;  // point_stability.hpp
};

// Derives the constants from a scene that load_scene/parse_scene has already validated.
CosseratConstants cosserat_constants(const Scene& scene);

// sigma = lambda tr(eps) 1 + (mu + mu_c) eps + (mu - mu_c) eps^T
template <int D>
inline Eigen::Matrix<double, D, D, Eigen::RowMajor> cosserat_stress(
    const Eigen::Matrix<double, D, D, Eigen::RowMajor>& eps, const CosseratConstants& c) {
  Eigen::Matrix<double, D, D, Eigen::RowMajor> s = (c.mu + c.mu_c) * eps + (c.mu - c.mu_c) * eps.transpose();
  s.diagonal().array() += c.lambda * eps.trace();
  return s;
}

// m = a1 tr(kap) 1 + a2 kap + a3 kap^T (3-D); m = B_w kap (2-D, kap = grad w_z).
template <int D, int R>
inline Eigen::Matrix<double, R, D, Eigen::RowMajor> couple_stress(
    const Eigen::Matrix<double, R, D, Eigen::RowMajor>& kap, const CosseratConstants& c) {
  if constexpr (D == 2) {
    return c.bending_modulus * kap;
  } else {
    Eigen::Matrix<double, R, D, Eigen::RowMajor> m = c.a2 * kap + c.a3 * kap.transpose();
    m.diagonal().array() += c.a1 * kap.trace();
    return m;
  }
}

}  // namespace mppm::solver
