// Drucker-Prager cone slopes and cohesion factor for the two Mohr-Coulomb matches.
#include "solver/plasticity/drucker_prager_cone.hpp"

#include <cmath>

namespace mppm::plasticity {

ConeCoefficients cone_coefficients(double friction_angle, double dilatancy_angle, ConeMatch match) {
  const double sin_phi = std::sin(friction_angle);
  const double cos_phi = std::cos(friction_angle);
  const double sin_psi = std::sin(dilatancy_angle);
  ConeCoefficients c;
  if (match == ConeMatch::triaxial_compression) {
    // Compression meridian of Mohr-Coulomb (sigma1 = sigma2 > sigma3, tension positive).
    c.friction_slope = 6.0 * sin_phi / (3.0 - sin_phi);
    c.dilatancy_slope = 6.0 * sin_psi / (3.0 - sin_psi);
    c.cohesion_factor = 6.0 * cos_phi / (3.0 - sin_phi);
  } else {
    // Plane-strain limit state: the out-of-plane plastic strain rate vanishes, which fixes
    // sigma_zz; requiring the in-plane limit (and dilatancy ratio) to be Mohr-Coulomb's
    // gives these (README.md). For psi = phi they reduce to the associated textbook match.
    const double s = std::sqrt(3.0 + sin_psi * sin_psi);
    c.dilatancy_slope = 3.0 * sin_psi / s;
    c.friction_slope = 3.0 * sin_phi * s / (3.0 + sin_phi * sin_psi);
    c.cohesion_factor = 3.0 * cos_phi * s / (3.0 + sin_phi * sin_psi);
  }
  return c;
}

}  // namespace mppm::plasticity
