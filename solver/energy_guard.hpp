// The running energy check of a run (SPEC section 9): energy growth that the external work does
// not explain stops the run. Relative to the largest energy seen so far, so that round-off in a
// run whose energy is (still, or again) near zero is never mistaken for growth.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "solver/explicit_dynamics.hpp"

namespace mppm::solver {

class EnergyGuard {
 public:
  // The first `start_step` steps are not checked: a load switched on at t = 0 gives tiny
  // energies at first, and a real instability grows exponentially anyway.
  explicit EnergyGuard(double tolerance, std::int64_t start_step = 50)
      : tolerance_(tolerance), start_step_(start_step) {}

  // Returns the reason to stop, if any.
  std::optional<std::string> check(std::int64_t step, const EnergyState& energy, double initial_total);

 private:
  double tolerance_;
  std::int64_t start_step_;
  double scale_ = 0.0;
};

}  // namespace mppm::solver
