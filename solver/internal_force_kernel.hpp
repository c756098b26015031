// The hot kernel: internal force and moment per unit volume of every owned point (docs/theory.md
// sections 2-4), in two passes over the CSR bonds.
//   pass 1 (per point i): eps_i, kap_i from the composite state and the relative rotation,
//     sigma_i, m_i, and the per-point tensors A_i = sigma_i K_i^-1 - G_s (C:K_i^-1) eps_i and
//     Q_i = m_i K_i^-1 - g_i kap_i (g_i = G_s B_w tr K_i^-1 / d); then point i's own share of its
//     force and moment, formed from bond sums of this pass (own_share);
//   pass 2 (per point i): with T_ij - T_ji = (A_i + A_j) xi + G_s (C:K_i^-1 + C:K_j^-1) U_ij
//     (the stabilization of both ends folded in, since z_u = U_ij - eps xi), the force
//     sum_j (T_ij - T_ji) V_j and the moment sum_j [(M_ij - M_ji) + 1/2 xi x (T_ij - T_ji)] V_j:
//     the bond loop adds the neighbours' shares (the A_j, C:K_j^-1, Q_j, g_j terms) to point i's.
// Each point writes only its own entries, so the result does not depend on the thread count.
// Templated on dimension and on the compile-time effect set: an effect that is off costs nothing.
// Viscoplasticity: sigma = C : (eps - eps_vp), m = m(kap - kap_vp); with a StepAdvance, pass 1
// first advances each point's plastic state by the return map (once per time step).
// Damage (docs/theory.md section 7): broken bonds are skipped; with a StepAdvance, pass 2 also books
// each bond's work and counts the bonds that reach the critical work, through the damage policy
// (bond_work_policy.hpp), which is empty without the effect.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/bond_kinematics.hpp"
#include "solver/bond_products.hpp"
#include "solver/bond_sums.hpp"
#include "solver/bond_work_policy.hpp"
#include "solver/compiled_effects.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/exact_point_sums.hpp"
#include "solver/internal_forces.hpp"
#include "solver/multiply_add.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/point_data.hpp"
#include "solver/step_advance.hpp"
#include "solver/symmetric_tensor.hpp"
#include "solver/unsaturated_coupling.hpp"
#include "solver/viscoplastic_point.hpp"

namespace mppm::solver::kernel {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
template <int R, int D>
using RMat = Eigen::Matrix<double, R, D, Eigen::RowMajor>;
// The force and moment tensors A and Q as PointData stores them: by columns, which the bond
// products of pass 2 load as they use them (bond_products.hpp). A one-row Q (2-D) is the same
// either way, and Eigen allows a single row only row-major.
template <int R, int D>
using ColumnTensor = Eigen::Matrix<double, R, D, R == 1 ? Eigen::RowMajor : Eigen::ColMajor>;

// The bond loops work on plain doubles with loops over compile-time extents: Eigen's small
// expression templates are not reliably inlined in a loop this large (measured: 4x slower in 3-D).
#define MPPM_INLINE inline __attribute__((always_inline))

// Twice the stabilization energy density of a point (docs/theory.md section 3), sum_j V_j [z_u . (G_s C:K_i^-1)
// z_u + g_i |z_w|^2] with z_u = U - eps_i xi and z_w = (w_j - w_i) - kap_i xi. Gathered bond by bond
// as the second moments uu = sum_j V_j U (x) U (upper triangle) and ww = sum_j V_j |w_j - w_i|^2, four
// multiply-adds per bond in 2-D (a z per bond was eleven): with eps_i = S K_i^-1 (S = sum_j V_j
// U (x) xi, K_i = sum_j V_j xi (x) xi), sum_j V_j z_u (x) z_u = uu - eps_i K_i eps_i^T, and
// sum_j V_j |z_w|^2 = ww - kap_i : (kap_i K_i). Where the field is nearly affine the two terms
// nearly cancel: what is left there is rounding of 1e-16 of uu's size, while the stabilization
// energy itself is physically zero (far below what an energy row resolves). Contracted with the
// point's constants once (C:K^-1 is symmetric).
template <int D, int R, bool Polar>
struct StabilizationEnergySum {
  double uu[D * (D + 1) / 2] = {};
  double ww = 0.0;

