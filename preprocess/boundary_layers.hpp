// Boundary layers (docs/theory.md section 8, docs/scene.md):
// - kinematic (velocity/displacement) boundary k: the lattice points OUTSIDE the body within
//   `depth` (>= the horizon) of its facets form the fictitious layer, region = k;
// - traction/pressure boundary k: the lattice points INSIDE within the traction depth of its
//   facets get boundary_id = k and the outward normal of their nearest facet.
// Where several boundaries of the same kind reach a point, the nearest wins (ties: the lower k,
// i.e. the earlier boundary condition). A layer does not wrap around the edge of its boundary
// into the space beside a neighbouring free (or loaded) boundary: an outside point that is
// nearer to another part of the body boundary than to its kinematic boundary is left out
// (ties, e.g. the corner regions beyond a shared edge, stay in the layer, so the families of
// body points at the edge are complete). Serial scatter in a fixed order: deterministic.
#pragma once
#include <cstdint>
#include <vector>

#include "preprocess/geometry_model.hpp"
#include "preprocess/lattice.hpp"

namespace mppm::pre {

struct LayerRequest {
  std::int32_t boundary = 0;        // k, 1-based
  double depth = 0.0;               // [m]
  std::vector<std::size_t> facets;  // into the body boundary
};

struct LayerTags {                     // per lattice point (LatticeGrid::index)
  std::vector<std::int32_t> boundary;  // 0 = none, else k
  std::vector<std::int32_t> facet;     // nearest facet of that boundary
  std::vector<double> distance;        // to it [m]
};

// `inside_side`: true tags points of the body (traction), false points outside it (layers).
LayerTags assign_layers(const LatticeGrid& grid, const std::vector<std::uint8_t>& inside, const FacetMesh& boundary,
                        const std::vector<LayerRequest>& requests, bool inside_side);

// Removes the tagged points that are nearer (by more than 1e-9 dx) to some facet of the whole
// `boundary` than to the boundary they were given; `reach` bounds the distances of tagged points.
void drop_points_nearer_to_other_facets(LayerTags& tags, const LatticeGrid& grid, const FacetMesh& boundary,
                                        double reach);

}  // namespace mppm::pre
