// Shared machinery of the stability suite: the short / long form switch, the scenes
// and the points made from them, reading a run directory back (run_info.json, energy.csv,
// log.txt), running the stage executables for exit-code cases, and the margin records that
// `make -C workflows stability-report` renders into tests/stability/README.md.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"

namespace mppm::stability {

// The same case runs in a short form (default suite) or a long form (label `slow`, selected
// by MPPM_STABILITY_FORM=long in the ctest entry): only the number of steps differs.
bool long_form();
const char* form_name();
std::int64_t steps_for_form(std::int64_t short_steps, std::int64_t long_steps);

// tests/stability/scenes/NAME
std::string scene_path(const std::string& name);
// The path of work directory `name` under ${CMAKE_BINARY_DIR}/stability-work/<form>/.
std::string work_path(const std::string& name);
// The same, removed first (with its content) so that a case starts from nothing.
std::string fresh_directory(const std::string& name);
// ${CMAKE_BINARY_DIR}/bin/NAME
std::string program(const std::string& name);

// The points of a scene, made by the preprocessor library (cached per scene path, spacing and
// horizon factor: the cases override nothing else the lattice depends on).
const PointCloud& points_of(const Scene& scene);

// A run directory read back through its files, as a user or the postprocessor sees it.
struct RunReport {
  std::string status;  // run_info.json
  std::string message;
  std::string limiting_mode;
  std::string driver;  // "driven by ..." from the critical-step line of log.txt
  std::int64_t steps = 0;
  double time_step = 0.0;
  double critical_time_step = 0.0;
  double largest_time_step = 0.0;  // run_info.json largest_time_step_s
  // energy.csv
  std::size_t energy_rows = 0;
  bool all_finite = true;            // every cell of every row
  double worst_balance_error = 0.0;  // max |balance_error| over the rows
  double max_total_energy = 0.0;     // kinetic + rotational + elastic + stabilization
  double max_stabilization_energy = 0.0;
  double final_external_work = 0.0;
  double final_total_energy = 0.0;
  double final_plastic_dissipation = 0.0;
  bool plastic_dissipation_never_decreases = true;  // row to row, beyond round-off
  double final_fracture_dissipation = 0.0;
  bool fracture_dissipation_never_decreases = true;  // row to row, beyond round-off
  // Energy put into the model by bond breakage, as the energy check measures it
  // (solver/energy_guard.hpp): the sum of the row-to-row decreases of the fracture dissipation.
  double fracture_dissipation_decrease = 0.0;
  // The balance error recomputed from the energy columns (kinetic + rotational + elastic +
  // stabilization + plastic + fracture dissipation - external work - first row's total, over
  // max(|work|, kinetic + stored + dissipated, first row's total)), worst over the rows whose scale
  // is above 1e-12 of the run's largest (earlier rows hold round-off only), and the same without
  // the fracture column: what the balance would say if it did not count the breaks.
  double worst_recomputed_balance_error = 0.0;
  double worst_balance_without_fracture = 0.0;
  std::int64_t detached_points = -1;   // run_info.json
  std::int64_t broken_bonds = -1;      // "broken bonds N (pairs)" of log.txt's last line (damage runs)
  std::vector<std::string> snapshots;  // the snapshot files listed in run_info.json, in order
  std::string log;                     // log.txt
};
RunReport read_run(const std::string& run_directory);

// Runs the scene (with --set overrides) on its points through mppm::solver::solve into a
// fresh run directory `name` and reads it back.
RunReport solve_scene(const std::string& scene_file, const std::vector<std::string>& overrides,
                      const std::string& name);

// The auto time step the solver picks for a scene (a one-step run), so that a case can ask
// for a number of steps rather than a simulated time.
double auto_time_step(const std::string& scene_file, const std::vector<std::string>& overrides,
                      const std::string& name);

// Runs a stage executable; returns its exit code and what it printed (stdout + stderr).
struct CommandResult {
  int exit_code = -1;
  std::string output;
};
CommandResult run_program(const std::string& executable, const std::vector<std::string>& arguments);

// One row of the margins table: the hazard, the expected outcome, what was measured and the
// margin to the pass/fail limit. Written (atomically) to
// ${CMAKE_BINARY_DIR}/stability/<form>/<id>.json before the test's assertions, so a failing
// long run still leaves its numbers for inspection.
struct MarginRecord {
  std::string id;  // file name and sort key, e.g. "01-length-scale-20mm"
  std::string hazard;
  std::string expected;
  std::string measured;  // numbers with units, human readable
  std::string margin;    // e.g. "balance error 3.1e-14 vs limit 5e-3 (1.6e11 x)"
  bool pass = false;     // the test's own verdict on the measured numbers
};
void record_margin(const MarginRecord& record);

// Formatting for records and messages.
std::string sci(double value, int digits = 3);

// Reads a whole text file (empty if it does not exist).
std::string read_text(const std::string& path);

// "%.17g": a number that reads back exactly (for --set values).
std::string exact(double value);

}  // namespace mppm::stability
