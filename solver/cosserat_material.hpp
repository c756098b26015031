// Material constants of the elastic Cosserat solid as the kernels use them (docs/theory.md sections 3-5),
// derived once from the scene, plus the constitutive laws sigma(eps) and m(kap).
#pragma once
#include <Eigen/Dense>
#include <optional>
#include <string>

#include "common/scene.hpp"
#include "solver/plasticity/cosserat_elasticity.hpp"
#include "solver/retention_curve.hpp"

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
  double density = 0.0;         // rho = solid_fraction * material.density [kg/m^3]
  double micro_inertia = 0.0;   // I = 1/2 pi rho l^2 [kg/m]
  double stabilization = 0.0;   // G_s
  double solid_fraction = 1.0;  // phi0 (porosity output n = 1 - phi0 / J)
  double length_scale = 0.0;    // l [m]
  // Pore fluid (docs/theory.md section 12): the coupling of pass 1, p = M (zeta - n0 - b tr eps) and the
  // total stress sigma' - b p 1 (0 without the effect).
  double biot_coefficient = 0.0;  // b
  double biot_modulus = 0.0;      // M [Pa]
  // Unsaturated (material.pore_fluid.retention): p from the content by the retention inverse and
  // Bishop's total stress sigma' - b S_r p 1 (solver/unsaturated_coupling.hpp).
  std::optional<RetentionCurve> retention{};
  FluidStorage fluid_storage{};     // n0, b, M of the retention inverse
  double critical_bond_work = 0.0;  // w_cr [J/m^6] from G_cr (damage effect; 0 otherwise)
  // material.damage.compressed_bonds: hold: a bond at its critical work breaks only once stretched.
  bool hold_compressed_bonds = false;
  // Damage thresholds from the scene's numerics block (docs/scene.md), defaults as there.
  double detach_energy_rise = Numerics{}.detach_energy_rise;            // bond_breakage.cpp
  double overload_factor = Numerics{}.overload_factor;                  // bond_breakage.cpp
  double damaged_frequency_ratio = Numerics{}.damaged_frequency_ratio;  // point_stability.hpp
};

// Derives the constants from a scene that load_scene/parse_scene has already validated.
CosseratConstants cosserat_constants(const Scene& scene);

// sigma(eps) and m(kap) of the D x D strain and the R x D wryness: the one Cosserat law
// (plasticity::isotropic_cosserat_law) with these constants. One copy per source file (static:
// internal linkage) and never inlined, so that every instantiation of the force kernel calls the
// same code. Its rounding does not depend on that: the project compiles without the compiler's
// contractions (-ffp-contract=off; the kernel fuses only where multiply_add.hpp says), so the law
// rounds the same in every file, inlined or not, and an effect that is on but inactive gives the
// bits of the run without it. It stays out of line as it was when the kernel's file was compiled
// with contractions; that has not been measured since.
template <int D>
[[gnu::noinline]] static Eigen::Matrix<double, D, D, Eigen::RowMajor> cosserat_stress(
    const Eigen::Matrix<double, D, D, Eigen::RowMajor>& eps, const CosseratConstants& c) {
  return plasticity::isotropic_cosserat_law(eps, c.lambda, c.mu + c.mu_c, c.mu - c.mu_c);
}

// m = a1 tr(kap) 1 + a2 kap + a3 kap^T in 3-D: one copy per file, as cosserat_stress.
[[gnu::noinline, maybe_unused]] static Eigen::Matrix<double, 3, 3, Eigen::RowMajor> couple_stress_3d(
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>& kap, const CosseratConstants& c) {
  return plasticity::isotropic_cosserat_law(kap, c.a1, c.a2, c.a3);
}

// m = B_w kap in 2-D (kap = grad w_z: one product per component, nothing to fuse, so inlined),
// the 3-D law otherwise.
template <int D, int R>
[[gnu::always_inline]] inline Eigen::Matrix<double, R, D, Eigen::RowMajor> couple_stress(
    const Eigen::Matrix<double, R, D, Eigen::RowMajor>& kap, const CosseratConstants& c) {
  if constexpr (D == 2) {
    return c.bending_modulus * kap;
  } else {
    return couple_stress_3d(kap, c);
  }
}

}  // namespace mppm::solver
