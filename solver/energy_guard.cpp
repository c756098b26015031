// The running energy check.
#include "solver/energy_guard.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mppm::solver {

std::optional<std::string> EnergyGuard::check(std::int64_t step, const EnergyState& e, double initial_total) {
  // Both dissipations start at 0 (ExplicitDynamics::initialize), the value before the first row.
  created_plastic_ += std::max(0.0, last_plastic_ - e.plastic_dissipation);
  created_fracture_ += std::max(0.0, last_fracture_ - e.fracture_dissipation);
  last_plastic_ = e.plastic_dissipation;
  last_fracture_ = e.fracture_dissipation;
  const double created = created_plastic_ + created_fracture_;
  const double unexplained = e.accounted() - initial_total - e.external_work + created;
  scale_ = std::max({scale_, std::abs(e.external_work), std::abs(e.accounted()), e.total(), e.kinetic_terms,
                     std::abs(e.plastic_dissipation), std::abs(e.fracture_dissipation), initial_total});
  if (step < start_step_ || !(unexplained > tolerance_ * scale_)) return std::nullopt;
  std::ostringstream s;
  s.precision(6);
  s << "energy grew by " << unexplained << " J more than the external work explains (" << unexplained / scale_
    << " of the energy scale " << scale_ << " J > numerics.energy_check_tolerance " << tolerance_ << ")";
  if (created_fracture_ > 0.0 && created_fracture_ >= 0.5 * unexplained)
    s << "; of it, " << created_fracture_
      << " J were put in by bond breakage (the fracture dissipation decreased by that much: breaking bonds raised "
         "the stored and kinetic energy)";
  if (created_plastic_ > 0.0 && created_plastic_ >= 0.5 * unexplained)
    s << "; of it, " << created_plastic_ << " J were put in by plastic flow (the plastic dissipation decreased)";
  return s.str();
}

}  // namespace mppm::solver