  MPPM_INLINE void add(const double* U, [[maybe_unused]] const double* wi, [[maybe_unused]] const double* wj,
                       double vj) {
    for (int r = 0; r < D; ++r) {
      const double vu = vj * U[r];
      for (int col = r; col < D; ++col)
        uu[symmetric_index<D>(r, col)] = multiply_add(vu, U[col], uu[symmetric_index<D>(r, col)]);
    }
    if constexpr (Polar)
      for (int r = 0; r < R; ++r) {
        const double om = wj[r] - wi[r];
        ww = multiply_add(vj * om, om, ww);
      }
  }
  // sum_j V_j [z_u . Ck z_u + g |z_w|^2] with the point's strain and wryness (row-major), its
  // stored K^-1 and C:K^-1 (packed, symmetric_tensor.hpp) and g; 0 for a detached point (K^-1 = 0).
  MPPM_INLINE double contract(const double* eps_i, [[maybe_unused]] const double* kap_i, const double* kinv_packed,
                              const double* cki, [[maybe_unused]] double gi) const {
    using M = Eigen::Matrix<double, D, D, Eigen::RowMajor>;
    const M kinv = unpack_symmetric<D>(kinv_packed);
    const double det = kinv.determinant();
    if (!(det != 0.0)) return 0.0;
    const M k = kinv.inverse();
    // eps_i K_i eps_i^T in plain loops: Eigen's product of three is emitted out of line, and its one
    // copy would be shared by the force kernel's file (fused multiply-adds) and the energies' file.
    double ek[D * D];
    for (int r = 0; r < D; ++r)
      for (int b = 0; b < D; ++b) {
        double sum = 0.0;
        for (int a = 0; a < D; ++a) sum += eps_i[r * D + a] * k(a, b);
        ek[r * D + b] = sum;
      }
    double e = 0.0;
    for (int r = 0; r < D; ++r)
      for (int col = r; col < D; ++col) {
        double eke = 0.0;
        for (int b = 0; b < D; ++b) eke += ek[r * D + b] * eps_i[col * D + b];
        const int s = symmetric_index<D>(r, col);
        e += (col == r ? 1.0 : 2.0) * cki[s] * (uu[s] - eke);
      }
    if constexpr (Polar) {
      using RM = Eigen::Matrix<double, R, D, Eigen::RowMajor>;
      const Eigen::Map<const RM> kap(kap_i);
      e += gi * (ww - kap.cwiseProduct(kap * k).sum());
    }
    return e;
  }
};

// eps_i = [sum_j V_j U_ij (x) xi] K_i^-1 and kap_i = [sum_j V_j (w_j - w_i) (x) xi] K_i^-1.
template <int D, class Effects, bool StoredXi>
MPPM_INLINE void point_strains(const PointData& p, const BondFamilies& f, std::size_t i, const Mat<D>& kinv,
                               Mat<D>& eps, RMat<rotation_components<D>, D>& kap) {
  constexpr int R = rotation_components<D>;
  BondSums<D, R> sums;
  bond_sums<D, Effects, StoredXi>(p, f, i, sums);
  eps = Eigen::Map<const Mat<D>>(sums.S) * kinv;
  if constexpr (Effects::micropolar) kap = Eigen::Map<const RMat<R, D>>(sums.Sk) * kinv;
}

// The elastic energies [J] of point i (1/2 V eps_e : sigma, the out-of-plane term of plane strain
// included, and 1/2 V kap_e : m) for its strain and wryness, with its plastic state as it is.
template <int D, class Effects>
StoredEnergy elastic_energies(const PointData& p, const CosseratConstants& c, std::size_t i, const Mat<D>& eps,
                              [[maybe_unused]] const RMat<rotation_components<D>, D>& kap) {
  constexpr int R = rotation_components<D>;
  constexpr int RD = R * D;
  const double vi = p.volume[i];
  StoredEnergy e;
  if constexpr (Effects::viscoplasticity) {
    const auto eps_elastic = viscoplastic::elastic_strain<D>(eps, &p.plastic_strain[i * 9]);
    e.force_stress =
        vi * viscoplastic::elastic_energy_density<D>(eps_elastic, viscoplastic::elastic_stress<D>(eps_elastic, c));
  } else {
    e.force_stress = 0.5 * vi * (eps.cwiseProduct(cosserat_stress<D>(eps, c))).sum();
  }
  if constexpr (Effects::micropolar) {
    RMat<R, D> kap_elastic = kap;
    if constexpr (Effects::viscoplasticity) kap_elastic -= Eigen::Map<const RMat<R, D>>(&p.plastic_wryness[i * RD]);
    e.couple_stress = 0.5 * vi * (kap_elastic.cwiseProduct(couple_stress<D, R>(kap_elastic, c))).sum();
  }
  if constexpr (Effects::pore_fluid) {
    // The fluid's stored energy V p^2 / (2 M) at this strain and the fluid content held
    // (docs/theory.md section 12): the pass-1 pressure's potential.
    // Unsaturated: the work the fluid received, booked per point (solver/unsaturated_coupling.hpp).
    if (p.region[i] == 0 && c.retention) {
      e.fluid = p.fluid_energy[i];
    } else if (p.region[i] == 0) {
      const double pressure = c.biot_modulus * (p.fluid_content_change[i] - c.biot_coefficient * eps.trace());
      e.fluid = 0.5 * vi * pressure * pressure / c.biot_modulus;
    }
  }
  return e;
}

// The elastic energies of point i at the strain and wryness of the last force evaluation (the
// stored ones; zero for a detached point): what the energy rows sum, in point order. Computed
// here rather than stored by the force pass, which saves two doubles per point for a few
// operations per point on the steps that report energies.
template <int D, class Effects>
StoredEnergy elastic_energy_of_point(const PointData& p, const CosseratConstants& c, std::size_t i) {
  constexpr int R = rotation_components<D>;
  if (p.detached[i]) return {};
  const Mat<D> eps = Eigen::Map<const Mat<D>>(&p.strain[i * D * D]);
  RMat<R, D> kap = RMat<R, D>::Zero();
  if constexpr (Effects::micropolar) kap = Eigen::Map<const RMat<R, D>>(&p.wryness[i * R * D]);
  return elastic_energies<D, Effects>(p, c, i, eps, kap);
}

// The sums over the owned points of elastic_energy_of_point and of the stabilization energies of
// the last evaluation with energies (PointData::stabilization_energy): the stored energy of an
// energy row. Summed exactly (exact_point_sums), so the same bits for any thread count; the chunks
// run in parallel (a stress evaluation per point).
template <int D, class Effects>
StoredEnergy stored_energy_sums(const PointData& p, const CosseratConstants& c) {
  const auto sums = exact_point_sums<4>(p, [&](std::size_t lo, std::size_t hi, ExactSums<4>& acc) {
    for (std::size_t i = lo; i < hi; ++i) {
      const StoredEnergy e = elastic_energy_of_point<D, Effects>(p, c, i);
      acc[0] += e.force_stress;
      acc[1] += e.couple_stress;
      acc[2] += p.stabilization_energy[i];
      acc[3] += e.fluid;
    }
  });
  StoredEnergy sum;
  sum.force_stress = sums[0];
  sum.couple_stress = sums[1];
  sum.stabilization = sums[2];
  sum.fluid = sums[3];
  return sum;
}

// The energy stored at one point [J] (force stress, couple stress, stabilization), with its bonds,
// shape tensor and plastic state as they are now: the same numbers as an evaluation with energies
// gives (elastic_energy_of_point and stabilization_energy). Breakage uses it on the few points
// whose bonds changed, before and after the change (bond_breakage.cpp).
template <int D, class Effects>
StoredEnergy stored_energy_of_point(const PointData& p, const BondFamilies& f, const CosseratConstants& c,
                                    std::size_t i) {
  constexpr int R = rotation_components<D>;
  constexpr bool polar = Effects::micropolar;
  StoredEnergy e;
  if (p.detached[i]) return e;
  const double vi = p.volume[i];
  const Mat<D> kinv = unpack_symmetric<D>(&p.shape_inverse[i * symmetric_components<D>]);
  Mat<D> eps;
  [[maybe_unused]] RMat<R, D> kap;
  if (f.xi.empty())
    point_strains<D, Effects, false>(p, f, i, kinv, eps, kap);
  else
    point_strains<D, Effects, true>(p, f, i, kinv, eps, kap);
  e = elastic_energies<D, Effects>(p, c, i, eps, kap);
  const double zero_rotation[3] = {0.0, 0.0, 0.0};
  const double* ui = &p.displacement[i * D];
  const double* wi = polar ? &p.rotation[i * R] : zero_rotation;
  const double* cki = &p.stabilization_ck[i * symmetric_components<D>];
  [[maybe_unused]] const double gi = polar ? p.stabilization_rot[i] : 0.0;
  StabilizationEnergySum<D, R, polar> stab;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    if constexpr (Effects::damage)
      if (!f.acting(b)) continue;
    const auto j = static_cast<std::size_t>(f.neighbor[b]);
    double xi[D];
    bond_vector<D>(f, p.position.data(), i, b, xi);
    const double* wj = polar ? &p.rotation[j * R] : zero_rotation;
    double U[D];
    composite_state<D, R, polar>(ui, &p.displacement[j * D], wi, wj, xi, U);
    stab.add(U, wi, wj, p.volume[j]);
  }
  e.stabilization =
      0.5 * vi *
      stab.contract(eps.data(), polar ? kap.data() : nullptr, &p.shape_inverse[i * symmetric_components<D>], cki, gi);
  return e;
}

