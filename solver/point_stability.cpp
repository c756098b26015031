// The stiffness block of one point's degrees of freedom in closed form (point_stability.hpp).
//
// A field that moves only point i, u_i = a, w_i = theta (q = (a, theta)), strains two kinds of
// points (docs/theory.md sections 2-3; c_i = K_i^-1 s_i with s_i = sum_j b V_j xi_ij, F_i = sum_j b V_j):
//  - point i: U_ij = -a - 1/2 theta x xi_ij for every bond, so eps_i = -a (x) c_i - 1/2 [theta]_x,
//    kap_i = -theta (x) c_i, and the stabilization residuals z_ij = -a (1 - c_i . xi_ij),
//    zw_ij = -theta (1 - c_i . xi_ij) give 1/2 V_i (F_i - s_i . c_i)(a . Ck_i a + g_i |theta|^2);
//  - every k with i in its family (xi_ki = -xi_ik, d = K_k^-1 xi_ki, r = V_i xi_ki . d <= 1):
//    only the bond k-i moves, U_ki = a + 1/2 theta x xi_ik, so eps_k = V_i U_ki (x) d,
//    kap_k = V_i theta (x) d (both of rank one: their energy in closed form, rank_one_energy), and
//    the stabilization gives 1/2 V_k V_i (1 - r)(U . Ck_k U + g_k |theta|^2).
// The energy is 1/2 q^T H_i q, assembled from these linear maps of q.
#include "solver/point_stability.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "solver/compiled_effects.hpp"
#include "solver/symmetric_tensor.hpp"

