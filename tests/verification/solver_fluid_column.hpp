// Test helpers of the pore fluid's boundaries (docs/theory.md section 12): the column periodic
// across, its saturated scene and its conditions, shared with the verification problems
// (tests/verification/problems/fluid_column.hpp).
#pragma once
#include "tests/verification/problems/fluid_column.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver::testing {

using verification::boundary_info;
using verification::column_cloud;
using verification::ColumnModel;
using verification::ColumnTags;
using verification::condition;
using verification::count_tagged;
using verification::saturated_scene;

}  // namespace mppm::solver::testing