// Point i's own share of its force and moment, from its tensors and the bond sums of pass 1:
// sum_j V_j (A_i xi + C:K_i^-1 U) = A_i m + C:K_i^-1 s, and in the moment sum_j V_j (Q_i xi +
// g_i Om) = Q_i m + g_i sw and 1/2 sum_j V_j xi x (A_i xi + C:K_i^-1 U) = 1/2 e_abc (A_i K_i +
// C:K_i^-1 S)_cb (K_i = sum_j V_j xi (x) xi, the inverse of the stored K_i^-1). Pass 2 adds the
// neighbours' shares bond by bond: taking these terms out of the bond loop saves about a third
// of its operations. The same sums, rounded otherwise than bond by bond.
template <int D, bool Polar>
MPPM_INLINE void own_share(const Mat<D>& a, const Mat<D>& ck, const Mat<D>& kinv,
                           [[maybe_unused]] const RMat<rotation_components<D>, D>& q, [[maybe_unused]] double g,
                           const BondSums<D, rotation_components<D>>& sums, double* force,
                           [[maybe_unused]] double* moment) {
  constexpr int R = rotation_components<D>;
  const Eigen::Map<const Vec<D>> m(sums.m), s(sums.s);
  Eigen::Map<Vec<D>> force_out(force);
  force_out = a * m + ck * s;
  if constexpr (Polar) {
    const Mat<D> k = kinv.inverse();
    const Mat<D> both = a * k + ck * Eigen::Map<const Mat<D>>(sums.S);
    Eigen::Matrix<double, R, 1> own = q * m;
    for (int r = 0; r < R; ++r) own(r) += g * sums.sw[r];
    if constexpr (D == 2) {
      own(0) += 0.5 * (both(1, 0) - both(0, 1));
    } else {
      own(0) += 0.5 * (both(2, 1) - both(1, 2));
      own(1) += 0.5 * (both(0, 2) - both(2, 0));
      own(2) += 0.5 * (both(1, 0) - both(0, 1));
    }
    Eigen::Map<Eigen::Matrix<double, R, 1>> moment_out(moment);
    moment_out = own;
  }
}