namespace mppm::solver {

namespace {

template <int D>
using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

// theta x xi as a linear map of theta (D x R): 2-D (-xi_y, xi_x); 3-D -[xi]_x.
template <int D>
Eigen::Matrix<double, D, rotation_components<D>> cross_map(const double* xi) {
  Eigen::Matrix<double, D, rotation_components<D>> m;
  if constexpr (D == 2) {
    m << -xi[1], xi[0];
  } else {
    m << 0.0, xi[2], -xi[1], -xi[2], 0.0, xi[0], xi[1], -xi[0], 0.0;
  }
  return m;
}

// Adds V x (eps : sigma(eps) + kap : m(kap)) as a bilinear form over the probe basis, for
// eps = E[p] and kap = G[p] (p = 0..n-1), i.e. twice the elastic energy of the point.
template <int D, int N>
void add_elastic(const CosseratConstants& c, double volume, const std::array<Mat<D>, N>& eps,
                 const std::array<Eigen::Matrix<double, rotation_components<D>, D, Eigen::RowMajor>, N>* kap,
                 Eigen::Matrix<double, N, N>& H) {
  constexpr int R = rotation_components<D>;
  for (int p = 0; p < N; ++p) {
    const Mat<D> sp = cosserat_stress<D>(eps[p], c);
    Eigen::Matrix<double, R, D, Eigen::RowMajor> mp;
    if (kap) mp = couple_stress<D, R>((*kap)[p], c);
    for (int q = p; q < N; ++q) {
      double v = eps[q].cwiseProduct(sp).sum();
      if (kap) v += (*kap)[q].cwiseProduct(mp).sum();
      H(p, q) += volume * v;
      if (q != p) H(q, p) += volume * v;
    }
  }
}

// (t + r) d d^T + s |d|^2 1: e : law(e) = a^T [this] a for e = a (x) d under the isotropic law
// t tr(e) 1 + s e + r e^T (isotropic_cosserat_law). In plain doubles, the outer product as
// ((t + r) d_a) d_b: the order of the Eigen expression it replaced, so the blocks kept their bits.
template <int D>
[[gnu::always_inline]] inline void rank_one_energy(const double* d, double d2, double trace_modulus,
                                                   double symmetric_modulus, double transpose_modulus,
                                                   double (&out)[D][D]) {
  const double outer_modulus = trace_modulus + transpose_modulus;
  const double diagonal = symmetric_modulus * d2;
  for (int a = 0; a < D; ++a) {
    const double scaled = outer_modulus * d[a];
    for (int e = 0; e < D; ++e) out[a][e] = scaled * d[e];
    out[a][a] += diagonal;
  }
}

// The terms of a neighbour k whose family holds i (the second kind above): the share of H_i's
// translation block, S = V_k V_i^2 [(t + r) d d^T + s |d|^2 1] + w Ck_k (t, s, r the isotropic
// law's trace, symmetric and transpose moduli: rank_one_energy), with d = K_k^-1 xi_ki, |d|^2,
// V_k V_i^2 and w = V_k V_i (1 - r_k), r_k = min(1, V_i xi_ki . d). (eps_k = V_i U_ki (x) d is of rank
// one, so its elastic energy is this closed form, without a stress per probe.)
template <int D>
struct NeighbourTerms {
  double strain[D][D];  // S, row-major
  double d[D];
  double d2;
  double vk_vi2;
  double w;
};

// In plain doubles, each product and sum in the order the Eigen expressions it replaces took
// (K^-1 xi and the dot products summed from the first component), so that the blocks keep their
// bits. With Eigen's small temporaries, which went through memory, the non-polar 3-D benchmark
// block's values took 0.14-0.15 s at 1 thread, against 0.12-0.13 s now.
template <int D>
[[gnu::always_inline]] inline NeighbourTerms<D> neighbour_terms(const double* kinv_k, const double* ck_k,
                                                                const double* xi_ik, double vi, double vk,
                                                                const CosseratConstants& c) {
  NeighbourTerms<D> n;
  double xi_ki[D];
  for (int a = 0; a < D; ++a) xi_ki[a] = -xi_ik[a];
  for (int a = 0; a < D; ++a) {
    double sum = kinv_k[symmetric_index<D>(a, 0)] * xi_ki[0];
    for (int e = 1; e < D; ++e) sum += kinv_k[symmetric_index<D>(a, e)] * xi_ki[e];
    n.d[a] = sum;
  }
  double d2 = n.d[0] * n.d[0], xi_d = xi_ki[0] * n.d[0];
  for (int a = 1; a < D; ++a) {
    d2 += n.d[a] * n.d[a];
    xi_d += xi_ki[a] * n.d[a];
  }
  n.d2 = d2;
  n.vk_vi2 = vk * vi * vi;
  const double r = std::min(1.0, vi * xi_d);
  n.w = vk * vi * (1.0 - r);
  double m[D][D];
  rank_one_energy<D>(n.d, d2, c.lambda, c.mu + c.mu_c, c.mu - c.mu_c, m);
  for (int a = 0; a < D; ++a)
    for (int e = 0; e < D; ++e) n.strain[a][e] = n.vk_vi2 * m[a][e] + n.w * ck_k[symmetric_index<D>(a, e)];
  return n;
}

// The blocks of L^T S L (S symmetric, L = [1, C], C = 1/2 theta x xi as a map of theta) that hold
// the rotations, added to `coupling` (S C, whose transpose is the other off-diagonal block) and
// `rotation` (C^T S C). Written out in plain doubles: C has a zero diagonal in 3-D, and with Eigen's
// fixed-size products of L the point blocks of the 3-D benchmark block took a third longer (0.63 s
// against 0.47 s). In 2-D each sum is in the order Eigen's 2 x 2 products took (the first
// component's product plus the second's), so that the blocks keep their bits.
template <int D>
[[gnu::always_inline]] inline void add_rotation_blocks(
    const double (&S)[D][D], const double* xi, double (&coupling)[D][rotation_components<D>],
    double (&rotation)[rotation_components<D>][rotation_components<D>]) {
  if constexpr (D == 2) {
    const double c0 = 0.5 * -xi[1], c1 = 0.5 * xi[0];  // C = 1/2 (-xi_y, xi_x) (cross_map)
    const double sc0 = S[0][0] * c0 + S[0][1] * c1, sc1 = S[1][0] * c0 + S[1][1] * c1;
    coupling[0][0] += sc0;
    coupling[1][0] += sc1;
    rotation[0][0] += c0 * sc0 + c1 * sc1;
  } else {
    const double h0 = 0.5 * xi[0], h1 = 0.5 * xi[1], h2 = 0.5 * xi[2];
    double sc[3][3];  // S C, C = -[h]_x (cross_map)
    for (int a = 0; a < 3; ++a) {
      sc[a][0] = h1 * S[a][2] - h2 * S[a][1];
      sc[a][1] = h2 * S[a][0] - h0 * S[a][2];
      sc[a][2] = h0 * S[a][1] - h1 * S[a][0];
    }
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < 3; ++j) coupling[a][j] += sc[a][j];
    for (int j = 0; j < 3; ++j) {
      rotation[0][j] += h1 * sc[2][j] - h2 * sc[1][j];
      rotation[1][j] += h2 * sc[0][j] - h0 * sc[2][j];
      rotation[2][j] += h0 * sc[1][j] - h1 * sc[0][j];
    }
  }
}

template <int D, bool Polar>
Eigen::Matrix<double, D + (Polar ? rotation_components<D> : 0), D + (Polar ? rotation_components<D> : 0)> block(
    const PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i) {
  constexpr int R = Polar ? rotation_components<D> : 0;
  constexpr int RR = rotation_components<D>;
  constexpr int N = D + R;
  using Block = Eigen::Matrix<double, N, N>;
  using RMat = Eigen::Matrix<double, RR, D, Eigen::RowMajor>;
  Block H = Block::Zero();
  if (p.detached[i]) return H;
  const double vi = p.volume[i];
  constexpr int S = symmetric_components<D>;
  const Mat<D> kinv_i = unpack_symmetric<D>(&p.shape_inverse[i * S]);
  const Mat<D> ck_i = unpack_symmetric<D>(&p.stabilization_ck[i * S]);
  // s_i = sum_j V_j xi_ij in plain doubles (an Eigen bond vector went through memory: shape_tensor.cpp).
  double s_sum[D] = {};
  double family = 0.0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    if (!f.acting(b)) continue;
    const double vj = p.volume[static_cast<std::size_t>(f.neighbor[b])];
    double xi[D];
    bond_vector<D>(f, p.position.data(), i, b, xi);
    for (int a = 0; a < D; ++a) s_sum[a] += vj * xi[a];
    family += vj;
  }
  const Vec<D> s = Eigen::Map<const Vec<D>>(s_sum);
  const Vec<D> ci = kinv_i * s;

