// The measured released fractions of the dissipation calibration (damage_calibration.hpp).
#include "solver/damage_calibration.hpp"

#include <array>
#include <sstream>

namespace mppm::solver {

namespace {

// rho against G_s, the mean over the horizon factors measured (the spread across them is the
// calibration's accuracy). Produced by `make -C workflows/damage-calibration` (mppm-damage-
// calibration: a crack driven through Rice's strip by fixed grips at W H = 1.5 G_cr, time step
// 0.4 x critical), 2026-12-01:
//  2-D, horizon factors 2.55, 3.05, 3.55, 4.05, 5.05: G_s 0.1: 0.713 (0.698-0.725), 0.2: 0.774
//    (0.760-0.801), 0.3: 0.804 (0.790-0.818), 0.5: 0.844 (0.830-0.853). At 2.05 the crack does not
//    start from the notch at G_s 0.1 and 0.2 (0.814 and 0.834 at 0.3 and 0.5): not covered.
//  3-D, horizon factors 2.55 and 3.05: G_s 0.1: 0.694 (0.668, 0.720), 0.2: 0.757 (0.743, 0.771),
//    0.3: 0.832 (0.845, 0.819).
// Measured again 2026-12-02, after the overloaded-point detachment and the memory changes, 2-D:
// G_s 0.1: 0.702 (0.684-0.748), 0.2: 0.750 (0.718-0.798), 0.3: 0.779 (0.768-0.785), 0.5: 0.823
// (0.817-0.826), 1.5-3 % below the table (the calibration tests of the suite pass with it). The
// table is kept until the whole matrix (3-D too) and the crack-branching checks are run again
// with a new one: it sets w_cr of every dissipation-calibrated run.
struct Entry {
  double stabilization, rho;
};
constexpr std::array<Entry, 4> kTable2d{{{0.1, 0.713}, {0.2, 0.774}, {0.3, 0.804}, {0.5, 0.844}}};
constexpr std::array<Entry, 3> kTable3d{{{0.1, 0.694}, {0.2, 0.757}, {0.3, 0.832}}};
constexpr double kHorizon2d[2] = {2.55, 5.05};
constexpr double kHorizon3d[2] = {2.55, 3.05};

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
