// Energy dissipated per unit new crack area (docs/theory.md section 7; a verification case): a straight
// crack is driven through a strip (2-D) or a slab (3-D, periodic through its thickness z) from a
// pre-crack on the mid-plane y = H/2 by fictitious layers above and below (grips), which open it
// by a fixed amount and then hold. This is Rice's strip under fixed grips: far ahead of the crack
// the strip is in uniaxial strain eps = opening / H, and a crack that runs releases the energy
// W H = 1/2 (lambda + 2 mu) eps^2 H per unit area, whatever its length. The opening is set so that
// W H = overload x G_cr (the crack must be driven: overload > 1; the excess goes into waves, not
// into the crack, if the model is calibrated). When the halves have separated, the fracture
// dissipation the solver reports (the stored energy released by the breaks, which closes the
// energy balance) divided by the new crack area should equal G_cr, for the critical bond work
// w_cr calibrated from G_cr (2-D 3 G_cr / (2 t delta^3), 3-D 4 G_cr / (pi delta^4)).
#pragma once
#include <cstddef>
#include <cstdint>

#include "common/scene.hpp"

namespace mppm::verification {

// The material of the crack-branching plate (workflows/crack-branching/README.md: lambda = mu = 14 GPa, mu_c = mu / 3,
// a3 = 56 kN, l = 2 mm, 2650 kg/m^3 at solid fraction 0.95; in 3-D a1 = 0.2 a3, a2 = a3 (a2 > a3
// keeps the couple-stress energy positive), a3 = 0.3 of it), micropolar and damage with G_cr =
// 160 N/m and the lattice calibration: the crack problems of the tests, the accuracy study and the
// calibration benchmark share it.
void set_crack_branching_material(Scene& scene);

struct CrackStrip {
  int length = 80;           // body points along x
  int height = 20;           // body points along y (even: the crack plane lies between two rows)
  int depth = 6;             // body points along z (3-D only; periodic)
  int notch = 20;            // pre-crack from the left edge, in points along x
  double overload = 1.3;     // W H / G_cr at the final opening
  double grip_speed = 0.1;   // each grip moves away from the mid-plane at this speed [m/s]
  double end_time = 200e-6;  // [s] stop at the latest here
  double safety = 0.4;       // time step = safety x critical step
  int threads = 1;
};

struct CrackEnergyResult {
  bool separated = false;                 // no intact bond crosses the mid-plane any more
  double separation_time = 0.0;           // [s]
  double fracture_dissipation = 0.0;      // [J] as the solver reports it (energy.csv)
  double crack_area = 0.0;                // new crack area (length - notch) x t (2-D) or x depth (3-D) [m^2]
  double broken_bond_area = 0.0;          // 3-D: the new crack area the crack_area field reads [m^2]
  double measured_g = 0.0;                // fracture_dissipation / crack_area [J/m^2]
  double broken_bond_work = 0.0;          // sum V_i V_j W_ij over the broken pairs [J]
  double crossing_bond_work = 0.0;        // the same over the broken pairs across the mid-plane [J]
  double largest_bond_work_ratio = 0.0;   // max W_ij / w_cr over the intact bonds at the end
  double critical_g = 0.0;                // the scene's G_cr
  double balance_error = 0.0;             // of the run at its end (ExplicitDynamics::balance_error)
  double external_work = 0.0;             // [J]
  double available_energy = 0.0;          // W H x crack area at the final opening [J]
  std::size_t crossing_bonds_broken = 0;  // pairs across the mid-plane right of the notch, broken
  std::size_t crossing_bonds = 0;         // pairs across the mid-plane right of the notch
  std::size_t other_bonds_broken = 0;     // broken pairs that do not cross the mid-plane
  std::size_t points = 0;
  std::size_t bonds = 0;
  std::int64_t steps = 0;
  double time_step = 0.0;
  double solve_seconds = 0.0;     // the time integration (model build and time step excluded)
  std::int64_t bond_updates = 0;  // bonds x force evaluations of the integration
  double ratio() const { return measured_g / critical_g; }
};

// The scene gives the material (damage parameters included), spacing, horizon factor, thickness
// and effects (damage must be on); boundary conditions and time settings are the strip's own.
CrackEnergyResult drive_crack(const Scene& scene, const CrackStrip& strip);

}  // namespace mppm::verification
