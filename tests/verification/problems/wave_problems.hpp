// Wave problems with analytic answers (a verification case), on periodic lattices so that
// there are no boundary reflections: the P wave sqrt((lambda + 2 mu) / rho), the coupled
// shear-rotation wave of a Cosserat medium,
//   (W^2 - (mu + mu_c) k^2 / rho) (W^2 - (B k^2 + 4 mu_c) / I) = 4 mu_c^2 k^2 / (rho I),
// both branches at one wave number, and its cut-off frequency 2 sqrt(mu_c / I) at k = 0.
// Each sets a standing wave along x into the model and measures its frequency.
#pragma once
#include <array>

#include "solver/cosserat_material.hpp"
#include "tests/verification/problems/frequency_measurement.hpp"

namespace mppm::verification {

// Analytic answers.
double p_wave_speed(const solver::CosseratConstants& c);
// W^2 of the acoustic (0) and optical (1) branch at wave number k; in 3-D the wryness component
// w_z,x meets B_w = a2, in 2-D a3 (CosseratConstants::bending_modulus).
std::array<double, 2> coupled_branches(const solver::CosseratConstants& c, double k);
double cutoff_frequency(const solver::CosseratConstants& c);

struct WaveMeasurement {
  FrequencyMeasurement measured;
  double analytic_omega = 0.0;
  double ratio() const { return measured.omega / analytic_omega; }
};

// Each integrates 2.3 periods of an acoustic wave (4 zero crossings) or 6.3 of an optical one,
// times `duration_factor` (more periods average the crossing times better).
// u_x = U sin(kx) (micropolar or not, 2-D or 3-D).
WaveMeasurement measure_p_wave(solver::Model& model, double k, TimeStepChoice choice, double duration_factor = 1.0);
// u_y = U sin(kx), w_z = R cos(kx) with the branch's amplitude ratio (micropolar model).
WaveMeasurement measure_coupled_wave(solver::Model& model, double k, int branch, TimeStepChoice choice,
                                     double duration_factor = 1.0);
// w_z uniform (micropolar model).
WaveMeasurement measure_cutoff(solver::Model& model, TimeStepChoice choice, double duration_factor = 1.0);

}  // namespace mppm::verification
