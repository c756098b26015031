// Load curves: the run's load.csv (every component of every loaded boundary) reduced to one
// displacement and one force per boundary along its loading axis, the main loaded boundary
// and its peak load (docs/stages.md "Metrics").
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace mppm::post {

struct LoadTable {
  std::vector<std::string> columns;       // header of load.csv
  std::vector<std::vector<double>> rows;  // rows[r][c]
  std::vector<std::string> notes;
};

struct LoadedBoundary {
  std::string name;
  std::vector<int> displacement_columns;  // one per axis (d of them)
  std::vector<int> force_columns;
  int axis = 0;  // loading axis: 0 x, 1 y, 2 z
};

struct LoadCurve {
  std::vector<double> time;                              // [s]
  std::vector<LoadedBoundary> boundaries;                // load.csv order
  std::vector<std::vector<double>> displacement, force;  // [boundary][row] along the axis
};

struct PeakLoad {
  std::string boundary;
  int axis = 0;
  std::optional<double> peak_load_N;             // max |F| along the axis
  std::optional<double> displacement_at_peak_m;  // |u| along the axis at that row
  std::optional<double> time_at_peak_s;
};

// Reads load.csv; throws InputError naming file:line. A last line without its newline (a run
// killed while writing) is dropped with a note.
LoadTable read_load_table(const std::string& path);

// Groups NAME_u[xyz]_m / NAME_F[xyz]_N columns; the loading axis of a boundary is the one with
// the largest peak |force| (ties: largest |displacement|).
LoadCurve make_load_curve(const LoadTable& table);

// The main loaded boundary: the first boundary in `kinematic_boundaries` order (velocity or
// displacement conditions, whose reaction force is the measured load) that moves; otherwise the
// boundary with the largest peak force (first in file order on ties).
PeakLoad find_peak_load(const LoadCurve& curve, const std::vector<std::string>& kinematic_boundaries);

// CSV text: time_s, then NAME_u<axis>_m, NAME_F<axis>_N per boundary.
std::string load_curve_csv(const LoadCurve& curve);

}  // namespace mppm::post
