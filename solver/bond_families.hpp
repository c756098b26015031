// Families within the horizon (docs/theory.md section 1), stored from both ends in CSR form: the bonds of
// owned point i are offset[i] .. offset[i+1]-1, each with its neighbour's local index. The
// reference bond vector xi = x_j - x_i is computed from the positions where it is needed (the
// same bits as a stored one, and 8 D bytes per bond less to store and stream); only periodic
// verification lattices store it, wrapped to the minimum image (bond_vector below). Every
// point owns its own bond list, so kernels write only the point they loop over (no atomics,
// no races).
#pragma once
#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "solver/point_data.hpp"

namespace mppm::solver {

struct BondFamilies {
  int dimension = 2;
  std::vector<std::int64_t> offset;  // owned + 1 entries
  // Local index of the neighbour (owned or ghost). A bond broken by damage keeps its entry with the
  // sign bit set (break_bond): the force pass reads the index anyway, so the test costs it no
  // load, and no per-bond flag array is needed (1 B per bond entry).
  std::vector<std::int32_t> neighbor;
  std::vector<double> xi;  // D per bond, periodic lattices only (else empty)
  // Damage effect only (empty otherwise):
  // W_ij [J/m^6] of every bond pair, stored once, at its lower-index end (lower global id in a
  // distributed run: PointOrder): the pairs of point i are its bonds to higher ones (the tail of
  // its sorted list), the k-th of them at
  // work[pair_offset[i] + k]. The force pass computes a bond's work at that end only (the other end
  // would give the same bits), so a copy at the other end would cost 8 B per bond entry for nothing.
  std::vector<double> work;
  std::vector<std::int64_t> pair_offset;  // owned + 1 entries
  // A distributed run (the points have ghosts): the owned points whose families hold no ghost
  // (interior) and the others (border), each ascending. The force pass computes the interior while
  // the ghosts' values travel (docs/theory.md section 13). Both empty on one process.
  std::vector<std::size_t> interior_points, border_points;

  std::size_t bond_count() const { return neighbor.size(); }
  std::size_t pair_count() const { return work.size(); }

  // The first bond of point i to a higher index (damage: pair_offset filled), without the
  // bisection of first_bond_above: point i's pairs are the tail of its list.
  std::int64_t first_pair_bond(std::size_t i) const { return offset[i + 1] - (pair_offset[i + 1] - pair_offset[i]); }

  // The bond acts (it is not broken).
  bool acting(std::int64_t b) const { return neighbor[static_cast<std::size_t>(b)] >= 0; }
  // The neighbour's index, broken or not.
  std::size_t neighbor_of(std::int64_t b) const { return index_of(neighbor[static_cast<std::size_t>(b)]); }
  // Breaks bond entry b for good (its other end is a separate entry).
  void break_bond(std::int64_t b) { neighbor[static_cast<std::size_t>(b)] |= kBrokenBit; }

