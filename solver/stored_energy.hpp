// The elastic energy stored at a point or in the whole body [J], by kind (docs/theory.md
// section 11): what one point's energy functions return and what an energy row sums.
#pragma once

namespace mppm::solver {

struct StoredEnergy {
  double force_stress = 0.0;   // 1/2 eps:sigma (elastic parts; plane strain: sigma_zz term included)
  double couple_stress = 0.0;  // 1/2 kap:m (elastic parts; 0 without micropolar)
  double stabilization = 0.0;
  double fluid = 0.0;  // V p^2 / (2 M) of the pore fluid (docs/theory.md section 12; 0 without it)
  double elastic() const { return force_stress + couple_stress; }
  double total() const { return force_stress + couple_stress + stabilization + fluid; }
};

}  // namespace mppm::solver
