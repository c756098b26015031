// How the Drucker-Prager cone f = q + M_phi p - k(c) is fitted to Mohr-Coulomb: the slopes
// M_phi, M_psi and the cohesion factor k/c for the two matches a scene can choose
// (docs/theory.md section 6). The derivations are in README.md.
#pragma once
#include "common/scene.hpp"

namespace mppm::plasticity {

// The two matches are the scene's enum (common/scene.hpp, key material.viscoplasticity.cone_match).
using mppm::ConeMatch;

struct ConeCoefficients {
  double friction_slope = 0.0;   // M_phi: slope of the yield cone, dq/d(-p)
  double dilatancy_slope = 0.0;  // M_psi: slope of the plastic potential
  double cohesion_factor = 0.0;  // k / c: the cone's q at p = 0 per unit cohesion
};

// Angles in radians. Triaxial compression: M_x = 6 sin x / (3 - sin x),
// k = 6 c cos(phi) / (3 - sin(phi)) -- (fix) the source paper prints 3 - cos(phi).
// Plane strain: M_psi = 3 sin(psi) / S, M_phi = 3 sin(phi) S / (3 + sin(phi) sin(psi)),
// k = 3 c cos(phi) S / (3 + sin(phi) sin(psi)), S = sqrt(3 + sin^2(psi)).
ConeCoefficients cone_coefficients(double friction_angle, double dilatancy_angle, ConeMatch match);

}  // namespace mppm::plasticity