  static constexpr std::int32_t kBrokenBit = INT32_MIN;
  static std::size_t index_of(std::int32_t entry) { return static_cast<std::size_t>(entry & INT32_MAX); }
};

// The order of the neighbour lists: by global id in a distributed run (PointData::global_id), by
// local index (which is the global id) on one process.
struct PointOrder {
  std::span<const std::int64_t> global_id;  // empty: the local index
  PointOrder() = default;
  explicit PointOrder(const PointData& p) : global_id(p.global_id) {}
  std::int64_t operator()(std::size_t i) const {
    return global_id.empty() ? static_cast<std::int64_t>(i) : global_id[i];
  }
};

// The first bond of point i to a neighbour later in the order (neighbours are sorted by it).
inline std::int64_t first_bond_above(const BondFamilies& f, std::size_t i, PointOrder order = {}) {
  const std::int32_t* first = f.neighbor.data() + f.offset[i];
  const std::int32_t* last = f.neighbor.data() + f.offset[i + 1];
  const std::int64_t key = order(i);
  return std::upper_bound(first, last, key,
                          [&](std::int64_t v, std::int32_t e) { return v < order(BondFamilies::index_of(e)); }) -
         f.neighbor.data();
}

// The entry of bond (j, i) in owned point j's list (by bisection: neighbours are sorted), -1 if j
// has none.
inline std::int64_t mirror_bond(const BondFamilies& f, std::size_t i, std::size_t j, PointOrder order = {}) {
  const std::int32_t* first = f.neighbor.data() + f.offset[j];
  const std::int32_t* last = f.neighbor.data() + f.offset[j + 1];
  const std::int64_t key = order(i);
  const std::int32_t* it = std::lower_bound(
      first, last, key, [&](std::int32_t e, std::int64_t v) { return order(BondFamilies::index_of(e)) < v; });
  return it != last && BondFamilies::index_of(*it) == i ? static_cast<std::int64_t>(it - f.neighbor.data()) : -1;
}

// W_ij of bond b of point i (damage), read from either end of the bond.
double bond_work(const BondFamilies& f, std::size_t i, std::int64_t b);

// xi of bond b of point i: x_j - x_i from the positions, or the stored minimum image.
template <int D>
inline void bond_vector(const BondFamilies& f, const double* position, std::size_t i, std::int64_t b, double* xi) {
  if (!f.xi.empty()) {
    for (int a = 0; a < D; ++a) xi[a] = f.xi[static_cast<std::size_t>(b) * D + a];
  } else {
    const std::size_t j = f.neighbor_of(b);
    for (int a = 0; a < D; ++a) xi[a] = position[j * D + a] - position[i * D + a];
  }
}
inline void bond_vector(const BondFamilies& f, const PointData& p, std::size_t i, std::int64_t b, double* xi) {
  if (p.dimension == 2)
    bond_vector<2>(f, p.position.data(), i, b, xi);
  else
    bond_vector<3>(f, p.position.data(), i, b, xi);
}

struct FamilyOptions {
  double horizon = 0.0;
  double spacing = 0.0;  // tolerance 1e-9 * spacing keeps lattice points on the sphere in
  // Period of the lattice along each axis (0 = not periodic). For verification lattices
  // (waves, layers): bonds then use the minimum image, and each period must exceed 2 horizons.
  std::array<double, 3> period{0.0, 0.0, 0.0};
};

// Cell-list search (brute force with minimum images when periodic). Neighbours of each point
// are sorted by index (by global id in a distributed run: PointData::global_id, PointOrder), so the
// storage does not depend on the search order, the thread count or the partition.
// With ghosts it also splits the owned points into interior and border (split_interior_and_border).
BondFamilies build_families(const PointData& points, const FamilyOptions& options);

// Sets interior_points and border_points from the neighbour lists (a neighbour at or above `owned`
// is a ghost).
void split_interior_and_border(BondFamilies& families, std::size_t owned);

// Fills pair_offset and sizes work (zero) for the bond pairs (damage), each at its end earlier in
// `order`. Families must be symmetric (every bond between owned points stored from both ends; a
// ghost's list is its owner's); throws std::logic_error if not.
void index_bond_pairs(BondFamilies& families, PointOrder order = {});

// Removes the bonds for which cut(bond) is true from both ends; `cut` must be symmetric.
template <class Predicate>
void remove_bonds(BondFamilies& families, Predicate&& cut) {
  const int D = families.dimension;
  std::size_t kept = 0;
  std::int64_t start = 0;
  for (std::size_t i = 0; i + 1 < families.offset.size(); ++i) {
    const std::int64_t end = families.offset[i + 1];
    for (std::int64_t b = start; b < end; ++b) {
      if (cut(i, static_cast<std::size_t>(b))) continue;
      families.neighbor[kept] = families.neighbor[b];
      if (!families.xi.empty())
        for (int c = 0; c < D; ++c) families.xi[kept * D + c] = families.xi[b * D + c];
      ++kept;
    }
    start = end;
    families.offset[i + 1] = static_cast<std::int64_t>(kept);
  }
  families.neighbor.resize(kept);
  if (!families.xi.empty()) families.xi.resize(kept * D);
  if (!families.pair_offset.empty()) throw std::logic_error("remove_bonds: call it before index_bond_pairs");
}

}  // namespace mppm::solver
