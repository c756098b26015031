// The ghosts of a part of a distributed run (docs/theory.md section 13): every point of another
// part within the bond reach of one of the part's points, found with the families' own search
// (neighbour_search.hpp), so a process holds exactly the neighbours its families name. The search
// goes by distance, not by adjacent parts: a part thinner than the horizon gets its ghosts from
// every part they lie in.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "solver/neighbour_search.hpp"

namespace mppm::solver {

// The indices (ascending) of the points not in `part` within `reach` (bond_reach) of a point of it
// (neighbour_search.hpp; `spacing` the lattice's, 0 to search by cells).
std::vector<std::size_t> halo_points(const PointPositions& points, std::span<const std::int32_t> part_of,
                                     std::int32_t part, double reach, double spacing);

}  // namespace mppm::solver
