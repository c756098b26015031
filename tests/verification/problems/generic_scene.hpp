// A scene built in code with a generic Cosserat material: the solver tests' scene and the skeleton
// of the verification problems that need no particular material (the Terzaghi column).
#pragma once
#include <array>

#include "common/scene.hpp"

namespace mppm::verification {

// A scene with a generic Cosserat material (values of the order of a stiff soil/rock; the tests
// only need them to be distinct and positive definite).
inline Scene make_scene(int dimension, bool micropolar, double dx, double horizon_factor) {
  Scene s;
  s.path = "solver-test.yaml";
  s.name = "solver-test";
  s.dimension = dimension;
  s.thickness = dimension == 2 ? 1e-3 : 1.0;
  s.geometry.spacing = dx;
  s.geometry.horizon_factor = horizon_factor;
  s.material.density = 2000.0;
  s.material.solid_fraction = 0.8;
  s.material.lambda = 1.2e9;
  s.material.mu = 0.9e9;
  s.material.mu_c = 0.4e9;
  s.material.length_scale = 2.0 * dx;
  const double bending = s.material.mu * s.material.length_scale * s.material.length_scale;
  // 2-D: B_w = a3; 3-D: a2 > a3 keeps the couple-stress energy positive definite.
  s.material.couple_moduli = dimension == 2 ? std::array<double, 3>{0.0, 0.0, bending}
                                            : std::array<double, 3>{0.2 * bending, bending, 0.3 * bending};
  s.effects.micropolar = micropolar;
  s.numerics.stabilization = 0.1;
  s.time.end = 1e-3;
  return s;
}

}  // namespace mppm::verification
