// A patch of a model (docs/theory.md section 9): the points within a radius of a centre point, with
// their neighbours, as a model of its own whose linear operator, on fields that vanish outside the
// patch, is the whole model's. Lanczos on such fields works on a principal submatrix of M^-1 K:
// its Ritz values are lower bounds of the whole model's, and where the highest mode lives inside
// the patch they are the whole model's to the patch's truncation. The start-up names the limiting
// mode on the patch around the stiffest point (critical_time_step.cpp), at a small fraction of the
// cost of the whole operator.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/model.hpp"

namespace mppm::solver {

struct ModelPatch {
  // The patch's points and their neighbours (the points whose pass-1 tensors enter the patch's
  // forces), in the whole model's order, with the whole model's shape tensors and bonds among
  // them: the force on a patch point of a field that vanishes outside the patch is the one the
  // whole model gives (its neighbours' bonds to points outside carry no displacement, so leaving
  // them out leaves their sums as they are).
  Model model;
  std::vector<std::uint8_t> inside;  // 1 for the patch's own points
  std::size_t points_inside = 0;
};

// Whether the model can be cut into patches: one process (a distributed run's patch would span
// processes), without the pore fluid (its operator reads fluid state the patch does not carry) and
// with the state at rest without history (the start-up's operator).
bool can_cut_patches(const Model& model);

// The patch of the points within `radius` of point `centre` (its reference position).
ModelPatch cut_patch(const Model& model, std::size_t centre, double radius);

}  // namespace mppm::solver