// Pore fluid (docs/theory.md section 12): at a body point, the pressure of the fluid content held, at
// the point's new strain, p = M (zeta - n0 - b tr eps) (the undrained update; the flow changes zeta
// between force evaluations), stored, and the total stress sigma' - b p 1 in place of sigma'.
// Unsaturated (a retention curve): p by the retention inverse and Bishop's sigma' - b S_r p 1, the
// stored fluid energy booked from the strain of the last evaluation, eps_before
// (solver/unsaturated_coupling.hpp). The fictitious layers carry no fluid.
template <int D>
MPPM_INLINE void add_pore_pressure(PointData& p, const CosseratConstants& c, std::size_t i, const Mat<D>& eps,
                                   const Eigen::Map<Mat<D>>& eps_before, Mat<D>& sigma) {
  if (p.region[i] != 0) return;
  // The saturated pressure, rounded here as the saturated model rounds it (this file is contracted
  // with FMAs), so that a point with p >= 0 has the saturated model's bits with a retention curve too.
  const double pressure = c.biot_modulus * (p.fluid_content_change[i] - c.biot_coefficient * eps.trace());
  if (c.retention) {
    const double stress =
        undrained_unsaturated_update(p, *c.retention, c.fluid_storage, i, pressure, eps.trace(), eps_before.trace());
    for (int a = 0; a < D; ++a) sigma(a, a) -= c.biot_coefficient * stress;
    return;
  }
  p.pore_pressure[i] = pressure;
  for (int a = 0; a < D; ++a) sigma(a, a) -= c.biot_coefficient * pressure;
}

