// The bond-work bookkeeping of the damage effect (docs/theory.md section 7) as a policy of the
// force passes (internal_force_kernel.hpp), which call it at fixed points: pass 1 forms the
// tensor sums it needs, pass 2 hands it every bond that books work, and the evaluation ends by
// remembering its state for the next increment. BondWorkPolicy<D, Effects> without damage is
// empty and its calls compile to nothing.
//
// With a StepAdvance, each bond's work W_ij grows by the trapezoid-rule increment
// 1/2 (t_old + t) . (U - U_old) + 1/2 (m_old + m) . (Om - Om_old) of its pair force t = T_ij - T_ji
// and pair moment m = M_ij - M_ji, and the bond counts as breaking when W_ij >= w_cr
// (update_after_breakage breaks it). The old pair force is rebuilt from per-point arrays (the
// previous displacement and rotation, and the sums A + A_prev, Q + Q_prev that pass 1 forms: a few
// numbers per point instead of D + R per bond). Seen from j, every term of the increment is the
// exact negative of the one seen from i (xi, U, Om, t, m all change sign, and IEEE addition
// commutes), so the increment is computed once, by the lower-index end (the lower global id in a
// distributed run, whose ghosts keep the previous state and get the tensor sums too), which holds the bond
// pair's W_ij (BondFamilies::work). Both ends break in the same step, for any thread count.
#pragma once
#include <cstddef>
#include <cstdint>

#include "solver/bond_families.hpp"
#include "solver/bond_kinematics.hpp"
#include "solver/bond_products.hpp"
#include "solver/compiled_effects.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/multiply_add.hpp"
#include "solver/point_data.hpp"
#include "solver/symmetric_tensor.hpp"

namespace mppm::solver::kernel {

template <int D, class Effects, bool Damage = Effects::damage>
class BondWorkPolicy;

// Damage off: nothing to book.
template <int D, class Effects>
class BondWorkPolicy<D, Effects, false> {
 public:
  static constexpr bool active = false;
  static void detached_tensor_sums(PointData&, std::size_t, bool) {}
  static void force_tensor_sum(PointData&, std::size_t, const double*, bool) {}
  static void moment_tensor_sum(PointData&, std::size_t, const double*, bool) {}
  static void remember_state(PointData&, std::int64_t) {}
  BondWorkPolicy(const PointData&, BondFamilies&, const CosseratConstants&, std::size_t, bool) {}
  void add(std::int64_t, std::size_t, const double*, const double*, const double*, const double*, const double*) {}
  void finish(PointData&, std::size_t) const {}
};

template <int D, class Effects>
class BondWorkPolicy<D, Effects, true> {
  static constexpr int R = rotation_components<D>;
  static constexpr bool polar = Effects::micropolar;
  static constexpr int DD = D * D;
  static constexpr int RD = R * D;
  static constexpr int S = symmetric_components<D>;

 public:
  static constexpr bool active = true;

  // Pass 1, advancing (`advancing`): the sums of this evaluation's tensors and the previous ones
  // (point_data.hpp), each formed before pass 1 overwrites the previous tensor. A detached
  // point's tensors are zero now, so its sums are its previous tensors.
  static void detached_tensor_sums(PointData& p, std::size_t i, bool advancing) {
    if (!advancing) return;
    for (int k = 0; k < DD; ++k) p.force_tensor_sum[i * DD + k] = p.force_tensor[i * DD + k];
    if constexpr (polar)
      for (int k = 0; k < RD; ++k) p.moment_tensor_sum[i * RD + k] = p.moment_tensor[i * RD + k];
  }
  // A + A_prev, before A (a, by columns as stored) is stored.
  static void force_tensor_sum(PointData& p, std::size_t i, const double* a, bool advancing) {
    if (advancing)
      for (int k = 0; k < DD; ++k) p.force_tensor_sum[i * DD + k] = a[k] + p.force_tensor[i * DD + k];
  }
  // Q + Q_prev, before Q (q, by columns as stored) is stored.
  static void moment_tensor_sum(PointData& p, std::size_t i, const double* q, bool advancing) {
    if (advancing)
      for (int k = 0; k < RD; ++k) p.moment_tensor_sum[i * RD + k] = q[k] + p.moment_tensor[i * RD + k];
  }

  // After pass 2 (which read the previous state; pass 1 formed the tensor sums): this
  // evaluation's displacement and rotation for the next increment. Called by every thread of
  // the force pass's parallel region (a work-shared loop).
  static void remember_state(PointData& p, std::int64_t n) {
#pragma omp for schedule(static)
    for (std::int64_t s = 0; s < n; ++s) {
      const auto i = static_cast<std::size_t>(s);
      for (int r = 0; r < D; ++r) p.previous_displacement[i * D + r] = p.displacement[i * D + r];
      if constexpr (polar)
        for (int r = 0; r < R; ++r) p.previous_rotation[i * R + r] = p.rotation[i * R + r];
    }
  }

