// Symmetric D x D tensors of a point (K^-1 and C:K^-1) stored as their upper triangle, row by row:
// 2-D (xx, xy, yy), 3-D (xx, xy, xz, yy, yz, zz). The full tensors are exactly symmetric (K^-1 is
// symmetrized when it is computed, and C:K^-1 is built from it), so unpacking gives the same bits
// as the full storage did, for 3 doubles per point less in 3-D (1 in 2-D) per tensor.
#pragma once
#include <Eigen/Dense>

namespace mppm::solver {

template <int D>
inline constexpr int symmetric_components = D*(D + 1) / 2;

// Position of entry (r, c) of a symmetric D x D tensor in its packed upper triangle.
template <int D>
constexpr int symmetric_index(int r, int c) {
  const int lo = r < c ? r : c, hi = r < c ? c : r;
  return lo * D - lo * (lo - 1) / 2 + (hi - lo);
}

template <int D>
inline Eigen::Matrix<double, D, D, Eigen::RowMajor> unpack_symmetric(const double* packed) {
  Eigen::Matrix<double, D, D, Eigen::RowMajor> m;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) m(r, c) = packed[symmetric_index<D>(r, c)];
  return m;
}

// The upper triangle of m (its lower one is the same by construction).
template <int D>
inline void pack_symmetric(const Eigen::Matrix<double, D, D, Eigen::RowMajor>& m, double* packed) {
  for (int r = 0; r < D; ++r)
    for (int c = r; c < D; ++c) packed[symmetric_index<D>(r, c)] = m(r, c);
}

}  // namespace mppm::solver
