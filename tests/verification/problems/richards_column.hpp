// A fine 1-D reference for unsaturated infiltration (docs/theory.md section 12, "Unsaturated
// (retention)"): Richards' equation in its mixed form on a rigid column (eps_v = 0),
//   d zeta(p) / dt = -dq/dz,   q = -k' k_r(p) (dp/dz + rho_f g)   (z up, q the upward Darcy flux),
// with zeta, k_r from the retention unit (solver/retention_curve.hpp). Cell-centred finite volumes,
// the face conductivity the mean of its cells' k_r; backward Euler in time with Newton's method on
// the mixed form (Celia's scheme: the storage is zeta(p^{n+1}) - zeta(p^n), not a capacity times
// dp, so that the fluid is conserved to the Newton tolerance at any step). Implicit because the
// explicit step is bounded by dz^2 c / (k' k_r) at the wet end, which for the fine grids of a
// reference would take ~1e6 steps. The bottom is impermeable; the top takes a constant inflow or a
// prescribed pressure. Written for tests: the lattice's unsaturated infiltration is to be checked
// against it (cumulative inflow, wetting front, mass balance).
#pragma once
#include <vector>

#include "solver/retention_curve.hpp"

namespace mppm::verification {

struct RichardsColumn {
  double length = 1.0;  // [m], z = 0 the bottom, z = length the top
  int cells = 100;
  solver::RetentionCurve curve;
  solver::FluidStorage storage;  // n0, b (unused: rigid), M
  double mobility = 0.0;         // k' = k / mu_f [m^2 / (Pa s)]
  double fluid_density = 1000.0;
  double gravity = 9.81;            // |g| along -z; 0: none
  double initial_pressure = 0.0;    // uniform, < 0 a suction [Pa]
  bool top_pressure_given = false;  // false: the inflow top_flux; true: the pressure top_pressure
  double top_flux = 0.0;            // inflow velocity through the top [m/s], > 0 into the column
  double top_pressure = 0.0;        // [Pa]
  double end_time = 0.0;            // [s]
  int steps = 100;                  // backward Euler steps (each may be split in halves if Newton fails)
};

struct RichardsResult {
  std::vector<double> z;           // cell centres [m]
  std::vector<double> pressure;    // at end_time [Pa]
  std::vector<double> saturation;  // S_r at end_time
  double initial_saturation = 0.0;
  double inflow = 0.0;              // cumulative inflow through the top per unit area [m]
  double stored = 0.0;              // sum dz (zeta - zeta_0) [m]
  double mass_balance_error = 0.0;  // |stored - inflow| / |inflow|
  double front_depth = 0.0;         // wetting front below the top [m] (wetting_front_depth)
  int newton_iterations = 0;
  int step_splits = 0;
  bool converged = true;  // false: a step did not converge even after 20 halvings
};

RichardsResult solve_richards_column(const RichardsColumn& column);

// The depth below the top where S_r first crosses (S_initial + S_top) / 2 going down, S_top the top
// cell's saturation, interpolated linearly between cell centres (0 if it never does).
double wetting_front_depth(const RichardsResult& result, double length);

}  // namespace mppm::verification
