// The points file of the block scenes of tests/data/scenes (solver_case1_block.yaml and its
// neighbours): 12 x 12 body points of 2.5 mm over a bottom velocity layer of 3 rows, written to
// DIRECTORY/block.vtp for the tests that run mppm-solve's command.
#pragma once
#include <cstdint>
#include <string>

#include "common/point_cloud.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver::testing {

inline std::string write_block_points(const std::string& directory) {
  const double dx = 2.5e-3;
  PointCloud c = make_lattice(2, {12, 15, 1}, dx, 0.01);
  c.horizon = 2.05 * dx;
  std::int64_t layer = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    c.y[i] -= 3 * dx;  // body from y = 0 up, layer below
    if (c.y[i] < 0.0) {
      c.region[i] = c.boundary_id[i] = 1;
      ++layer;
    }
  }
  c.boundaries = {BoundaryInfo{"bottom", "velocity", 12 * dx * 0.01, layer, "", 0.0}};
  const std::string path = directory + "/block.vtp";
  write_point_cloud(c, path);
  return path;
}

}  // namespace mppm::solver::testing
