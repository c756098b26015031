// Files of a run directory other than snapshots (docs/stages.md "Files between stages"):
// the contract between mppm-solve (writer) and mppm-postprocess / restart (readers).
//
// load.csv   header: time_s, then for every boundary condition NAME (scene order) its mean
//            displacement and its reaction (kinematic) or applied (traction) force:
//              NAME_ux_m, NAME_uy_m[, NAME_uz_m], NAME_Fx_N, NAME_Fy_N[, NAME_Fz_N]
//            (2-D forces are for the scene thickness), or for a pore fluid condition the fluid
//            volume through it (fluid_load_columns): a drained one NAME_outflow_m3_per_s (the rate
//            of the last flow update, out of the body), NAME_outflow_m3 (so far), a fed one
//            NAME_inflow_m3_per_s, NAME_inflow_m3 (into the body; 2-D: for the scene thickness).
//            One row per load_interval.
// energy.csv header: time_s, kinetic_J, rotational_kinetic_J, elastic_J, stabilization_J,
//            plastic_dissipation_J, fracture_dissipation_J, external_work_J, balance_error
//            balance_error = (kinetic + elastic + stabilization + dissipations - external
//            work - initial total) / max(|external work|, total energy, tiny): relative.
// run_info.json (rewritten atomically after a snapshot at most once a second of wall time, and at
// checkpoints, stops and the end):
//   {"status": "running" | "completed" | "numerical_failure" | "interrupted" | "write_error",
//    "message": "...", "points": N, "bonds": N, "steps": N, "time_s": t,
//    "wall_seconds": s, "loop_wall_seconds": s,
//    "start_up_seconds": {"read_scene": s, "read_points": s, ...}, "start_up_total_seconds": s,
//    "threads": n, "effects": ["micropolar", ...],
//    "dimension": d, "time_step_s": dt, "critical_time_step_s": dt_c,
//    "critical_step_estimate": "patch" | "whole_model",
//    "limiting_mode": "translational" | "rotational",
//    "snapshots": [{"file": "snapshots/snapshot_000000.snap", "step": 0, "time_s": 0.0}, ...],
//    "detached_points": N}
#pragma once
#include <string>
#include <vector>

namespace mppm::run_files {

// With the pore fluid, four more columns at the end: fluid_stored_J (V p^2 / (2 M)),
// flow_dissipation_J (the stored fluid energy the flow removed so far, the energy the fluid carried
// out through the boundaries included), fluid_mass_balance ((fluid volume - initial + outflow -
// inflow) / initial: round-off) and flow_splitting_J (the scheme's kinetic energy the flow's force
// corrections removed so far: the fractional step's O(dt^2) splitting term, in the balance).
inline std::vector<std::string> energy_columns(bool pore_fluid = false) {
  std::vector<std::string> columns{"time_s",
                                   "kinetic_J",
                                   "rotational_kinetic_J",
                                   "elastic_J",
                                   "stabilization_J",
                                   "plastic_dissipation_J",
                                   "fracture_dissipation_J",
                                   "external_work_J",
                                   "balance_error"};
  if (pore_fluid)
    columns.insert(columns.end(), {"fluid_stored_J", "flow_dissipation_J", "fluid_mass_balance", "flow_splitting_J"});
  return columns;
}

// Column names of one loaded boundary in load.csv.
inline std::vector<std::string> load_columns(const std::string& boundary, int dimension) {
  static const char* axes = "xyz";
  std::vector<std::string> columns;
  for (int c = 0; c < dimension; ++c) columns.push_back(boundary + "_u" + axes[c] + "_m");
  for (int c = 0; c < dimension; ++c) columns.push_back(boundary + "_F" + axes[c] + "_N");
  return columns;
}

// Column names of one pore fluid boundary condition in load.csv: drained (pore_pressure) or fed
// (fluid_flux).
inline std::vector<std::string> fluid_load_columns(const std::string& boundary, bool drained) {
  const std::string what = drained ? "_outflow" : "_inflow";
  return {boundary + what + "_m3_per_s", boundary + what + "_m3"};
}

}  // namespace mppm::run_files
