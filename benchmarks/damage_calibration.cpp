// mppm-damage-calibration: measures the share of the breaking work that the breaks of a running
// crack remove from the model (the "released fraction" rho), per dimension, horizon factor and
// stabilization coefficient, with Rice's strip under fixed grips
// (tests/verification/problems/crack_energy.hpp), for the `dissipation` calibration of the damage
// effect. Not a test: it prints one CSV row per setting. `make -C workflows/damage-calibration`
// runs the calibration matrix with it, `make -C workflows/damage-calibration table` writes the
// solver's table (solver/damage_calibration_table.hpp) from the rows, `... check` compares them
// (workflows/damage-calibration/README.md).
//
// rho depends on the discretization only: measured within +-4 % across the material (Poisson
// ratio 0 and 0.25, mu_c = mu / 3 and mu, a3 / 10, non-polar), the spacing (0.5 and 0.25 mm) and
// G_cr (the linear elastic problem is self-similar in it), so the strip uses the crack-branching
// material at dx = 0.5 mm; it depends on the horizon factor and G_s by up to 30 %.
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "common/comma_list.hpp"
#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "tests/verification/problems/crack_energy.hpp"

using namespace mppm;

namespace {

const char* kUsage =
    R"(usage: mppm-damage-calibration --dimension D --horizon-factors M1,M2,... --stabilizations G1,G2,...

Drives a crack through a strip (2-D, 80 x 20 points) or a slab (3-D, 30 x 10 x (2m + 1) points,
periodic through z) by fixed grips (W H = 1.5 G_cr) and prints, per setting, the energy the breaks
removed and the work the broken bonds across the crack absorbed, both per unit new crack area and
relative to G_cr (lattice calibration of w_cr):
  dimension,horizon_factor,stabilization,released_fraction,absorbed_fraction,separated,other_pairs,seconds
The solver's table is the mean of released_fraction over the horizon factors of the matrix that
`make -C workflows/damage-calibration` runs (`make -C workflows/damage-calibration table` writes it).
)";

std::vector<double> numbers(const std::string& list, const std::string& option) {
  std::vector<double> out;
  for (const std::string& item : split_commas(list)) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0')
      throw InputError(option + ": expected numbers separated by commas, got '" + list + "'");
    out.push_back(v);
  }
  if (out.empty()) throw InputError(option + ": expected at least one number");
  return out;
}

Scene calibration_scene(int dimension, double horizon_factor, double stabilization) {
  Scene s;
  s.path = "damage-calibration.yaml";
  s.dimension = dimension;
  s.thickness = dimension == 2 ? 1e-3 : 1.0;
  s.geometry.spacing = 0.5e-3;
  s.geometry.horizon_factor = horizon_factor;
  verification::set_crack_branching_material(s);
  s.numerics.stabilization = stabilization;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{
      "mppm-damage-calibration", kUsage, {"--dimension", "--horizon-factors", "--stabilizations"}, {}};
  return run_stage(argc, argv, spec, [](const CommandLine& cl) -> int {
    const std::string d = cl.option("--dimension").value_or("2");
    if (d != "2" && d != "3") throw InputError("--dimension: expected 2 or 3, got '" + d + "'");
    const int dimension = d == "2" ? 2 : 3;
    const auto factors = numbers(cl.option("--horizon-factors").value_or("3.05"), "--horizon-factors");
    const auto stabilizations = numbers(cl.option("--stabilizations").value_or("0.1"), "--stabilizations");
    std::printf(
        "dimension,horizon_factor,stabilization,released_fraction,absorbed_fraction,separated,other_pairs,seconds\n");
    for (const double m : factors)
      for (const double g : stabilizations) {
        verification::CrackStrip strip;
        strip.overload = 1.5;
        strip.safety = 0.4;
        strip.threads = omp_get_max_threads();
        if (dimension == 3) {
          strip.length = 30;
          strip.height = 10;
          strip.notch = 8;
          strip.depth = static_cast<int>(2 * m) + 1;
        }
        const auto r = verification::drive_crack(calibration_scene(dimension, m, g), strip);
        std::printf("%d,%g,%g,%.4f,%.4f,%d,%zu,%.1f\n", dimension, m, g, r.ratio(),
                    r.crossing_bond_work / r.crack_area / r.critical_g, r.separated ? 1 : 0, r.other_bonds_broken,
                    r.solve_seconds);
        std::fflush(stdout);
      }
    return 0;
  });
}
