// The `dissipation` calibration of the damage effect: the measured share rho of the breaking work
// that a running crack's breaks remove from the model, per dimension, horizon factor and
// stabilization coefficient. With w_cr = w_cr(lattice) / rho the crack dissipates G_cr per unit
// new area (docs/theory.md section 7's verification) instead of rho G_cr.
//
// Why rho < 1: a correspondence point that loses bonds renormalizes its shape tensor and keeps the
// strain of its remaining family, so it keeps part of the energy the broken bonds carried; that
// part later leaves the crack faces as waves. rho is a property of the discretization (horizon
// factor, G_s, dimension), and less of the material, the spacing or G_cr (within +-4 % over the
// variations benchmarks/damage_calibration.cpp lists; not everywhere: workflows/damage-calibration/
// README.md). The table holds the mean over the horizon factors, within 6.6 % of each measured one. The table is
// generated: `make -C workflows/damage-calibration` measures the matrix with build/bin/mppm-damage-calibration, `make
// -C workflows/damage-calibration table` writes solver/damage_calibration_table.hpp from it, `... check` compares the
// two (workflows/damage-calibration/README.md).
#pragma once
#include <optional>
#include <string>

namespace mppm::solver {

// rho for the setting, linearly interpolated in the horizon factor and in G_s between the measured
// points; nullopt outside the measured ranges (released_fraction_ranges says which).
std::optional<double> released_fraction(int dimension, double horizon_factor, double stabilization);

// "horizon factor 2.05 to 5.05, G_s 0.1 to 0.5" for messages.
std::string released_fraction_ranges(int dimension);

}  // namespace mppm::solver