// Pass 1 at point i: strain and wryness, constitutive update (the return map with `advance`),
// the force/moment tensors A_i, Q_i, and point i's own share of its force and moment (own_share;
// pass 2 adds the rest). The elastic energies come from the stored strain and wryness when they
// are asked for (elastic_energy_of_point).
template <int D, class Effects, bool StoredXi>
MPPM_INLINE void pass1_point(PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i,
                             [[maybe_unused]] const StepAdvance* advance) {
  constexpr int R = rotation_components<D>;
  constexpr bool polar = Effects::micropolar;
  constexpr int DD = D * D;
  constexpr int RD = R * D;
  [[maybe_unused]] const double* __restrict vol = p.volume.data();
  Eigen::Map<Mat<D>> eps_out(&p.strain[i * DD]);
  Eigen::Map<ColumnTensor<D, D>> a_out(&p.force_tensor[i * DD]);
  using Work = BondWorkPolicy<D, Effects>;
  // Damage, advancing: the tensor sums of the bond work, before the tensors are overwritten.
  const bool advancing = advance != nullptr;
  if (p.detached[i]) {
    Work::detached_tensor_sums(p, i, advancing);
    eps_out.setZero();
    a_out.setZero();
    for (int r = 0; r < D; ++r) p.force[i * D + r] = 0.0;
    if constexpr (polar) {
      Eigen::Map<RMat<R, D>>(&p.wryness[i * RD]).setZero();
      Eigen::Map<ColumnTensor<R, D>>(&p.moment_tensor[i * RD]).setZero();
      for (int r = 0; r < R; ++r) p.moment[i * R + r] = 0.0;
    }
    if constexpr (Effects::viscoplasticity)
      if (advance) p.plastic_dissipation[i] = 0.0;
    return;
  }
  const Mat<D> kinv = unpack_symmetric<D>(&p.shape_inverse[i * symmetric_components<D>]);
  BondSums<D, R> sums;
  bond_sums<D, Effects, StoredXi>(p, f, i, sums);
  const Mat<D> eps = Eigen::Map<const Mat<D>>(sums.S) * kinv;
  [[maybe_unused]] RMat<R, D> kap;
  if constexpr (polar) kap = Eigen::Map<const RMat<R, D>>(sums.Sk) * kinv;
  Mat<D> sigma;
  if constexpr (Effects::viscoplasticity) {
    double* plastic_strain = &p.plastic_strain[i * 9];
    // Outside material.viscoplasticity.region the point stays elastic: no return map.
    if (advance && !p.plastic_active[i]) p.plastic_dissipation[i] = 0.0;
    if (advance && p.plastic_active[i]) {
      // eps_out and the stored wryness still hold the previous evaluation: the step's start.
      p.plastic_dissipation[i] =
          vol[i] * viscoplastic::advance_point<D, R, polar>(eps, polar ? kap.data() : nullptr, Mat<D>(eps_out),
                                                            polar ? &p.wryness[i * RD] : nullptr, plastic_strain,
                                                            polar ? &p.plastic_wryness[i * RD] : nullptr,
                                                            p.equivalent_plastic_strain[i], c, *advance);
    }
    const auto eps_elastic = viscoplastic::elastic_strain<D>(eps, plastic_strain);
    const auto stress = viscoplastic::elastic_stress<D>(eps_elastic, c);
    sigma = stress.in_plane;
  } else {
    sigma = cosserat_stress<D>(eps, c);
  }
  if constexpr (Effects::pore_fluid) add_pore_pressure<D>(p, c, i, eps, eps_out, sigma);
  const Mat<D> ck = unpack_symmetric<D>(&p.stabilization_ck[i * symmetric_components<D>]);
  eps_out = eps;
  const Mat<D> a = sigma * kinv - ck * eps;
  const ColumnTensor<D, D> a_columns = a;
  Work::force_tensor_sum(p, i, a_columns.data(), advancing);
  a_out = a_columns;
  [[maybe_unused]] RMat<R, D> q;
  [[maybe_unused]] double g = 0.0;
  if constexpr (polar) {
    RMat<R, D> kap_elastic = kap;
    if constexpr (Effects::viscoplasticity) kap_elastic -= Eigen::Map<const RMat<R, D>>(&p.plastic_wryness[i * RD]);
    const RMat<R, D> m = couple_stress<D, R>(kap_elastic, c);
    g = p.stabilization_rot[i];
    q = m * kinv - g * kap;
    const ColumnTensor<R, D> q_columns = q;
    Work::moment_tensor_sum(p, i, q_columns.data(), advancing);
    Eigen::Map<RMat<R, D>>(&p.wryness[i * RD]) = kap;
    Eigen::Map<ColumnTensor<R, D>>(&p.moment_tensor[i * RD]) = q_columns;
  }
  own_share<D, polar>(a, ck, kinv, q, g, sums, &p.force[i * D], polar ? &p.moment[i * R] : nullptr);
}

