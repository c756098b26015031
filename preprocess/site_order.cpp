// The Z-order numbering of the lattice's sites (see site_order.hpp).
#include "preprocess/site_order.hpp"

namespace mppm::pre {

namespace {

using Site = std::array<std::int64_t, 3>;

// Appends the occupied sites of the grid inside the cube of `edge` sites per side (a power of two)
// at `corner`, in Z-order: the cube's eight (2-D: four) halves in turn, z slowest and x fastest.
void append_cube(const LatticeGrid& grid, std::span<const std::uint8_t> occupied, const Site& corner, std::int64_t edge,
                 std::vector<std::int64_t>& order) {
  for (int a = 0; a < 3; ++a)
    if (corner[a] >= grid.count[a]) return;
  if (edge == 1) {
    const std::int64_t g = grid.index(corner[0], corner[1], corner[2]);
    if (occupied[static_cast<std::size_t>(g)]) order.push_back(g);
    return;
  }
  const std::int64_t half = edge / 2;
  const int z_halves = grid.dimension == 3 ? 2 : 1;
  for (int z = 0; z < z_halves; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x)
        append_cube(grid, occupied, {corner[0] + x * half, corner[1] + y * half, corner[2] + z * half}, half, order);
}

}  // namespace

std::vector<std::int64_t> sites_in_z_order(const LatticeGrid& grid, std::span<const std::uint8_t> occupied) {
  std::int64_t edge = 1;
  while (edge < grid.count[0] || edge < grid.count[1] || edge < grid.count[2]) edge *= 2;
  std::vector<std::int64_t> order;
  append_cube(grid, occupied, {0, 0, 0}, edge, order);
  return order;
}

}  // namespace mppm::pre
