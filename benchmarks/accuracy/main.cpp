// mppm-accuracy: one run of the accuracy-cost study (workflows/accuracy-cost/README.md). Runs
// one verification problem with the given discretization and prints one CSV row: the
// parameters, the error against the analytic answer, the wall time, the bond updates per second
// and the peak memory of the process.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "benchmarks/accuracy/accuracy_problem.hpp"
#include "benchmarks/accuracy/peak_memory.hpp"
#include "common/command_line.hpp"
#include "common/input_error.hpp"

using namespace mppm;

namespace {

const char* kUsage = R"(usage: mppm-accuracy --problem NAME [options]
       mppm-accuracy --header

Runs one verification problem of the accuracy-cost study and prints one CSV row to stdout.

problems:
  p_wave               P-wave speed sqrt((lambda + 2 mu) / rho) on a periodic lattice (2-D or 3-D)
  shear_rotation_wave  both branches of the coupled Cosserat shear-rotation wave (2-D or 3-D)
  cutoff_frequency     the rotational cut-off frequency 2 sqrt(mu_c / I) (k = 0)
  layer_shear          stiffness of a Cosserat layer in shear, rotations held on both faces (2-D)
  crack_energy         work absorbed by the broken bonds per unit new crack area vs G_cr: a crack
                       driven through a 10 mm strip (2-D) or slab (3-D) by fixed grips
  terzaghi             Terzaghi's consolidation of an 80 mm column periodic across, loaded and
                       drained on top, impermeable fixed base (2-D): degree of consolidation from
                       the settlement and base pressure against the series, T_v from 0.1 to 1

options:
  --dimension D        2 (plane strain, default) or 3
  --resolution N       points per wavelength (waves, wavelength 0.1 m) or body rows of the layer
                       (height 30 mm), of the crack strip (10 mm) or of the column (80 mm);
                       default 40
  --horizon-factor M   delta = M dx (default 3.05)
  --safety S           time step = S x the critical step of the discrete operator (default 0.8)
  --stabilization G    zero-energy-mode control G_s (default 0.1)
  --threads N          OpenMP threads (default 1)
  --sweep LABEL        label written in the sweep column (default: none)
  --header             print the CSV header line and exit

error = |measured / analytic - 1| of the wave's frequency (speed), of the cut-off frequency, of
the layer's shear stiffness tau / (U / h) or of the work per crack area against G_cr; for
shear_rotation_wave the larger of its two branches; for terzaghi max |U - U_series| (absolute)
and, in the last column (second_error), max |p_base / p0 - series|.
Exit codes: 0 success, 2 bad option, 1 anything else.
)";

constexpr const char* kHeader =
    "problem,sweep,dimension,resolution,spacing_m,horizon_factor,safety,stabilization,threads,status,error,"
    "signed_error,measured,analytic,points,bonds,steps,time_step_s,setup_seconds,wall_seconds,bond_updates,"
    "bond_updates_per_second,peak_memory_bytes,load_average,second_error";

double number_option(const CommandLine& cl, const std::string& name, double fallback) {
  const auto text = cl.option(name);
  if (!text) return fallback;
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text->size() || !std::isfinite(value))
    throw InputError(name + ": expected a number, got '" + *text + "'");
  return value;
}

int integer_option(const CommandLine& cl, const std::string& name, int fallback) {
  const double value = number_option(cl, name, fallback);
  if (value != std::floor(value) || std::abs(value) > 1e6)
    throw InputError(name + ": expected an integer, got '" + *cl.option(name) + "'");
  return static_cast<int>(value);
}

// The machine's 1-minute load average when the run ends (/proc/loadavg; empty off Linux): wall
// times on a machine shared with other jobs are read with it.
std::string load_average() {
  std::ifstream file("/proc/loadavg");
  std::string first;
  file >> first;
  return first;
}

// Shortest round-trip form of a number (CSV cells).
std::string cell(double v) {
  if (std::isnan(v)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

int run(const CommandLine& cl) {
  if (cl.has_flag("--header")) {
    std::cout << kHeader << "\n";
    return kExitSuccess;
  }
  if (!cl.positional.empty()) throw InputError("unexpected argument '" + cl.positional.front() + "' (see --help)");
  accuracy::StudyParameters p;
  const auto problem = cl.option("--problem");
  if (!problem)
    throw InputError(
        "--problem: missing (expected one of p_wave, shear_rotation_wave, cutoff_frequency, "
        "layer_shear, crack_energy, terzaghi)");
  p.problem = *problem;
  p.dimension = integer_option(cl, "--dimension", p.dimension);
  p.resolution = integer_option(cl, "--resolution", p.resolution);
  p.horizon_factor = number_option(cl, "--horizon-factor", p.horizon_factor);
  p.safety = number_option(cl, "--safety", p.safety);
  p.stabilization = number_option(cl, "--stabilization", p.stabilization);
  if (const std::string problem_error = accuracy::validate_parameters(p); !problem_error.empty())
    throw InputError(problem_error);
  if (!cl.threads) omp_set_num_threads(1);
  const int threads = omp_get_max_threads();
  const std::string sweep = cl.option("--sweep").value_or("");
  if (sweep.find_first_of(",\"\n") != std::string::npos)
    throw InputError("--sweep: a label without commas, quotes or newlines, got '" + sweep + "'");

  const accuracy::StudyResult r = accuracy::run_problem(p);
  const double nan = std::nan("");
  const bool ok = std::isfinite(r.error);
  std::cout << p.problem << "," << sweep << "," << p.dimension << "," << p.resolution << "," << cell(r.spacing) << ","
            << cell(p.horizon_factor) << "," << cell(p.safety) << "," << cell(p.stabilization) << "," << threads << ","
            << (ok ? "ok" : "not_converged") << "," << cell(ok ? r.error : nan) << ","
            << cell(ok ? r.signed_error : nan) << "," << cell(r.measured) << "," << cell(r.analytic) << ",";
  std::cout << r.points << "," << r.bonds << "," << r.steps << "," << cell(r.time_step) << "," << cell(r.setup_seconds)
            << "," << cell(r.wall_seconds) << "," << cell(r.bond_updates) << ","
            << cell(r.kernel_seconds > 0 ? r.bond_updates / r.kernel_seconds : nan) << ",";
  std::cout << accuracy::peak_memory_bytes() << "," << load_average() << "," << cell(ok ? r.second_error : nan) << "\n";
  return kExitSuccess;
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{
      "mppm-accuracy",
      kUsage,
      {"--problem", "--dimension", "--resolution", "--horizon-factor", "--safety", "--stabilization", "--sweep"},
      {"--header"}};
  return run_stage(argc, argv, spec, run);
}