// Pass 2 at point i: adds to the own share that pass 1 left in its force and moment the
// neighbours' shares, bond by bond: sum_j V_j (A_j xi + C:K_j^-1 U) to the force and
// sum_j V_j [Q_j xi + g_j Om + 1/2 xi x (A_j xi + C:K_j^-1 U)] to the moment. With
// accumulate_work (damage, advancing) the damage policy also books the bond work and counts the
// bonds that reach the critical work (bond_work_policy.hpp); with WithEnergy the point's
// stabilization energy.
template <int D, class Effects, bool WithEnergy, bool StoredXi>
MPPM_INLINE void pass2_point(PointData& p, BondFamilies& f, const CosseratConstants& c, std::size_t i,
                             bool accumulate_work) {
  constexpr int R = rotation_components<D>;
  constexpr bool polar = Effects::micropolar;
  constexpr int DD = D * D;
  constexpr int RD = R * D;
  constexpr int S = symmetric_components<D>;
  const double zero_rotation[3] = {0.0, 0.0, 0.0};
  const double* __restrict u = p.displacement.data();
  const double* __restrict w = polar ? p.rotation.data() : zero_rotation;
  const double* __restrict vol = p.volume.data();
  const double* __restrict xis = f.xi.data();
  const double* __restrict pos = p.position.data();
  const std::int32_t* __restrict nb = f.neighbor.data();
  const std::int64_t* __restrict off = f.offset.data();
  const double* __restrict a_all = p.force_tensor.data();
  const double* __restrict ck_all = p.stabilization_ck.data();
  [[maybe_unused]] const double* __restrict q_all = polar ? p.moment_tensor.data() : nullptr;
  [[maybe_unused]] const double* __restrict g_all = polar ? p.stabilization_rot.data() : zero_rotation;
  // Point i's values in locals: the loop's stores (the bond work) could alias the arrays,
  // which would make the compiler reload them for every bond.
  double ui[D], pos_i[D], wi[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < D; ++k) ui[k] = u[i * D + k];
  for (int k = 0; k < D; ++k) pos_i[k] = pos[i * D + k];
  if constexpr (polar)
    for (int k = 0; k < R; ++k) wi[k] = w[i * R + k];
  BondWorkPolicy<D, Effects> work(p, f, c, i, accumulate_work);
  double force[lane_slots<D>] = {};
  double moment[R > 0 ? lane_slots<R> : 1] = {};
  // With energies (the steps that report them), the stabilization energy from the same bonds.
  [[maybe_unused]] StabilizationEnergySum<D, R, polar> stab_energy;
  // One bond; with BooksWork (from the damage policy's first_work_bond on) also its work.
  auto visit_bond = [&]<bool BooksWork>(std::int64_t b) __attribute__((always_inline)) {
    // Nothing writes the neighbour lists during the force pass: a bond that reaches its critical
    // work here still acts in this evaluation, and update_after_breakage breaks it afterwards.
    BondView<D> bond;
    if (!read_bond<D, R, polar, Effects::damage, StoredXi>(b, nb, xis, pos, pos_i, vol, w, bond)) return;
    const std::size_t j = bond.j;
    const double* xi = bond.xi;
    const double vj = bond.vj;
    const double* wj = bond.wj;
    const double* aj = a_all + j * DD;
    const double* ckj = ck_all + j * S;
    double U[D];
    composite_state<D, R, polar>(ui, u + j * D, wi, wj, xi, U);
    double t[lane_slots<D>];  // the neighbour's share A_j xi + C:K_j^-1 U
    add_neighbour_share<D>(aj, ckj, xi, U, vj, t, force);
    if constexpr (polar) add_neighbour_moment<D, R>(q_all + j * RD, g_all[j], wi, wj, xi, t, vj, moment);
    if constexpr (BooksWork) work.add(b, j, xi, U, wi, wj, ckj);
    if constexpr (WithEnergy) stab_energy.add(U, wi, wj, vj);
  };
  if constexpr (BondWorkPolicy<D, Effects>::active) {
    const std::int64_t split = work.first_work_bond();
    for (std::int64_t b = off[i]; b < split; ++b) visit_bond.template operator()<false>(b);
    for (std::int64_t b = split; b < off[i + 1]; ++b) visit_bond.template operator()<true>(b);
  } else {
    for (std::int64_t b = off[i]; b < off[i + 1]; ++b) visit_bond.template operator()<false>(b);
  }
  for (int r = 0; r < D; ++r) p.force[i * D + r] += force[r];
  if constexpr (polar)
    for (int r = 0; r < R; ++r) p.moment[i * R + r] += moment[r];
  if constexpr (WithEnergy)
    p.stabilization_energy[i] = 0.5 * vol[i] *
                                stab_energy.contract(&p.strain[i * DD], polar ? &p.wryness[i * RD] : nullptr,
                                                     &p.shape_inverse[i * S], &ck_all[i * S], polar ? g_all[i] : 0.0);
  work.finish(p, i);
}

// The points a pass visits: a list of local indices, or (no list) 0 .. count-1.
struct PointSelection {
  const std::size_t* list = nullptr;
  std::int64_t count = 0;
  std::size_t operator[](std::int64_t s) const { return list ? list[s] : static_cast<std::size_t>(s); }
};

