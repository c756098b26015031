// Regular lattices built in memory (no points file, no preprocessor) and the model built from a
// lattice and a scene: the common ground of the verification tests and the accuracy-cost study
// (benchmarks/accuracy). A non-zero period makes the lattice periodic along that axis.
#pragma once
#include <array>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/model.hpp"
#include "solver/regular_lattice.hpp"

namespace mppm::verification {

// Points at ((i + 1/2) dx, (j + 1/2) dx[, (k + 1/2) dx]); volume dx^d (2-D: dx^2 t); all body.
inline PointCloud make_lattice(int dimension, std::array<int, 3> n, double dx, double thickness = 1.0) {
  return solver::make_regular_lattice(dimension, n, dx, thickness);
}

// The model of a cloud with the scene's material, effects, horizon and spacing.
inline solver::Model make_model(const PointCloud& cloud, const Scene& scene, std::array<double, 3> period = {0, 0, 0}) {
  solver::ModelOptions o = solver::model_options(scene);
  o.period = period;
  return solver::build_model(cloud, o);
}

}  // namespace mppm::verification
