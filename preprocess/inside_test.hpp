// Which lattice points lie in the body. Scanline crossing counts with exact predicates:
// every lattice line (2-D: rows along x; 3-D: lines along x) is intersected with the closed
// boundary facets, and a point is inside when an odd number of facets cross its line beyond it.
//
// Robustness (holes, re-entrant corners, lines through mesh vertices or along facets):
// - which facets a line crosses is decided with exact orientation predicates (CGAL Epick) on
//   the line moved by an infinitesimal (+eps in y, +eps^2 in z: simulation of simplicity), so
//   a line through a vertex or an edge is counted once, never twice or zero times;
// - whether a point is before or after a crossing is decided exactly (orientation of the point
//   against the facet) whenever the point lies within the facet's x extent;
// - a point exactly on the boundary (any facet, exact test) is inside: the body is closed.
// The result depends only on the geometry, never on the thread count (each line writes only
// its own points).
#pragma once
#include <cstdint>
#include <vector>

#include "preprocess/geometry_model.hpp"
#include "preprocess/lattice.hpp"

namespace mppm::pre {

// 1 = inside or on the boundary, 0 = outside; indexed like LatticeGrid::index.
// `boundary` must be closed (validate_boundary); its orientation does not matter.
std::vector<std::uint8_t> classify_inside(const LatticeGrid& grid, const FacetMesh& boundary);

std::vector<std::uint8_t> classify_inside_2d(const LatticeGrid& grid, const FacetMesh& boundary);
std::vector<std::uint8_t> classify_inside_3d(const LatticeGrid& grid, const FacetMesh& boundary);

}  // namespace mppm::pre
