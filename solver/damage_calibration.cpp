// The measured released fractions of the dissipation calibration (damage_calibration.hpp).
#include "solver/damage_calibration.hpp"

#include <array>
#include <sstream>

#include "solver/damage_calibration_table.hpp"

namespace mppm::solver {

namespace {

// rho against G_s, the mean over the horizon factors measured (the spread across them is the
// calibration's accuracy), per dimension, and the measured horizon factor range: the generated
// table (`make -C workflows/damage-calibration table` writes it from the calibration matrix of
// mppm-damage-calibration: a crack driven through Rice's strip by fixed grips at W H = 1.5 G_cr,
// time step 0.4 x critical; `make -C workflows/damage-calibration check` compares it with the
// matrix). The table covers the measured ranges only; at horizon factor 2.05 the 2-D crack does
// not start from the notch at G_s 0.1 and 0.2, so that factor is not measured.
using calibration_table::Entry;
using calibration_table::kHorizon2d;
using calibration_table::kHorizon3d;
using calibration_table::kTable2d;
using calibration_table::kTable3d;

template <std::size_t N>
std::optional<double> interpolate(const std::array<Entry, N>& table, double g) {
  // A little slack at the ends: G_s is often written as 0.1 and read back with round-off.
  constexpr double kSlack = 1e-9;
  if (g < table.front().stabilization - kSlack || g > table.back().stabilization + kSlack) return std::nullopt;
  if (g <= table.front().stabilization) return table.front().rho;
  for (std::size_t k = 1; k < N; ++k)
    if (g <= table[k].stabilization) {
      const double s = (g - table[k - 1].stabilization) / (table[k].stabilization - table[k - 1].stabilization);
      return table[k - 1].rho + s * (table[k].rho - table[k - 1].rho);
    }
  return table.back().rho;
}

}  // namespace

std::optional<double> released_fraction(int dimension, double horizon_factor, double stabilization) {
  const double* h = dimension == 3 ? kHorizon3d : kHorizon2d;
  if (horizon_factor < h[0] - 1e-9 || horizon_factor > h[1] + 1e-9) return std::nullopt;
  return dimension == 3 ? interpolate(kTable3d, stabilization) : interpolate(kTable2d, stabilization);
}

std::string released_fraction_ranges(int dimension) {
  std::ostringstream s;
  if (dimension == 3)
    s << "horizon factor " << kHorizon3d[0] << " to " << kHorizon3d[1] << " and numerics.stabilization "
      << kTable3d.front().stabilization << " to " << kTable3d.back().stabilization;
  else
    s << "horizon factor " << kHorizon2d[0] << " to " << kHorizon2d[1] << " and numerics.stabilization "
      << kTable2d.front().stabilization << " to " << kTable2d.back().stabilization;
  return s.str();
}

}  // namespace mppm::solver
