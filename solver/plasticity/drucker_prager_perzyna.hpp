// The micro-polar Drucker-Prager Perzyna material point update of docs/theory.md section 6: model
// constants, the plastic state a point carries, and the backward-Euler return map
// (scalar Newton on the multiplier, with the eta/dt term, plus the apex return).
// Pure functions on fixed-size Eigen types: no allocation, no shared state, so a per-point
// kernel gives bitwise-identical results for any number of threads. README.md has the model.
#pragma once
#include <Eigen/Core>

#include "solver/plasticity/cosserat_elasticity.hpp"
#include "solver/plasticity/drucker_prager_cone.hpp"

namespace mppm::plasticity {

// Generalized second invariant (de Borst 1991): J2 = a1 s:s + a2 s:s^T + a3 m:m / l^2.
// The default (1/4, 1/4, 1/2) sees only the symmetric part of the deviatoric stress.
struct GeneralizedJ2Weights {
  double a1 = 0.25, a2 = 0.25, a3 = 0.5;
};

// Equivalent plastic strain rate: ebar' = sqrt(b1 e':e' + b2 e':e'^T + b3 l^2 kap':kap'),
// e' the deviatoric plastic strain rate. The defaults make ebar work-conjugate to q.
struct EquivalentStrainWeights {
  double b1 = 1.0 / 3.0, b2 = 1.0 / 3.0, b3 = 2.0 / 3.0;
};

struct DruckerPragerParameters {
  double friction_angle = 0.0;     // phi [rad]
  double dilatancy_angle = 0.0;    // psi [rad]
  double cohesion = 0.0;           // c0 [Pa]
  double hardening = 0.0;          // h [Pa] per unit ebar (< 0: softening)
  double residual_cohesion = 0.0;  // floor of c [Pa]
  double viscosity = 0.0;          // eta [Pa s] (0: rate-independent)
  double length_scale = 0.0;       // l [m]; 0: couple stresses do not enter J2
  ConeMatch cone_match = ConeMatch::triaxial_compression;
  GeneralizedJ2Weights j2;
  EquivalentStrainWeights equivalent_strain;
};

// Resolved model: parameters plus the derived cone coefficients.
struct DruckerPragerPerzyna {
  DruckerPragerParameters parameters;
  ConeCoefficients cone;

  // c(ebar) = max(c0 + h ebar, c_residual) and its slope dc/debar.
  double cohesion_at(double ebar) const;
  double cohesion_slope_at(double ebar) const;
  // k(c) of the yield function.
  double cone_strength(double cohesion) const { return cone.cohesion_factor * cohesion; }
};

// Checks the parameters and derives the cone. Throws std::invalid_argument with the
// message "KEY: problem (expected ...)", KEY relative to `material.` (e.g.
// "viscoplasticity.friction_angle"), so callers can prefix the file and block.
DruckerPragerPerzyna make_drucker_prager_perzyna(const DruckerPragerParameters& parameters);

// What a material point carries between steps.
template <int Dim>
struct PlasticState {
  Eigen::Matrix3d plastic_strain = Eigen::Matrix3d::Zero();  // eps_vp (non-symmetric)
  Curvature<Dim> plastic_wryness = Curvature<Dim>::Zero();   // kap_vp
  double equivalent_plastic_strain = 0.0;                    // ebar
  double cohesion = 0.0;                                     // c(ebar) [Pa]
};

template <int Dim>
PlasticState<Dim> initial_plastic_state(const DruckerPragerPerzyna& model) {
  PlasticState<Dim> state;
  state.cohesion = model.cohesion_at(0.0);
  return state;
}

template <int Dim>
struct PointUpdate {
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();       // sigma_{n+1} [Pa]
  Curvature<Dim> couple_stress = Curvature<Dim>::Zero();  // m_{n+1} [N/m]
  PlasticState<Dim> state;                                // state_{n+1}
  double dissipation = 0.0;                               // sigma:d(eps_vp) + m:d(kap_vp) over the step [J/m^3]
  double multiplier = 0.0;                                // d(gamma): the step's increment of the Perzyna multiplier
  double overstress = 0.0;  // f(sigma_{n+1}, c_{n+1}) = eta * d(gamma)/dt [Pa]; 0 if elastic
  bool plastic = false;     // the trial state was outside the cone
  bool apex = false;        // returned to the apex (all deviatoric blocks zeroed)
  int iterations = 0;       // Newton iterations of the cone return
};

// One backward-Euler step of a material point: total strain eps and wryness kap at the end
// of the step, the point's state at its start, elastic constants, model, time step dt.
// 2-D: plane strain, eps with zero z components, kap = grad w_z. dt > 0 (with eta > 0 and
// dt <= 0 the step stays elastic; with eta = 0 dt does not matter).
PointUpdate<2> drucker_prager_perzyna_update(const Eigen::Matrix3d& strain, const Eigen::Vector2d& wryness,
                                             const PlasticState<2>& state, const CosseratElasticity<2>& elasticity,
                                             const DruckerPragerPerzyna& model, double dt);
PointUpdate<3> drucker_prager_perzyna_update(const Eigen::Matrix3d& strain, const Eigen::Matrix3d& wryness,
                                             const PlasticState<3>& state, const CosseratElasticity<3>& elasticity,
                                             const DruckerPragerPerzyna& model, double dt);

}  // namespace mppm::plasticity
