// Regular lattices built in memory (no points file, no preprocessor) and the model built from a
// lattice and a scene: the common ground of the verification tests and the accuracy-cost study
// (benchmarks/accuracy). A non-zero period makes the lattice periodic along that axis.
#pragma once
#include <array>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/model.hpp"

namespace mppm::verification {

// Points at ((i + 1/2) dx, (j + 1/2) dx[, (k + 1/2) dx]); volume dx^d (2-D: dx^2 t). Every
// point is in the body (region 0).
inline PointCloud make_lattice(int dimension, std::array<int, 3> n, double dx, double thickness = 1.0) {
  PointCloud c;
  c.dimension = dimension;
  c.spacing = dx;
  c.thickness = dimension == 2 ? thickness : 1.0;
  const int nz = dimension == 2 ? 1 : n[2];
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        c.x.push_back((i + 0.5) * dx);
        c.y.push_back((j + 0.5) * dx);
        c.z.push_back(dimension == 3 ? (k + 0.5) * dx : 0.0);
        c.volume.push_back(dimension == 2 ? dx * dx * thickness : dx * dx * dx);
        c.region.push_back(0);
        c.boundary_id.push_back(0);
        c.normal_x.push_back(0.0);
        c.normal_y.push_back(0.0);
        c.normal_z.push_back(0.0);
      }
  return c;
}

// The model of a cloud with the scene's material, effects, horizon and spacing.
inline solver::Model make_model(const PointCloud& cloud, const Scene& scene, std::array<double, 3> period = {0, 0, 0}) {
  solver::ModelOptions o = solver::model_options(scene);
  o.period = period;
  return solver::build_model(cloud, o);
}

}  // namespace mppm::verification
