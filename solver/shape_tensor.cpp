// Shape tensors and stabilization tensors per point.
#include "solver/parallel_policy.hpp"
#include "solver/shape_tensor.hpp"

#include <Eigen/Eigenvalues>

namespace mppm::solver {

namespace {

template <int D>
std::size_t update(PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
  using Vec = Eigen::Matrix<double, D, 1>;
  const auto n = static_cast<std::int64_t>(p.owned);
  const bool has_rot = !p.stabilization_rot.empty();
  std::size_t detached = 0;
#pragma omp parallel for schedule(static) reduction(+ : detached) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    Mat K = Mat::Zero();
    int count = 0;
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      if (!f.intact.empty() && !f.intact[b]) continue;
      const Vec xi = Eigen::Map<const Vec>(&f.xi[b * D]);
      K += p.volume[f.neighbor[b]] * xi * xi.transpose();
      ++count;
    }
    bool detach = count < D + 1;
    if (!detach) {
      const Eigen::SelfAdjointEigenSolver<Mat> eig(K, Eigen::EigenvaluesOnly);
      const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(D - 1);
      detach = !(hi > 0.0) || !(lo >= kDetachReciprocalCondition * hi);
    }
    Eigen::Map<Mat> kinv(&p.shape_inverse[i * D * D]);
    Eigen::Map<Mat> ck(&p.stabilization_ck[i * D * D]);
    p.detached[i] = detach ? 1 : 0;
    if (detach) {
      kinv.setZero();
      ck.setZero();
      if (has_rot) p.stabilization_rot[i] = 0.0;
      ++detached;
      continue;
    }
    kinv = K.inverse();
    kinv = 0.5 * (kinv + kinv.transpose()).eval();  // exact symmetry of the stored inverse
    // (C : K^-1)_ik = C_ijkl K^-1_jl = (lambda + mu) K^-1_ik + mu tr(K^-1) delta_ik (isotropic C)
    ck = c.stabilization * ((c.lambda + c.mu) * kinv + c.mu * kinv.trace() * Mat::Identity());
    if (has_rot) p.stabilization_rot[i] = c.stabilization * c.bending_modulus * kinv.trace() / D;
  }
  return detached;
}

}  // namespace

std::size_t update_shape_tensors(PointData& p, const BondFamilies& f, const CosseratConstants& c) {
  return p.dimension == 2 ? update<2>(p, f, c) : update<3>(p, f, c);
}

}  // namespace mppm::solver
