// Lattice construction (see lattice.hpp).
#include "preprocess/lattice.hpp"

#include <cmath>

namespace mppm::pre {

LatticeGrid lattice_for_box(const Vec3& low, const Vec3& high, double spacing, int dimension, int padding) {
  LatticeGrid grid;
  grid.dimension = dimension;
  grid.spacing = spacing;
  for (int a = 0; a < 3; ++a) {
    if (a >= dimension) {
      grid.origin[a] = 0.0;
      grid.count[a] = 1;
      continue;
    }
    const double extent = high[a] - low[a];
    const auto cells = std::max<std::int64_t>(1, std::llround(extent / spacing));
    grid.origin[a] = low[a] + 0.5 * (extent - static_cast<double>(cells) * spacing) + 0.5 * spacing - padding * spacing;
    grid.count[a] = cells + 2 * padding;
  }
  return grid;
}

}  // namespace mppm::pre
