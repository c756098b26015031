// Shared helpers of the preprocessor tests: scenes written inline (YAML through the real
// parser, so the tests use the same path as users) and small geometric predicates.
#pragma once
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "preprocess/preprocessor.hpp"

namespace mppm::test {

inline std::string scenes_dir() { return std::string(MPPM_SOURCE_DIR) + "/tests/data/scenes"; }

// A scene with the given geometry (path relative to tests/data/scenes), lattice and boundary
// conditions (YAML list items, one per line, already indented by two spaces).
inline Scene inline_scene(int dimension, const std::string& file, const std::string& unit, const std::string& spacing,
                          double horizon_factor, const std::string& boundary_conditions,
                          const std::string& precracks = "[]", const std::string& thickness = "1 mm") {
  std::string text = "mppm: 1\nname: inline-test\ndimension: " + std::to_string(dimension) + "\n";
  if (dimension == 2) text += "thickness: " + thickness + "\n";
  text += "geometry:\n  file: " + file + "\n  unit: " + unit + "\n  spacing: " + spacing +
          "\n  horizon_factor: " + std::to_string(horizon_factor) + "\n  precracks: " + precracks + "\n";
  text += "material: {density: 2650, lambda: 14 GPa, mu: 14 GPa}\neffects: []\n";
  text += boundary_conditions.empty() ? "boundary_conditions: []\n" : "boundary_conditions:\n" + boundary_conditions;
  text += "time: {end: 1 us, step: 0.025 us}\noutput: {interval: 0.25 us}\n";
  return parse_scene(text, scenes_dir() + "/inline_test.yaml");
}

inline std::int64_t count_region(const PointCloud& cloud, int region) {
  std::int64_t n = 0;
  for (auto r : cloud.region) n += r == region;
  return n;
}

// Integer lattice index of a coordinate: (x - origin) / dx rounded (positions are cell centres).
inline long lattice_index(double x, double origin, double dx) { return std::lround((x - origin) / dx); }

}  // namespace mppm::test
