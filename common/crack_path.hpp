// The crack path of a damage run (docs/theory.md section 7, docs/stages.md "Metrics"): the points
// whose damage reached kCrackDamageThreshold. The solver records when each point got there in the
// run directory's crack_path.csv (docs/stages.md "Files between stages"); the postprocessor's crack
// metrics take their frames from that table, or from the damage field of the snapshots.
#pragma once
#include <string>
#include <vector>

namespace mppm {

// A point belongs to the crack path once its damage is at or above this. Damage only grows (bonds
// break for good), so a point stays on the path from the first time it gets there.
inline constexpr double kCrackDamageThreshold = 0.35;

namespace run_files {

// crack_path.csv: one row per point on the crack path, in the order the points got there (time,
// then point index): the point's index in the points file, its reference position (z = 0 in 2-D)
// and the time at the end of the step in which its damage reached the threshold (the run's start
// for the points the pre-crack cuts put there).
inline const std::vector<std::string>& crack_path_columns() {
  static const std::vector<std::string> columns{"point", "x_m", "y_m", "z_m", "time_s"};
  return columns;
}

}  // namespace run_files
}  // namespace mppm
