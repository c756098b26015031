// Test-data generator for the postprocessor: writes small, hand-made run directories in the
// format of common/snapshot_file.hpp and common/run_directory.hpp, with fields whose values
// are known functions of position and time (so readers can check them), at test time.
// Also used by the postprocessing benchmark (a million-point series).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mppm::post::testing {

struct RunFixture {
  int nx = 40, ny = 30;   // body lattice (2-D); two layer rows below and above
  double spacing = 1e-3;  // [m]
  double horizon_factor = 3.015;
  int snapshots = 4;                // at t = k * snapshot_interval
  double snapshot_interval = 1e-6;  // [s]
  bool micropolar = true;           // rotation, couple_stress
  bool damage = true;               // damage field (a crack growing from the left edge)
  bool plasticity = true;           // plastic_shear_strain (one inclined band)
  bool stress = true;               // stress, strain, porosity
  int stress_components = 9;        // 9 (3x3) or 4 (2-D in-plane block)
  std::string status = "completed";
  std::string message;
};

// Writes the run directory (created if needed). Returns the snapshot file paths.
std::vector<std::string> write_run_directory(const std::string& directory, const RunFixture& fixture);

// Point count of the fixture (body + layers).
std::int64_t fixture_points(const RunFixture& fixture);

}  // namespace mppm::post::testing
