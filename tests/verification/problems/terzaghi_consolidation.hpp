// Terzaghi's consolidation (docs/theory.md section 12; a verification case): a column periodic
// across (no lateral strain), loaded and drained on top, fixed and impermeable at its base,
// compared with the series: the degree of consolidation from the settlement, U = (s - s_u) /
// (s_d - s_u) with the discrete column's own undrained and drained static settlements s_u, s_d,
// and the base pressure p / p0. At a fixed height H the rows across it set the resolution only
// (the material, the permeability and the load follow from H): the pore-fluid test
// (tests/verification/test_solver_pore_fluid_boundaries.cpp) and the accuracy-cost study
// (benchmarks/accuracy) run the same column at their spacings.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"

namespace mppm::verification {

// Terzaghi's series for a layer of thickness H drained at z = 0, impermeable at z = H: the degree
// of consolidation U(T_v) and the pressure p(z, T_v) / p0.
double terzaghi_degree(double tv);
double terzaghi_pressure(double z_over_h, double tv);

// The column: `rows` rows (H = rows dx) of make_scene's skeleton (E_oed = lambda + 2 mu = 3 GPa,
// mixture density 1800 kg/m^3) saturated with b = 1 and M = E_oed, so that the undrained pressure
// is p0 = b M sigma0 / (E_oed + b^2 M) = sigma0 / 2 and c_v = k' M E_oed / (E_oed + b^2 M) =
// k' E_oed / 2. The permeability is chosen so that consolidation takes 1000 transits of the
// undrained wave, t_c = H^2 / c_v = 1000 H / c_u (c_u = sqrt((E_oed + b^2 M) / rho)): the
// skeleton is then in equilibrium at every instant to a lag of order its first mode's period, a
// thousandth of t_c.
struct TerzaghiColumn {
  Scene scene;
  PointCloud cloud;
  int columns = 8;  // points across: the period along x exceeds twice the horizon
  double dx = 0.0, height = 0.0, e_oed = 3e9, biot_modulus = 3e9, sigma0 = 1e6;
  double c_u = 0.0, c_v = 0.0, p0 = 0.0;
  double width() const { return columns * dx; }
};
TerzaghiColumn terzaghi_column(int rows, double dx, double horizon_factor);

// The column's static state under the full load: undrained (no flow: the pressure is the
// undrained one everywhere) or drained (b = 0: the skeleton alone, the end state of
// consolidation); its settlement and the mean pressure of its lower half.
struct TerzaghiStaticState {
  double settlement = 0.0, lower_pressure = 0.0;
  std::int64_t steps = 0;
};

// The state of the consolidating column at the first step at or past a target T_v.
struct TerzaghiSample {
  double tv = 0.0;               // T_v = c_v t / H^2 of that step
  double degree = 0.0;           // U from the settlement
  double base_pressure = 0.0;    // mean pressure of the bottom body row / p0
  double pressure_degree = 0.0;  // 1 - mean pressure of the body / p0
  double degree_series = 0.0;    // terzaghi_degree(tv)
  double base_series = 0.0;      // the series at the bottom row's centre, depth H - dx/2
};

struct TerzaghiRun {
  TerzaghiStaticState undrained, drained;
  std::vector<TerzaghiSample> samples;     // one per target, in order
  std::int64_t natural_flow_interval = 0;  // the flow schedule's interval at the step limit
  std::int64_t flow_interval = 0;          // the one the run used
  std::size_t points = 0, bonds = 0;
  std::int64_t steps = 0;      // mechanical steps of the two static runs and of the consolidation
  double time_step = 0.0;      // of the consolidation [s]
  double solve_seconds = 0.0;  // the three time integrations (model builds excluded)
  // max over the samples of |p_base / p0 - series|
  double base_pressure_error() const;
};

// The static states, then the column loaded over 0.002 t_c and consolidating until the last
// target T_v (ascending), at time step `safety` x the critical step of the discrete operator.
TerzaghiRun consolidate(const TerzaghiColumn& column, const std::vector<double>& tv_targets, double safety = 0.8);

}  // namespace mppm::verification