inline PointSelection all_owned(const PointData& p) { return {nullptr, static_cast<std::int64_t>(p.owned)}; }
inline PointSelection listed(const std::vector<std::size_t>& points) {
  return {points.data(), static_cast<std::int64_t>(points.size())};
}

// The two passes over a selection of points, shared by every evaluation: all owned points on one
// process, the interior and then the border points of a distributed run, the points around broken
// bonds. A point gives the same bits in each: the kernel fuses multiply-adds only where its source
// says so (multiply_add.hpp).
template <int D, class Effects, bool StoredXi>
void pass1_points(PointData& p, const BondFamilies& f, const CosseratConstants& c, const StepAdvance* advance,
                  PointSelection points) {
#pragma omp for schedule(static)
  for (std::int64_t s = 0; s < points.count; ++s) pass1_point<D, Effects, StoredXi>(p, f, c, points[s], advance);
}

template <int D, class Effects, bool WithEnergy, bool StoredXi>
void pass2_points(PointData& p, BondFamilies& f, const CosseratConstants& c, bool accumulate_work,
                  PointSelection points) {
#pragma omp for schedule(static)
  for (std::int64_t s = 0; s < points.count; ++s)
    pass2_point<D, Effects, WithEnergy, StoredXi>(p, f, c, points[s], accumulate_work);
}

// Damage: this evaluation's state for the next bond-work increment (after the barrier of pass 2),
// the ghosts' too (their owners' values of this evaluation): the lower end of a pair reads it.
template <int D, class Effects>
void remember_state(PointData& p) {
  BondWorkPolicy<D, Effects>::remember_state(p, static_cast<std::int64_t>(p.total()));
}

// A distributed run's ghosts get their owners' displacement and rotation before pass 1 and their
// pass-1 tensors between the passes, with damage in an advancing evaluation also the sums A + A_prev
// and Q + Q_prev the bond work reads at either end (one thread calls MPI, outside the parallel
// regions). Each exchange is begun, the interior points (no ghost in their families) are computed
// while the values travel, and the exchange is finished before the border points.
template <int D, class Effects>
void begin_ghost_kinematics(PointData& p) {
  constexpr int R = rotation_components<D>;
  p.ghost_source->begin_update(p.displacement, D);
  if constexpr (Effects::micropolar) p.ghost_source->begin_update(p.rotation, R);
}
template <int D, class Effects>
void begin_ghost_tensors(PointData& p, [[maybe_unused]] bool advancing) {
  constexpr int R = rotation_components<D>;
  p.ghost_source->begin_update(p.force_tensor, D * D);
  if constexpr (Effects::micropolar) p.ghost_source->begin_update(p.moment_tensor, R * D);
  if constexpr (Effects::damage) {
    if (advancing) {
      p.ghost_source->begin_update(p.force_tensor_sum, D * D);
      if constexpr (Effects::micropolar) p.ghost_source->begin_update(p.moment_tensor_sum, R * D);
    }
  }
}

// A pass over the interior points in blocks, the ghosts' transfers advanced between them: an MPI
// library moves a large message (over shared memory, or a network without its own progress) only
// inside its calls, so without them the values would travel only once the pass waits for them.
template <class Pass>
void interior_in_blocks(const PointData& p, PointSelection interior, bool threaded, Pass&& pass) {
  constexpr std::int64_t kBlocks = 8, kSmallestBlock = 2048;
  const std::int64_t per_block = std::max(kSmallestBlock, (interior.count + kBlocks - 1) / kBlocks);
  for (std::int64_t first = 0; first < interior.count; first += per_block) {
    const PointSelection block{interior.list + first, std::min(per_block, interior.count - first)};
#pragma omp parallel if (threaded)
    pass(block);
    p.ghost_source->advance_transfers();
  }
}

template <int D, class Effects, bool WithEnergy, bool StoredXi>
void overlapped_internal_forces(PointData& p, BondFamilies& f, const CosseratConstants& c, const StepAdvance* advance,
                                bool threaded) {
  if (f.interior_points.size() + f.border_points.size() != p.owned)
    throw std::logic_error("internal forces: the families' interior and border points are not set");
  const bool accumulate_work = Effects::damage && advance != nullptr;
  const PointSelection interior = listed(f.interior_points), border = listed(f.border_points);
  begin_ghost_kinematics<D, Effects>(p);
  interior_in_blocks(p, interior, threaded,
                     [&](PointSelection block) { pass1_points<D, Effects, StoredXi>(p, f, c, advance, block); });
  p.ghost_source->finish_updates();
#pragma omp parallel if (threaded)
  pass1_points<D, Effects, StoredXi>(p, f, c, advance, border);
  begin_ghost_tensors<D, Effects>(p, accumulate_work);
  interior_in_blocks(p, interior, threaded, [&](PointSelection block) {
    pass2_points<D, Effects, WithEnergy, StoredXi>(p, f, c, accumulate_work, block);
  });
  p.ghost_source->finish_updates();
#pragma omp parallel if (threaded)
  {
    pass2_points<D, Effects, WithEnergy, StoredXi>(p, f, c, accumulate_work, border);
    remember_state<D, Effects>(p);
  }
}

