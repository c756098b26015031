// The family of an interior point of the cubic lattice, as lattice offsets: every non-zero integer
// vector n (z = 0 in 2-D) with |n| <= horizon_factor + 1e-9, the reach of the family builder
// (solver/bond_families.cpp: |xi| <= delta + 1e-9 dx). The lattice sums of the model are sums over
// these offsets: the bond count of a family (memory estimate, preprocessor report), the bonds
// crossing a plane (the damage calibration), the micro-conductivity of the pore fluid.
#pragma once
#include <cmath>
#include <cstdint>

namespace mppm {

// visit(x, y, z) for every offset of the family, in a fixed order.
template <class Visit>
void for_each_family_offset(int dimension, double horizon_factor, Visit&& visit) {
  const double reach = horizon_factor + 1e-9;
  const int m = static_cast<int>(std::floor(reach));
  const int mz = dimension == 3 ? m : 0;
  for (int z = -mz; z <= mz; ++z)
    for (int y = -m; y <= m; ++y)
      for (int x = -m; x <= m; ++x)
        if ((x || y || z) && static_cast<double>(x * x + y * y + z * z) <= reach * reach) visit(x, y, z);
}

// The number of bonds of an interior point.
inline std::int64_t family_offset_count(int dimension, double horizon_factor) {
  std::int64_t count = 0;
  for_each_family_offset(dimension, horizon_factor, [&](int, int, int) { ++count; });
  return count;
}

}  // namespace mppm
