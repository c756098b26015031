// A regular lattice of material points built in memory (no points file, no preprocessor): the
// verification problems and tests build their bodies with it, and the run estimate its periodic
// sample of the bulk (solver/run_estimate.hpp).
#pragma once
#include <array>

#include "common/point_cloud.hpp"

namespace mppm::solver {

// Points at ((i + 1/2) dx, (j + 1/2) dx[, (k + 1/2) dx]); volume dx^d (2-D: dx^2 t). Every
// point is in the body (region 0).
inline PointCloud make_regular_lattice(int dimension, std::array<int, 3> n, double dx, double thickness = 1.0) {
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

}  // namespace mppm::solver