template <int D, class Effects, bool WithEnergy, bool StoredXi>
void internal_forces(PointData& p, BondFamilies& f, const CosseratConstants& c, const StepAdvance* advance) {
  const bool threaded = thread_bond_loop(f.bond_count());
  if (p.ghost > 0 && p.ghost_source) {
    overlapped_internal_forces<D, Effects, WithEnergy, StoredXi>(p, f, c, advance, threaded);
    return;
  }
  const bool accumulate_work = Effects::damage && advance != nullptr;
  // One parallel region for both passes (one fork/join per evaluation); the barrier at the end
  // of pass 1 makes every neighbour's tensors ready for pass 2.
#pragma omp parallel if (threaded)
  {
    pass1_points<D, Effects, StoredXi>(p, f, c, advance, all_owned(p));
    pass2_points<D, Effects, WithEnergy, StoredXi>(p, f, c, accumulate_work, all_owned(p));
    remember_state<D, Effects>(p);
  }
}

// The bond vectors come from the positions, or stored for periodic lattices: two kernels, chosen
// once per evaluation, so the bond loops carry no branch for it.
template <int D, class Effects, bool WithEnergy>
void internal_forces(PointData& p, BondFamilies& f, const CosseratConstants& c,
                     [[maybe_unused]] const StepAdvance* advance) {
  if (!f.xi.empty())
    internal_forces<D, Effects, WithEnergy, true>(p, f, c, advance);
  else
    internal_forces<D, Effects, WithEnergy, false>(p, f, c, advance);
}

// After bonds broke (damage): the forces of this step again, now without the broken bonds, so
// that the step's kick does not use a bond past its breaking (which would do work that nothing
// accounts for). Only the points whose families changed have new tensors, and only they and their
// neighbours have new forces: points.refreshed_points (sorted, owned; update_after_breakage lists
// them). Pass 1 runs on them (the plastic state is not advanced again; the neighbours get the same
// tensors again, and their own share of the force, which pass 2 completes), the ghosts' tensors
// are fetched (a distributed run: a collective call), then pass 2 (the bond work is not
// accumulated again), with energies. The next step's bond-work increment starts from these
// tensors. Their force and moment before are left in force/moment_before_refresh, for the
// integrator's energy bookkeeping.
template <int D, class Effects>
void refresh_after_breakage(PointData& p, BondFamilies& f, const CosseratConstants& c) {
  if constexpr (Effects::damage) {
    constexpr int R = rotation_components<D>;
    constexpr bool polar = Effects::micropolar;
    const bool stored_xi = !f.xi.empty();
    const std::vector<std::size_t>& around = p.refreshed_points;
    p.force_before_refresh.resize(around.size() * D);
    p.moment_before_refresh.resize(around.size() * R);
    for (std::size_t k = 0; k < around.size(); ++k) {
      const std::size_t i = around[k];
      for (int r = 0; r < D; ++r) p.force_before_refresh[k * D + r] = p.force[i * D + r];
      if constexpr (polar)
        for (int r = 0; r < R; ++r) p.moment_before_refresh[k * R + r] = p.moment[i * R + r];
    }
    // Serial (outside a parallel region, the passes' loops run on this thread alone): the lists are
    // short, and the ghosts' fetch between the passes is a collective call.
    if (stored_xi)
      pass1_points<D, Effects, true>(p, f, c, nullptr, listed(around));
    else
      pass1_points<D, Effects, false>(p, f, c, nullptr, listed(around));
    if (p.ghost > 0 && p.ghost_source) {
      begin_ghost_tensors<D, Effects>(p, false);
      p.ghost_source->finish_updates();
    }
    if (stored_xi)
      pass2_points<D, Effects, true, true>(p, f, c, false, listed(around));
    else
      pass2_points<D, Effects, true, false>(p, f, c, false, listed(around));
  } else {
    (void)p, (void)f, (void)c;
  }
}

#undef MPPM_INLINE

}  // namespace mppm::solver::kernel