  // Point i. Probe p: a = e_p (p < D) or theta = e_(p-D).
  std::array<Mat<D>, N> eps{};
  std::array<RMat, N> kap{};
  for (int q = 0; q < N; ++q) {
    eps[q].setZero();
    kap[q].setZero();
    if (q < D) {
      eps[q].row(q) = -ci.transpose();
    } else {
      // -1/2 [theta]_x with theta = e_(q-D): column k of [theta]_x is theta x e_k.
      Vec<D> ek;
      for (int k = 0; k < D; ++k) {
        ek.setZero();
        ek(k) = 1.0;
        eps[q].col(k) = -0.5 * cross_map<D>(ek.data()).col(q - D);
      }
      kap[q].row(q - D) = -ci.transpose();
    }
  }
  add_elastic<D, N>(c, vi, eps, Polar ? &kap : nullptr, H);
  const double residual_i = std::max(0.0, family - s.dot(ci));  // F_i - s . K^-1 s >= 0
  H.template topLeftCorner<D, D>() += vi * residual_i * ck_i;
  if constexpr (Polar)
    H.template bottomRightCorner<R, R>().diagonal().array() += vi * residual_i * p.stabilization_rot[i];

  // Every neighbour whose family holds i (the reverse bond acts exactly when this one does). The
  // blocks are summed in locals, each in the same order as into H; the two off-diagonal blocks
  // are transposes of each other (H is symmetric so far, and both get the same terms), so one sum
  // serves both. (Summed in H, in memory, each term waited for the previous one's store.)
  double translation[D][D];
  for (int a = 0; a < D; ++a)
    for (int e = 0; e < D; ++e) translation[a][e] = H(a, e);
  double coupling[D][RR] = {}, rotation[RR][RR] = {};
  if constexpr (Polar)
    for (int j = 0; j < R; ++j) {
      for (int a = 0; a < D; ++a) coupling[a][j] = H(a, D + j);
      for (int l = 0; l < R; ++l) rotation[j][l] = H(D + j, D + l);
    }
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    if (!f.acting(b)) continue;
    const auto k = static_cast<std::size_t>(f.neighbor[b]);
    if (p.detached[k]) continue;  // (a ghost's terms are its owner's: share_shape_terms)
    double xi_ik[D];
    bond_vector<D>(f, p.position.data(), i, b, xi_ik);
    const NeighbourTerms<D> n =
        neighbour_terms<D>(&p.shape_inverse[k * S], &p.stabilization_ck[k * S], xi_ik, vi, p.volume[k], c);
    for (int a = 0; a < D; ++a)
      for (int e = 0; e < D; ++e) translation[a][e] += n.strain[a][e];
    if constexpr (Polar) {
      // L^T S L for the symmetric S, by its blocks [S, S C; (S C)^T, C^T S C]: the identity's
      // products are not formed (S itself is the translation block's share above).
      add_rotation_blocks<D>(n.strain, xi_ik, coupling, rotation);
      if constexpr (D == 2) {
        rotation[0][0] += n.vk_vi2 * c.bending_modulus * n.d2;
      } else {
        double m[D][D];
        rank_one_energy<D>(n.d, n.d2, c.a1, c.a2, c.a3, m);
        for (int a = 0; a < D; ++a)
          for (int e = 0; e < D; ++e) rotation[a][e] += n.vk_vi2 * m[a][e];
      }
      for (int j = 0; j < R; ++j) rotation[j][j] += n.w * p.stabilization_rot[k];
    }
  }
  for (int a = 0; a < D; ++a)
    for (int e = 0; e < D; ++e) H(a, e) = translation[a][e];
  if constexpr (Polar)
    for (int j = 0; j < R; ++j) {
      for (int a = 0; a < D; ++a) H(a, D + j) = H(D + j, a) = coupling[a][j];
      for (int l = 0; l < R; ++l) H(D + j, D + l) = rotation[j][l];
    }
  return H;
}

