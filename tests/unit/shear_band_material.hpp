// The shear-band case's micro-polar Drucker-Prager Perzyna material (workflows/shear-band/scene.yaml),
// the material the return map is built for, shared by the plasticity tests.
#pragma once
#include <numbers>

#include "solver/plasticity/drucker_prager_perzyna.hpp"

namespace mppm::plasticity::testing {

inline constexpr double kDegree = std::numbers::pi / 180.0;

inline CosseratElasticity<2> shear_band_elasticity() { return CosseratElasticity<2>{13.9e6, 20.8e6, 41.6e6, 83.3}; }

inline DruckerPragerParameters shear_band_parameters() {
  DruckerPragerParameters prm;
  prm.friction_angle = 35.0 * kDegree;
  prm.dilatancy_angle = 15.0 * kDegree;
  prm.cohesion = 0.35e6;
  prm.hardening = -1.0e6;
  prm.residual_cohesion = 0.0035e6;
  prm.viscosity = 0.01e6;
  prm.length_scale = 2e-3;
  return prm;
}

}  // namespace mppm::plasticity::testing
