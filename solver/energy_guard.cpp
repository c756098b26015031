// The running energy check.
#include "solver/energy_guard.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mppm::solver {

namespace {

// The scheme's kinetic energy 1/2 M v^{n-1/2}.v^{n+1/2} is positive for every mode the time step
// follows (omega dt < 2) and negative for a mode beyond it, which grows geometrically (by |lambda|
// per step, lambda + 1/lambda = 2 - omega^2 dt^2). Such a run keeps its energy balance closed (the negative kinetic
// energy books the growth) until the values overflow, so the balance alone cannot see it.
std::optional<std::string> instability(const EnergyState& e, double scale, double tolerance) {
  const char* which = e.kinetic < -tolerance * scale              ? "translational"
                      : e.rotational_kinetic < -tolerance * scale ? "rotational"
                                                                  : nullptr;
  if (!which) return std::nullopt;
  std::ostringstream s;
  s.precision(6);
  s << "the run became unstable: the scheme's " << which << " kinetic energy 1/2 M v^{n-1/2}.v^{n+1/2} is "
    << (e.kinetic < -tolerance * scale ? e.kinetic : e.rotational_kinetic)
    << " J, negative beyond round-off (energy scale " << scale
    << " J): a mode oscillates faster than the time step can follow (omega dt > 2). Lower time.safety or "
       "time.step; in a damage run, raise numerics.damaged_frequency_ratio (docs/theory.md section 9)";
  return s.str();
}

}  // namespace

std::optional<std::string> EnergyGuard::check(std::int64_t step, const EnergyState& e, double initial_total) {
  if (!std::isfinite(e.accounted()) || !std::isfinite(e.external_work))
    return "the energies are no longer finite (kinetic " + std::to_string(e.kinetic) + " J, elastic " +
           std::to_string(e.elastic) + " J, external work " + std::to_string(e.external_work) +
           " J): the run became unstable";
  // Both dissipations start at 0 (ExplicitDynamics::initialize), the value before the first row.
  created_plastic_ += std::max(0.0, last_plastic_ - e.plastic_dissipation);
  created_fracture_ += std::max(0.0, last_fracture_ - e.fracture_dissipation);
  last_plastic_ = e.plastic_dissipation;
  last_fracture_ = e.fracture_dissipation;
  const double created = created_plastic_ + created_fracture_;
  const double unexplained = e.accounted() - initial_total - e.external_work + created;
  scale_ = std::max({scale_, std::abs(e.external_work), std::abs(e.accounted()), e.total(), e.kinetic_terms,
                     std::abs(e.plastic_dissipation), std::abs(e.fracture_dissipation), initial_total});
  if (step < start_step_) return std::nullopt;
  if (auto unstable = instability(e, scale_, tolerance_)) return unstable;
  if (!(unexplained > tolerance_ * scale_)) return std::nullopt;
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
