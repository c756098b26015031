// A 2-D column of saturated skeleton built in memory as the preprocessor would make it
// (docs/stages.md "Boundaries"), meant to be periodic along x (no lateral strain: a 1-D problem
// along y), its saturated scene and its conditions (docs/theory.md section 12): the ground of the
// pore fluid's boundary tests and of the Terzaghi problem.
//
// The column: nx x ny body points (region 0) at ((i + 1/2) dx, (j + 1/2) dx), `rows` rows of layer
// points below it (region 1: the base's layer, condition 1) and, with top_region > 0, above it
// (that region). The body's top row carries boundary id top_id and its bottom row bottom_id (the
// points of a traction or a fluid flux of those conditions; 0: none). Point order: the rows from
// the bottom up, so that a column without the top layer numbers its other points alike.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/model.hpp"
#include "tests/verification/problems/generic_scene.hpp"
#include "tests/verification/problems/periodic_lattice.hpp"

namespace mppm::verification {

struct ColumnTags {
  int top_region = 0, top_id = 0, bottom_id = 0;
};

inline PointCloud column_cloud(int nx, int ny, int rows, double dx, double thickness, ColumnTags tags) {
  const int all_rows = ny + rows + (tags.top_region > 0 ? rows : 0);
  PointCloud c = make_lattice(2, {nx, all_rows, 1}, dx, thickness);
  for (std::size_t i = 0; i < c.size(); ++i) {
    c.y[i] -= rows * dx;  // the body from y = 0 up
    const long row = std::lround(c.y[i] / dx - 0.5);
    const int region = row < 0 ? 1 : (row >= ny ? tags.top_region : 0);
    c.region[i] = c.boundary_id[i] = region;
    if (row == ny - 1) c.boundary_id[i] = tags.top_id;
    if (row == 0) c.boundary_id[i] = tags.bottom_id;
  }
  return c;
}

// The points of region r (layer) or of boundary id b on the body.
inline std::int64_t count_tagged(const PointCloud& c, int region, int boundary_id) {
  std::int64_t n = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    n += region > 0 ? c.region[i] == region : (c.region[i] == 0 && c.boundary_id[i] == boundary_id);
  return n;
}

// A condition of one value (pressure, pore pressure, fluid flux) or of d values, constant or ramped
// from 0 to its value at t0 > 0, on a physical group `group`.
inline BoundaryCondition condition(const std::string& name, BoundaryType type, std::vector<double> value,
                                   const std::string& group, double ramp = 0.0) {
  BoundaryCondition bc;
  bc.name = name;
  bc.type = type;
  bc.selector.physical_group = group;
  if (ramp > 0.0) {
    bc.value.times = {0.0, ramp};
    bc.value.values = {std::vector<double>(value.size(), 0.0), value};
  } else {
    bc.value.times = {0.0};
    bc.value.values = {value};
  }
  bc.constrained.assign(value.size(), true);
  return bc;
}

// The points file's description of condition `bc` with `points` points of its own, on `area`,
// made with its selection and `depth`.
inline BoundaryInfo boundary_info(const BoundaryCondition& bc, double area, std::int64_t points, double depth) {
  return BoundaryInfo{bc.name, to_string(bc.type), area, points, bc.selector.fingerprint(), depth};
}

// make_scene's skeleton (2-D, lambda 1.2 GPa, mu 0.9 GPa, porosity 0.2) saturated with water.
inline Scene saturated_scene(double dx, double horizon_factor, double permeability, double biot_modulus) {
  Scene s = make_scene(2, false, dx, horizon_factor);
  s.effects.pore_fluid = true;
  PoreFluidParameters f;
  f.permeability = permeability;
  f.fluid_viscosity = 1e-3;
  f.fluid_density = 1000.0;
  f.biot_coefficient = 1.0;
  f.biot_modulus = biot_modulus;
  s.material.pore_fluid = f;
  return s;
}

// The conditions and the model of a column, built as mppm-solve builds them, periodic along x
// with period `width`.
struct ColumnModel {
  solver::BoundaryConditions conditions;
  solver::Model model;
  ColumnModel(const Scene& scene, const PointCloud& cloud, double width)
      : conditions(scene, cloud, "column.vtp"), model(build(scene, cloud, conditions, width)) {}
  static solver::Model build(const Scene& scene, const PointCloud& cloud, const solver::BoundaryConditions& conditions,
                             double width) {
    solver::ModelOptions o = solver::model_options(scene);
    o.period = {width, 0.0, 0.0};
    o.fluid_boundaries = conditions.fluid_layout();
    return solver::build_model(cloud, o);
  }
};

}  // namespace mppm::verification
