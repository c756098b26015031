// Test helpers of the solver tests: regular lattices built in memory (no points file, no
// preprocessor), a scene with a chosen material built in code, and the model from both.
#pragma once
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/model.hpp"
#include "tests/verification/problems/generic_scene.hpp"
#include "tests/verification/problems/periodic_lattice.hpp"

namespace mppm::solver::testing {

// The lattice and model builders are shared with the accuracy-cost study.
using verification::make_lattice;
using verification::make_model;
using verification::make_scene;

// Water in the pores (docs/theory.md section 12): the pore-fluid tests' fluid, with their permeability,
// Biot coefficient and initial pressure.
inline PoreFluidParameters water(double permeability, double biot_coefficient, double initial_pressure = 0.0) {
  PoreFluidParameters f;
  f.permeability = permeability;
  f.fluid_viscosity = 1e-3;
  f.fluid_density = 1000.0;
  f.biot_coefficient = biot_coefficient;
  f.biot_modulus = 2e9;
  f.initial_pressure = initial_pressure;
  return f;
}

// True when the full horizon of point i lies inside the lattice (its family is symmetric).
inline bool is_interior(const Model& m, std::size_t i, std::array<int, 3> n, double dx, double horizon) {
  const int D = m.dimension();
  for (int a = 0; a < D; ++a) {
    const double x = m.points.position[i * D + a];
    if (x - 0.5 * dx < horizon - 1e-9 * dx || (n[a] - 0.5) * dx - x < horizon - 1e-9 * dx) return false;
  }
  return true;
}

// Turns the first and last `depth` columns (x) of a lattice into the fictitious layers of two
// kinematic boundary conditions 1 ("left") and 2 ("right"), as the preprocessor would.
inline void add_end_layers(PointCloud& c, int columns, int depth, const std::string& left_type,
                           const std::string& right_type) {
  const double dx = c.spacing;
  std::int64_t left = 0, right = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const int column = static_cast<int>(std::floor(c.x[i] / dx));
    if (column < depth) {
      c.region[i] = c.boundary_id[i] = 1;
      ++left;
    } else if (column >= columns - depth) {
      c.region[i] = c.boundary_id[i] = 2;
      ++right;
    }
  }
  double height = 0.0;
  for (double y : c.y) height = std::max(height, y + 0.5 * dx);
  const double area = height * (c.dimension == 2 ? c.thickness : height);
  c.boundaries = {BoundaryInfo{"left", left_type, area, left, "", 0.0},
                  BoundaryInfo{"right", right_type, area, right, "", 0.0}};
}

// A kinematic condition: constant (one row) or piecewise-linear rows of a vector value.
inline BoundaryCondition kinematic_condition(const std::string& name, BoundaryType type, std::vector<double> times,
                                             std::vector<std::vector<double>> values) {
  BoundaryCondition bc;
  bc.name = name;
  bc.type = type;
  bc.value.times = std::move(times);
  bc.value.values = std::move(values);
  bc.constrained.assign(bc.value.values.front().size(), true);
  return bc;
}

// Maximum absolute value of a vector.
inline double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace mppm::solver::testing
