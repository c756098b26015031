// Shape tensors and stabilization tensors per point.
#include "solver/shape_tensor.hpp"

#include <Eigen/Eigenvalues>

#include "solver/parallel_policy.hpp"
#include "solver/symmetric_tensor.hpp"

namespace mppm::solver {

namespace {

// G_s (C : K^-1) of point i from its stored K^-1: (C : K^-1)_ik = C_ijkl K^-1_jl = (lambda + mu)
// K^-1_ik + mu tr(K^-1) delta_ik (isotropic C). Zero for a detached point (K^-1 = 0).
template <int D>
void set_stabilization_tensor(PointData& p, const CosseratConstants& c, std::size_t i) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  constexpr int S = symmetric_components<D>;
  const Mat kinv = unpack_symmetric<D>(&p.shape_inverse[i * S]);
  const Mat ck = c.stabilization * ((c.lambda + c.mu) * kinv + c.mu * kinv.trace() * Mat::Identity());
  pack_symmetric<D>(ck, &p.stabilization_ck[i * S]);
}

// Recomputes K_i^-1 and the stabilization tensors of point i; returns true if it is detached.
template <int D>
bool update_point(PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  const bool has_rot = !p.stabilization_rot.empty();
  // K = sum_j V_j xi xi^T in plain doubles, each entry as (V_j xi_a) xi_b, the order of the Eigen
  // expression it replaced (so K keeps its bits): a bond vector in an Eigen vector went through
  // memory, and its reload stalled each bond (the 3-D benchmark block's shape tensors took 74 ms at
  // 1 thread).
  double k[D][D] = {};
  int count = 0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    if (!f.acting(b)) continue;
    double xi[D];
    bond_vector<D>(f, p.position.data(), i, b, xi);
    const double volume = p.volume[f.neighbor[b]];
    for (int a = 0; a < D; ++a) {
      const double scaled = volume * xi[a];
      for (int e = 0; e < D; ++e) k[a][e] += scaled * xi[e];
    }
    ++count;
  }
  const Mat K = Eigen::Map<const Mat>(&k[0][0]);
  bool detach = count < D + 1;
  if (!detach) {
    const Eigen::SelfAdjointEigenSolver<Mat> eig(K, Eigen::EigenvaluesOnly);
    const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(D - 1);
    detach = !(hi > 0.0) || !(lo >= kDetachReciprocalCondition * hi);
  }
  if (detach) {
    detach_point(p, i);
    return true;
  }
  p.detached[i] = 0;
  Mat kinv = K.inverse();
  kinv = 0.5 * (kinv + kinv.transpose()).eval();  // exact symmetry of the stored inverse
  pack_symmetric<D>(kinv, &p.shape_inverse[i * symmetric_components<D>]);
  set_stabilization_tensor<D>(p, c, i);
  if (has_rot) p.stabilization_rot[i] = c.stabilization * c.bending_modulus * kinv.trace() / D;
  return false;
}

template <int D>
std::size_t update_all(PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  const auto n = static_cast<std::int64_t>(p.owned);
  std::size_t detached = 0;
#pragma omp parallel for schedule(static) reduction(+ : detached) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t s = 0; s < n; ++s) detached += update_point<D>(p, f, c, static_cast<std::size_t>(s)) ? 1 : 0;
  return detached;
}

template <int D>
void update_some(PointData& p, const BondFamilies& f, const CosseratConstants& c,
                 const std::vector<std::size_t>& points) {
  const auto n = static_cast<std::int64_t>(points.size());
  // Each listed point writes only its own tensors; a few hundred points are not worth threads. A
  // detached point stays detached (it may keep bonds to no-fail points, which would otherwise
  // give it a lopsided shape tensor back).
#pragma omp parallel for schedule(static) if (n > 2048)
  for (std::int64_t s = 0; s < n; ++s) {
    const std::size_t i = points[static_cast<std::size_t>(s)];
    if (!p.detached[i]) update_point<D>(p, f, c, i);
  }
}

}  // namespace

void update_stabilization_tensors(PointData& p, const CosseratConstants& c) {
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (p.dimension == 2)
      set_stabilization_tensor<2>(p, c, i);
    else
      set_stabilization_tensor<3>(p, c, i);
  }
}

void detach_point(PointData& p, std::size_t i) {
  const std::size_t s = static_cast<std::size_t>(p.dimension * (p.dimension + 1) / 2);
  std::fill_n(p.shape_inverse.begin() + static_cast<std::ptrdiff_t>(i * s), s, 0.0);
  std::fill_n(p.stabilization_ck.begin() + static_cast<std::ptrdiff_t>(i * s), s, 0.0);
  if (!p.stabilization_rot.empty()) p.stabilization_rot[i] = 0.0;
  p.detached[i] = 1;
}

std::size_t update_shape_tensors(PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  return p.dimension == 2 ? update_all<2>(p, f, c) : update_all<3>(p, f, c);
}

void update_shape_tensors(PointData& p, const BondFamilies& f, const CosseratConstants& c,
                          const std::vector<std::size_t>& points) {
  p.dimension == 2 ? update_some<2>(p, f, c, points) : update_some<3>(p, f, c, points);
}

void share_shape_terms(PointData& p, bool all) {
  if (p.ghost == 0 || !p.ghost_source) return;
  const int S = p.dimension * (p.dimension + 1) / 2;
  p.ghost_source->update_ghosts(p.stabilization_ck, S);
  if (!p.stabilization_rot.empty()) p.ghost_source->update_ghosts(p.stabilization_rot, 1);
  if (!all) return;
  p.ghost_source->update_ghosts(p.shape_inverse, S);
  std::vector<double> detached(p.detached.begin(), p.detached.end());
  p.ghost_source->update_ghosts(detached, 1);
  for (std::size_t g = p.owned; g < p.total(); ++g) p.detached[g] = detached[g] != 0.0 ? 1 : 0;
}

}  // namespace mppm::solver