// M^-1/2 H M^-1/2 with M = rho V (translation), I V (rotation).
template <int N>
void scale_by_mass(const PointData& p, const CosseratConstants& c, std::size_t i, int D,
                   Eigen::Matrix<double, N, N>& H) {
  Eigen::Matrix<double, N, 1> scale;
  for (int q = 0; q < N; ++q) scale(q) = 1.0 / std::sqrt(p.volume[i] * (q < D ? c.density : c.micro_inertia));
  H = scale.asDiagonal() * H * scale.asDiagonal();
}

template <int N>
double largest(const Eigen::Matrix<double, N, N>& H) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(H, Eigen::EigenvaluesOnly);
  return std::max(0.0, eig.eigenvalues()(N - 1));
}

// The same for a part (at most 3 x 3) from Eigen's closed form: a patch centre needs no more
// accuracy.
template <int N>
double largest_in_closed_form(const Eigen::Matrix<double, N, N>& H) {
  if constexpr (N == 1) {
    return std::max(0.0, H(0, 0));
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig;
    eig.computeDirect(H, Eigen::EigenvaluesOnly);
    return std::max(0.0, eig.eigenvalues()(N - 1));
  }
}

template <int D, bool Polar>
double eigenvalue(const PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i) {
  if (p.detached[i]) return 0.0;
  auto H = block<D, Polar>(p, f, c, i);
  scale_by_mass(p, c, i, D, H);
  return largest(H);
}

