// One run of the accuracy-cost study (workflows/accuracy-cost): a verification problem with an
// analytic answer at given discretization parameters, its error and what it cost. The material
// and the physical sizes are fixed (a wavelength, a layer height), so the spacing changes the
// resolution only, as it does for a user refining a lattice.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace mppm::accuracy {

struct StudyParameters {
  std::string problem;  // one of problem_names()
  int dimension = 2;
  int resolution = 40;  // points per wavelength (waves) or body rows (layer, crack strip, column)
  double horizon_factor = 3.05;
  double safety = 0.8;         // time step = safety x critical step (explicit problems)
  double stabilization = 0.1;  // G_s
};

struct StudyResult {
  double spacing = 0.0;  // dx [m]
  // |measured / analytic - 1| (for the two-branch wave: the larger of its two branches)
  double error = 0.0;
  // (terzaghi: max |U - U_series| of the degree of consolidation, absolute)
  double signed_error = 0.0;              // measured / analytic - 1 of that quantity (terzaghi: U - U_series)
  double measured = 0.0, analytic = 0.0;  // rad/s (waves), Pa (layer stiffness), J/m^2 (crack), U (terzaghi)
  // A second error measure, NaN when the problem has none (terzaghi: max |p_base / p0 - series|).
  double second_error = std::numeric_limits<double>::quiet_NaN();
  std::size_t points = 0, bonds = 0;
  // time steps (terzaghi: of its two static runs and the consolidation), or conjugate-gradient
  // force evaluations (layer)
  std::int64_t steps = 0;
  double time_step = 0.0;       // [s], 0 for the static problem
  double setup_seconds = 0.0;   // families and shape tensors (periodic search: a test artefact)
  double wall_seconds = 0.0;    // critical-step estimate + integration, or the static solve
  double bond_updates = 0.0;    // bonds x force evaluations of the integration / solve
  double kernel_seconds = 0.0;  // the time of those force evaluations' loop
};

// The problems: p_wave, shear_rotation_wave, cutoff_frequency, layer_shear, crack_energy, terzaghi.
const std::vector<std::string>& problem_names();

// Runs one problem. Parameters must have been validated (validate_parameters).
StudyResult run_problem(const StudyParameters& parameters);

// Empty when the parameters are usable, else what is wrong (naming the option).
std::string validate_parameters(const StudyParameters& parameters);

}  // namespace mppm::accuracy
