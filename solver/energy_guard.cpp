// The running energy check.
#include "solver/energy_guard.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mppm::solver {

std::optional<std::string> EnergyGuard::check(std::int64_t step, const EnergyState& e, double initial_total) {
  const double unexplained = e.accounted() - initial_total - e.external_work;
  scale_ = std::max({scale_, std::abs(e.external_work), e.accounted(), initial_total});
  if (step < start_step_ || !(unexplained > tolerance_ * scale_)) return std::nullopt;
  std::ostringstream s;
  s.precision(6);
  s << "energy grew by " << unexplained << " J more than the external work explains (" << unexplained / scale_
    << " of the energy scale " << scale_ << " J > numerics.energy_check_tolerance " << tolerance_ << ")";
  return s.str();
}

}  // namespace mppm::solver
