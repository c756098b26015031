// The running energy check of a run (docs/theory.md section 9): energy growth that the external work does
// not explain stops the run. Relative to the largest energy seen so far, so that round-off in a
// run whose energy is (still, or again) near zero is never mistaken for growth; the scale also
// holds the size of the kinetic-energy terms (EnergyState::kinetic_terms), so that the round-off
// of the step in which a load starts, when every energy is still round-off, is not either.
//
// The balance counts the dissipations (plastic, fracture) as energy that left the model. A
// dissipation can only grow: where an accumulated dissipation decreases between two checked rows,
// the process put that energy into the model (e.g. bonds whose breaking raised the stored and
// kinetic energy, booked as a negative fracture dissipation), and a balance that books it closes
// while the model gained energy from nothing. The check therefore adds every such decrease to the
// unexplained growth, and names the process in its reason.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "solver/explicit_dynamics.hpp"

namespace mppm::solver {

class EnergyGuard {
 public:
  // The first `start_step` steps are not checked (numerics.energy_check_start_step): a load
  // switched on at t = 0 gives tiny energies at first, and a real instability grows
  // exponentially anyway.
  EnergyGuard(double tolerance, std::int64_t start_step) : tolerance_(tolerance), start_step_(start_step) {}

  // Returns the reason to stop, if any. Call it at every energy row (the decreases of the
  // dissipations are measured from row to row).
  std::optional<std::string> check(std::int64_t step, const EnergyState& energy, double initial_total);

  // Energy put into the model by a dissipative process so far [J]: the sum of the row-to-row
  // decreases of the plastic and of the fracture dissipation.
  double created_by_plasticity() const { return created_plastic_; }
  double created_by_breakage() const { return created_fracture_; }

  // What the check carries from row to row (a checkpoint stores it, a restart puts it back).
  struct History {
    double scale = 0.0;
    double last_plastic = 0.0, last_fracture = 0.0;
    double created_plastic = 0.0, created_fracture = 0.0;
  };
  History history() const { return {scale_, last_plastic_, last_fracture_, created_plastic_, created_fracture_}; }
  void restore(const History& h) {
    scale_ = h.scale;
    last_plastic_ = h.last_plastic;
    last_fracture_ = h.last_fracture;
    created_plastic_ = h.created_plastic;
    created_fracture_ = h.created_fracture;
  }

 private:
  double tolerance_;
  std::int64_t start_step_;
  double scale_ = 0.0;
  double last_plastic_ = 0.0, last_fracture_ = 0.0;
  double created_plastic_ = 0.0, created_fracture_ = 0.0;
};

}  // namespace mppm::solver
