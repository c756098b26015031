// The unsaturated pore fluid's coupling to the skeleton and its energy (docs/theory.md section 12,
// "Unsaturated (retention)"): the pressure recovered from the fluid content by the retention inverse,
// Bishop's pore stress chi p with chi = S_r, and the stored fluid energy, which under Bishop's stress
// is the work the fluid received, booked per point:
//   dW = p d zeta (flow, at a fixed skeleton)  -  b chi p d eps_v (the skeleton's deformation, at a fixed content).
// The saturated model keeps its closed form V p^2 / (2M); this unit serves scenes with a retention curve only.
#pragma once
#include <cstddef>

#include "solver/point_data.hpp"
#include "solver/retention_curve.hpp"

namespace mppm::solver {

// The pressure that holds the fluid content change `content_change` at the volumetric strain eps_v
// (pressure_from_fluid_content); NaN when none does (the point was drained below the liquid its pores
// can hold), which the run's guard reports with the point and the step.
double unsaturated_pressure(const RetentionCurve& curve, const FluidStorage& storage, double content_change,
                            double eps_v);

// Bishop's pore stress chi p = S_r(p) p: the pressure itself when saturated (the same bits).
inline double bishop_pressure(const RetentionCurve& curve, double p) { return p >= 0.0 ? p : saturation(curve, p) * p; }

// The undrained update of body point i in the force pass: its pressure at the fluid content held and
// the new volumetric strain eps_v (`saturated`, the saturated formula's p as the force pass rounds it,
// when that is >= 0; else the retention inverse's), stored; its stored fluid energy gains the work of
// the pore stress, -V b (chi p + chi p_before) / 2 (eps_v - eps_v_before) (the trapezoid rule over the
// strain change since the last evaluation; zero when the strain did not change). Returns chi p, the
// pore stress that b times the total stress subtracts.
double undrained_unsaturated_update(PointData& points, const RetentionCurve& curve, const FluidStorage& storage,
                                    std::size_t i, double saturated, double eps_v, double eps_v_before);

// The stored fluid energy that a flow update's change of fluid content gives point i:
// V (p_before + p) / 2 (zeta - zeta_before), the trapezoid rule of p d zeta (exact when saturated).
inline double flow_energy_change(const PointData& points, std::size_t i, double pressure_before,
                                 double content_increment) {
  return points.volume[i] * 0.5 * (pressure_before + points.pore_pressure[i]) * content_increment;
}

}  // namespace mppm::solver
