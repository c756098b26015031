// One bond as the force passes read it (docs/theory.md section 2): its neighbour, bond vector,
// the neighbour's volume and micro-rotation (read_bond), and the composite state U of the bond
// (composite_state). Plain doubles and compile-time extents, inlined into the bond loops.
#pragma once
#include <cstddef>
#include <cstdint>

#include "solver/multiply_add.hpp"

namespace mppm::solver::kernel {

// U = (u_j - u_i) - 1/2 (w_i + w_j) x xi: the composite state, with the MINUS sign of the fix in
// docs/theory.md section 2 (with `+` a rigid rotation u = theta x x, w = theta would not be strain free).
// Without micropolar, U = u_j - u_i.
template <int D, int R, bool Polar>
[[gnu::always_inline]] inline void composite_state(const double* ui, const double* uj, const double* wi,
                                                   const double* wj, const double* xi, double* U) {
  for (int a = 0; a < D; ++a) U[a] = uj[a] - ui[a];
  if constexpr (Polar) {
    if constexpr (D == 2) {
      const double wm = 0.5 * (wi[0] + wj[0]);
      U[0] = multiply_add(wm, xi[1], U[0]);  // -(w x xi)_x = +w xi_y
      U[1] = multiply_add(-wm, xi[0], U[1]);
    } else {
      const double wm[3] = {0.5 * (wi[0] + wj[0]), 0.5 * (wi[1] + wj[1]), 0.5 * (wi[2] + wj[2])};
      U[0] -= multiply_add(wm[1], xi[2], -wm[2] * xi[1]);
      U[1] -= multiply_add(wm[2], xi[0], -wm[0] * xi[2]);
      U[2] -= multiply_add(wm[0], xi[1], -wm[1] * xi[0]);
    }
  }
}

// A bond of point i: the neighbour j, the bond vector xi, V_j and w_j (R per point; without
// micropolar the zero rotation the caller passed).
template <int D>
struct BondView {
  std::size_t j;
  double xi[D];
  double vj;
  const double* wj;
};

// Reads bond b of point i (reference position pos_i) into `bond`; false for a broken bond (with
// damage: BondFamilies::kBrokenBit in its neighbour entry), which the force passes skip. The bond
// vector is stored (periodic lattices, StoredXi) or the difference of the positions. Without
// micropolar, w is the caller's zero rotation and every bond gets it.
template <int D, int R, bool Polar, bool Damage, bool StoredXi>
[[gnu::always_inline]] inline bool read_bond(std::int64_t b, const std::int32_t* __restrict nb,
                                             const double* __restrict xis, const double* __restrict pos,
                                             const double* pos_i, const double* __restrict vol, const double* w,
                                             BondView<D>& bond) {
  const std::int32_t entry = nb[b];
  if constexpr (Damage)
    if (entry < 0) return false;  // broken (BondFamilies::kBrokenBit)
  const auto j = static_cast<std::size_t>(entry);
  bond.j = j;
  for (int a = 0; a < D; ++a) bond.xi[a] = StoredXi ? xis[b * D + a] : pos[j * D + a] - pos_i[a];
  bond.vj = vol[j];
  bond.wj = Polar ? w + j * R : w;
  return true;
}

}  // namespace mppm::solver::kernel