  // Pass 2 at point i, booking work when `accumulate_work` (an advancing evaluation). A bond with a
  // no-fail end never breaks, so its work is not needed: a no-fail point (near a boundary
  // condition, or outside material.damage.region) skips the bookkeeping of all its bonds. Point
  // i's values are copied to members: the stores of the bond work could alias the arrays, which
  // would make the compiler reload them for every bond. Always inlined, like add and finish: an
  // out-of-line call would take the object's address, and its members would then stay in memory
  // and be reloaded after every store of a bond's work (measured: 2 % more instructions per bond
  // update with micropolar and damage).
  [[gnu::always_inline]] BondWorkPolicy(const PointData& p, BondFamilies& f, const CosseratConstants& c, std::size_t i,
                                        bool accumulate_work)
      : accumulate_work_(accumulate_work), critical_work_(c.critical_bond_work) {
    u_old_ = p.previous_displacement.data();
    w_old_ = polar ? p.previous_rotation.data() : nullptr;
    a_sum_ = p.force_tensor_sum.data();
    q_sum_ = polar ? p.moment_tensor_sum.data() : nullptr;
    g_all_ = polar ? p.stabilization_rot.data() : nullptr;
    no_fail_ = p.no_fail.data();
    pair_work_ = f.work.data();
    const bool work_here = accumulate_work && !p.no_fail[i];
    // The bonds to lower indices come first (sorted neighbours), and the k-th bond from `split`
    // on is the point's k-th pair: A_i + A_i0 and Q_i + Q_i0, C:K_i^-1 and g_i (the pair force
    // has both ends' shares).
    split_ = work_here ? f.first_pair_bond(i) : f.offset[i + 1];
    pair_base_ = work_here ? f.pair_offset[i] - split_ : 0;
    if (work_here) {
      for (int k = 0; k < D; ++k) ui0_[k] = u_old_[i * D + k];
      for (int k = 0; k < DD; ++k) ai_both_[k] = a_sum_[i * DD + k];
      for (int k = 0; k < S; ++k) cki_[k] = p.stabilization_ck[i * S + k];
      if constexpr (polar) {
        for (int k = 0; k < R; ++k) wi0_[k] = w_old_[i * R + k];
        for (int k = 0; k < RD; ++k) qi_both_[k] = q_sum_[i * RD + k];
        gi_ = g_all_[i];
      }
    }
  }

  // The first bond whose work point i books (its end when it books none): a bond's work is the
  // same bits from both ends, so it is computed once, at the lower-index end.
  std::int64_t first_work_bond() const { return split_; }

  // Bond b to j (bond vector xi, composite state U, rotations wi, wj, C:K_j^-1 ckj), from
  // first_work_bond() on: adds its work increment and counts it if it reaches the critical work.
  [[gnu::always_inline]] inline void add(std::int64_t b, std::size_t j, const double* xi, const double* U,
                                         const double* wi, const double* wj, const double* ckj) {
    if (no_fail_[j]) return;
    // dW = 1/2 (t0 + t) . (U - U0) + 1/2 (m0 + m) . (Om - Om0) of the pair force
    // t = T_ij - T_ji and pair moment m = M_ij - M_ji, with t0 + t summed before it is formed:
    // the stabilization tensors are those of the previous evaluation (they change only where
    // bonds broke, and refresh_after_breakage then starts the next increment from the new
    // ones), so t0 + t = (A_i0 + A_i + A_j0 + A_j) xi + (Ck_i + Ck_j)(U0 + U) and
    // m0 + m = (Q_i0 + Q_i + Q_j0 + Q_j) xi + (g_i + g_j)(Om0 + Om).
    const double* wj0 = polar ? w_old_ + j * R : nullptr;
    double U0[D];
    composite_state<D, R, polar>(ui0_, u_old_ + j * D, wi0_, wj0, xi, U0);
    const double* aj_both = a_sum_ + j * DD;
    double pair_force[lane_slots<D>];  // t0 + t
    pair_force_sum<D>(ai_both_, aj_both, cki_, ckj, xi, U0, U, pair_force);
    double dw = 0.0;
    for (int r = 0; r < D; ++r) dw = multiply_add(pair_force[r], U[r] - U0[r], dw);
    if constexpr (polar) {
      double pair_moment[lane_slots<R>], change[lane_slots<R>];  // m0 + m and Om - Om0
      pair_moment_sum<D, R>(qi_both_, q_sum_ + j * RD, gi_ + g_all_[j], wi, wj, wi0_, wj0, xi, pair_moment, change);
      for (int r = 0; r < R; ++r) dw = multiply_add(pair_moment[r], change[r], dw);
    }
    // The pair's work W_ij, at this (lower-index) end; counted here and broken afterwards by
    // update_after_breakage, which finds it by its work (this step's force had the bond, and
    // the energy the break releases is measured with it still acting).
    double& pair = pair_work_[pair_base_ + b];
    const double work = pair + 0.5 * dw;
    pair = work;
    if (work >= critical_work_) ++broken_;
  }

  // After point i's bonds: its count of bonds that reached the critical work (advancing only).
  [[gnu::always_inline]] void finish(PointData& p, std::size_t i) const {
    if (accumulate_work_) p.bonds_broken[i] = broken_;
  }

 private:
  const double* __restrict u_old_;
  const double* __restrict w_old_;
  const double* __restrict a_sum_;
  const double* __restrict q_sum_;
  const double* __restrict g_all_;
  const std::uint8_t* __restrict no_fail_;
  double* __restrict pair_work_;
  bool accumulate_work_;
  double critical_work_;
  std::int64_t split_ = 0, pair_base_ = 0;
  std::int32_t broken_ = 0;
  double ui0_[D] = {}, wi0_[3] = {0.0, 0.0, 0.0}, ai_both_[DD] = {}, qi_both_[RD > 0 ? RD : 1] = {}, cki_[S] = {};
  double gi_ = 0.0;
};

}  // namespace mppm::solver::kernel
