// A patch of a model (docs/theory.md section 9): the points within a radius of a centre, with
// their neighbours, as a model of its own whose linear operator, on fields that vanish outside the
// patch, is the whole model's. Lanczos on such fields works on a principal submatrix of M^-1 K:
// its Ritz values are lower bounds of the whole model's, and where the highest mode lives inside
// the patch they are the whole model's to the patch's truncation. The start-up estimates the
// critical step and names the limiting mode on the patch around the stiffest point
// (critical_time_step.cpp), at a small fraction of the cost of the whole operator.
//
// In a distributed run the patch is cut across processes: each process contributes its own points
// of the patch, and every process assembles the same patch, in the order of the points' global
// ids (one process: the model's order), so that its estimates have the same bits for any number
// of processes.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/model.hpp"
#include "solver/point_stability.hpp"

namespace mppm::solver {

struct ModelPatch {
  // The patch's points and their neighbours (the points whose pass-1 tensors enter the patch's
  // forces), in the order of their global ids, with the whole model's shape tensors and bonds
  // among them: the force on a patch point of a field that vanishes outside the patch is the one
  // the whole model gives (its neighbours' bonds to points outside carry no displacement, so
  // leaving them out leaves their sums as they are).
  Model model;
  std::vector<std::uint8_t> inside;  // 1 for the patch's own points
  std::size_t points_inside = 0;
};

// Where a patch is centred: a point's reference position [m] and its point block value, the same
// on every process.
struct PatchCentre {
  std::array<double, 3> position{0.0, 0.0, 0.0};
  double block_eigenvalue = 0.0;  // 0: no point (nothing to centre on)
};

// Whether the model can be cut into patches: without the pore fluid (its operator reads fluid
// state the patch does not carry) and with the state at rest without history on every process
// (the start-up's operator). Collective in a distributed run.
bool can_cut_patches(const Model& model);

// The stiffest point over all processes (the first of the largest, by global id) from each
// process's own (stiffest_points), as a patch centre. Collective in a distributed run.
PatchCentre patch_centre(const Model& model, const StiffestPoint& own);

// The patch of the points within `radius` of `centre`. Collective in a distributed run.
ModelPatch cut_patch(const Model& model, const std::array<double, 3>& centre, double radius);

// The points of the model over all processes. Collective in a distributed run.
std::size_t model_points(const Model& model);

}  // namespace mppm::solver
