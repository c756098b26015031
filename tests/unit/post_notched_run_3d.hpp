// A small real 3-D run directory for the postprocessor tests: the 3-D stability case
// (tests/stability/scenes/notched_impact_3d.yaml, a 100 x 20 x 10 mm notched bar at dx = 2 mm,
// 2752 points, struck at mid-span) made by the built mppm-preprocess and mppm-solve, shortened
// to 10 us: snapshots at 0, 5 and 10 us. About a second on the build machine.
#pragma once
#include <string>

#include "test_post_command.hpp"

namespace mppm::post::testing {

inline constexpr int kNotchedRunSnapshots = 3;

// Writes DIRECTORY/points.vtp and the run directory DIRECTORY/run; returns the run directory,
// or an empty string (the output of the failed stage in `failure`).
inline std::string write_notched_run_3d(const std::string& directory, std::string& failure) {
  const std::string scene = std::string(MPPM_SOURCE_DIR) + "/tests/stability/scenes/notched_impact_3d.yaml";
  const std::string bin = std::string(MPPM_BINARY_DIR) + "/bin/";
  const std::string points = directory + "/points.vtp", run = directory + "/run";
  auto stage = run_command({bin + "mppm-preprocess", scene, "-o", points, "--quiet"});
  if (stage.exit_code == 0)
    stage = run_command(
        {bin + "mppm-solve", scene, "--points", points, "-o", run, "--set", "time.end=10us", "--quiet", "--force"});
  if (stage.exit_code != 0) {
    failure = stage.output;
    return {};
  }
  return run;
}

}  // namespace mppm::post::testing
