// The uniform lattice: cell centres of a grid aligned with the body's bounding box (docs/scene.md:
// a 100 x 40 mm plate at 0.5 mm gives exactly 200 x 80 points), optionally padded by whole cells
// on every side to hold the fictitious boundary layers.
#pragma once
#include <array>
#include <cstdint>

#include "preprocess/geometry_model.hpp"

namespace mppm::pre {

struct LatticeGrid {
  int dimension = 2;
  double spacing = 0.0;                        // dx [m]
  Vec3 origin{};                               // centre of cell (0, 0, 0)
  std::array<std::int64_t, 3> count{1, 1, 1};  // cells per axis (z: 1 in 2-D)

  std::int64_t size() const { return count[0] * count[1] * count[2]; }
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const { return (k * count[1] + j) * count[0] + i; }
  double coordinate(int axis, std::int64_t i) const { return origin[axis] + static_cast<double>(i) * spacing; }
  std::array<std::int64_t, 3> site(std::int64_t flat) const {
    return {flat % count[0], (flat / count[0]) % count[1], flat / (count[0] * count[1])};
  }
  Vec3 position(std::int64_t flat) const {
    const auto [i, j, k] = site(flat);
    return {coordinate(0, i), coordinate(1, j), dimension == 2 ? 0.0 : coordinate(2, k)};
  }
};

// Number of cells along an extent L: round(L/dx) (at least 1), so that the lattice volume
// n dx matches the body's extent to within dx/2 per axis (ceil would add up to a whole extra
// layer of points: +4 % on a 100 x 20 x 10 mm part at 0.27 mm). The cells are centred on the
// box, so a symmetric body gets a symmetric lattice, and the next lattice position beyond the
// last one lies at least dx/4 outside the box: no point of the body is ever left off the grid.
// `padding` extra cells are added on both sides of every axis in use.
LatticeGrid lattice_for_box(const Vec3& low, const Vec3& high, double spacing, int dimension, int padding);

}  // namespace mppm::pre
