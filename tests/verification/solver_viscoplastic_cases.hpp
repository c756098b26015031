// Test cases of the viscoplastic solver tests, built in memory: a plane-strain compression
// specimen (top and bottom layers driven in y, free in x, micro-rotation held) whose
// quasi-static solution is homogeneous, and the analytic Drucker-Prager limit load of it.
#pragma once
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "common/run_directory.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver::testing {

constexpr double kDeg = std::numbers::pi / 180.0;

// Plane-strain compression whose quasi-static solution is homogeneous: u = (e_xx x, e_yy (y -
// y_mid)), w = 0, sigma = diag(0, s, s_zz). Every row of the top and bottom fictitious layers is
// its own velocity condition (speed proportional to its distance from mid-height, x free,
// micro-rotation held at 0), so the layers follow the affine field instead of moving as rigid
// blocks (a rigid layer restrains the body's lateral plastic expansion like a rough platen).
// The affine field is then an exact equilibrium of the discrete model: eps = E at every point,
// the uniform stress has no force on a free component (f_x = s_xx v_x + s_xy v_y = 0), and the
// body points, whose families are all complete in y, get no force at all.
// The layers are `depth` >= 2 horizons deep so that every point with a bond across the
// layer-body interface has a complete family: the reaction of the top layer is then exactly
// the stress flux s W t for every column away from the lateral faces.
struct CompressionCase {
  Scene scene;
  PointCloud cloud;
  int layer_rows = 0;   // conditions 0 .. layer_rows-1: bottom rows; then the top rows
  double width = 0.0;   // [m]
  double height = 0.0;  // body and layers [m]
};

inline CompressionCase compression_case(int nx, int ny_body, double end_time, double strain_rate, double viscosity) {
  constexpr double dx = 1e-3;
  constexpr int depth = 5;  // > 2 * 2.05
  CompressionCase c;
  c.scene = make_scene(2, true, dx, 2.05);
  c.scene.effects.viscoplasticity = true;
  ViscoplasticParameters vp;
  vp.friction_angle = 30.0 * kDeg;
  vp.dilatancy_angle = 10.0 * kDeg;
  vp.cohesion = 1e6;
  vp.hardening = 0.0;  // perfectly plastic: the load tends to a limit
  vp.residual_cohesion = 1e4;
  vp.viscosity = viscosity;
  vp.cone_match = ConeMatch::plane_strain;
  c.scene.material.viscoplasticity = vp;
  const int rows = ny_body + 2 * depth;
  c.cloud = make_lattice(2, {nx, rows, 1}, dx, c.scene.thickness);
  c.cloud.horizon = 2.05 * dx;
  c.layer_rows = depth;
  c.width = nx * dx;
  c.height = rows * dx;
  const double y_mid = 0.5 * c.height;
  c.cloud.boundaries.clear();
  c.scene.boundary_conditions.clear();
  std::vector<int> row_condition(rows, 0);
  for (int k = 0; k < 2 * depth; ++k) row_condition[k < depth ? k : rows - 2 * depth + k] = k + 1;
  std::vector<std::int64_t> count(2 * depth, 0);
  for (std::size_t i = 0; i < c.cloud.size(); ++i) {
    const int bc = row_condition[static_cast<int>(std::floor(c.cloud.y[i] / dx))];
    c.cloud.region[i] = c.cloud.boundary_id[i] = bc;
    if (bc > 0) ++count[bc - 1];
  }
  for (int k = 0; k < 2 * depth; ++k) {
    const int row = k < depth ? k : rows - 2 * depth + k;
    const std::string name = (k < depth ? "bottom" : "top") + std::to_string(k % depth);
    c.cloud.boundaries.push_back(BoundaryInfo{name, "velocity", c.width * c.scene.thickness, count[k], "", 0.0});
    // The speed ramps up over the first fifth of the run: a smooth start excites little vibration.
    const double speed = -strain_rate * ((row + 0.5) * dx - y_mid);
    BoundaryCondition bc =
        kinematic_condition(name, BoundaryType::velocity, {0.0, 0.2 * end_time}, {{0.0, 0.0}, {0.0, speed}});
    bc.constrained = {false, true};
    bc.rotation = History{{0.0}, {{0.0}}};
    c.scene.boundary_conditions.push_back(bc);
  }
  c.scene.time.end = end_time;
  c.scene.output.interval = end_time / 4;
  c.scene.output.fields = {
      "displacement", "rotation", "stress", "plastic_strain", "plastic_shear_strain", "equivalent_plastic_strain"};
  return c;
}

// Sum of the y reactions of the top layer's rows in a load.csv row (time, then per condition
// ux, uy, Fx, Fy).
inline double top_layer_force(const CompressionCase& c, const std::vector<double>& row) {
  double f = 0.0;
  for (int k = c.layer_rows; k < 2 * c.layer_rows; ++k) f += row[1 + 4 * k + 3];
  return f;
}

// The analytic plane-strain limit of a homogeneous Drucker-Prager state with lateral stress
// -p_c (tests/verification/test_plasticity_biaxial.cpp has the derivation): at the limit the
// stress is steady, so eps_vp,zz' = 0, s_zz = -2 q M_psi / 9, and f = 0 becomes the in-plane
// line R = A - B sigma_m; the plane-strain match makes it Mohr-Coulomb: B = sin phi,
// A = c cos phi, so sigma_yy = -(p_c (1 + sin phi) + 2 c cos phi) / (1 - sin phi).
inline double plane_strain_limit_stress(const ViscoplasticParameters& vp, double confinement) {
  const double s = std::sin(vp.friction_angle), c = vp.cohesion * std::cos(vp.friction_angle);
  return -(confinement * (1.0 + s) + 2.0 * c) / (1.0 - s);
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The rows of a CSV file (header skipped) as numbers.
inline std::vector<std::vector<double>> read_csv_rows(const std::string& path) {
  std::vector<std::vector<double>> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

inline std::string fresh_run_directory(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(MPPM_BINARY_DIR) / "solver-vp-test-runs" / name;
  std::filesystem::remove_all(dir);
  return dir.string();
}

}  // namespace mppm::solver::testing