// The values of a micro-polar block's translational and rotational parts.
template <int D>
std::array<double, 2> part_eigenvalues(const PointData& p, const BondFamilies& f, const CosseratConstants& c,
                                       std::size_t i) {
  constexpr int R = rotation_components<D>;
  if (p.detached[i]) return {0.0, 0.0};
  auto H = block<D, true>(p, f, c, i);
  scale_by_mass(p, c, i, D, H);
  const Eigen::Matrix<double, D, D> translational = H.template topLeftCorner<D, D>();
  const Eigen::Matrix<double, R, R> rotational = H.template bottomRightCorner<R, R>();
  return {largest_in_closed_form(translational), largest_in_closed_form(rotational)};
}

}  // namespace

double point_block_eigenvalue(const PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i) {
  const bool polar = !p.rotation.empty();
  if (p.dimension == 2) return polar ? eigenvalue<2, true>(p, f, c, i) : eigenvalue<2, false>(p, f, c, i);
  return polar ? eigenvalue<3, true>(p, f, c, i) : eigenvalue<3, false>(p, f, c, i);
}

void point_stiffness_block(const PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i,
                           double* out) {
  auto copy = [&](const auto& H) {
    for (int r = 0; r < H.rows(); ++r)
      for (int col = 0; col < H.cols(); ++col) out[r * H.cols() + col] = H(r, col);
  };
  const bool polar = !p.rotation.empty();
  if (p.dimension == 2) {
    if (polar)
      copy(block<2, true>(p, f, c, i));
    else
      copy(block<2, false>(p, f, c, i));
  } else {
    if (polar)
      copy(block<3, true>(p, f, c, i));
    else
      copy(block<3, false>(p, f, c, i));
  }
}

namespace {

// value(i) of every owned point, on the threads (each writes only its own entry).
template <class Value>
std::vector<std::invoke_result_t<Value, std::size_t>> per_point(const PointData& p, Value&& value) {
  const auto n = static_cast<std::int64_t>(p.owned);
  std::vector<std::invoke_result_t<Value, std::size_t>> out(p.owned);
#pragma omp parallel for schedule(static)
  for (std::int64_t s = 0; s < n; ++s) out[static_cast<std::size_t>(s)] = value(static_cast<std::size_t>(s));
  return out;
}

// Every owned point's block value (0 for the layers' points when `body_only`).
std::vector<double> block_values(const PointData& p, const BondFamilies& f, const CosseratConstants& c,
                                 bool body_only) {
  return per_point(
      p, [&](std::size_t i) { return !body_only || p.region[i] == 0 ? point_block_eigenvalue(p, f, c, i) : 0.0; });
}

// The first of the largest of `value(i)`, over the body points or all, whatever the thread count.
template <class Value>
void take_largest(StiffestPoint& out, const PointData& p, Value&& value, bool body_only) {
  for (std::size_t i = 0; i < p.owned; ++i)
    if ((!body_only || p.region[i] == 0) && value(i) > out.block_eigenvalue) out = {i, value(i)};
}

}  // namespace

StiffestPoints stiffest_points(const PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  const std::vector<double> value = block_values(p, f, c, false);
  StiffestPoints out;
  const auto at = [&](std::size_t i) { return value[i]; };
  take_largest(out.any, p, at, false);
  take_largest(out.body, p, at, true);
  return out;
}

StiffestParts stiffest_parts(const PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  StiffestParts out;
  if (p.rotation.empty()) return out;
  const std::vector<std::array<double, 2>> value = per_point(p, [&](std::size_t i) {
    return p.dimension == 2 ? part_eigenvalues<2>(p, f, c, i) : part_eigenvalues<3>(p, f, c, i);
  });
  take_largest(
      out.translational, p, [&](std::size_t i) { return value[i][0]; }, false);
  take_largest(
      out.rotational, p, [&](std::size_t i) { return value[i][1]; }, false);
  return out;
}

double max_point_block_eigenvalue(const PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  const std::vector<double> value = block_values(p, f, c, true);
  // The maximum does not depend on the order, so any thread count gives the same value.
  return value.empty() ? 0.0 : *std::max_element(value.begin(), value.end());
}

}  // namespace mppm::solver
