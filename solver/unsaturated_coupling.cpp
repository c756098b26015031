// The unsaturated coupling (see unsaturated_coupling.hpp; docs/theory.md section 12).
#include "solver/unsaturated_coupling.hpp"

#include <limits>

namespace mppm::solver {

double unsaturated_pressure(const RetentionCurve& curve, const FluidStorage& storage, double content_change,
                            double eps_v) {
  const RetentionInverse r = pressure_from_fluid_content(curve, storage, content_change, eps_v);
  return r.ok() ? r.pressure : std::numeric_limits<double>::quiet_NaN();
}

double undrained_unsaturated_update(PointData& p, const RetentionCurve& curve, const FluidStorage& storage,
                                    std::size_t i, double saturated, double eps_v, double eps_v_before) {
  const double stress_before = bishop_pressure(curve, p.pore_pressure[i]);
  const double pressure =
      saturated >= 0.0 ? saturated : unsaturated_pressure(curve, storage, p.fluid_content_change[i], eps_v);
  p.pore_pressure[i] = pressure;
  const double stress = bishop_pressure(curve, pressure);
  if (eps_v != eps_v_before)
    p.fluid_energy[i] -=
        p.volume[i] * storage.biot_coefficient * 0.5 * (stress + stress_before) * (eps_v - eps_v_before);
  return stress;
}

}  // namespace mppm::solver
