// With couple stresses off (no wryness, mu_c = 0) the micro-polar model must be classical
// Drucker-Prager with Perzyna viscosity. The reference here is the closed-form classical
// return written independently of the library: one shear modulus, so
//   q = q_trial - 3 mu dgamma,  p = p_trial - K M_psi dgamma,
//   dgamma = f_trial / (3 mu + K M_phi M_psi + k_c h + eta/dt)   (cone, c above its floor),
// and at the apex q = 0, dgamma = (M_phi p_trial - k_c c) / (K M_phi M_psi + eta/dt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "solver/plasticity/drucker_prager_perzyna.hpp"

namespace mppm::plasticity {
namespace {

using Eigen::Matrix3d;
constexpr double kDeg = std::numbers::pi / 180.0;

struct ClassicalParameters {
  double lambda, mu;
  double m_phi, m_psi, k_per_c;  // slopes and k/c
  double c0, h, c_res, eta;
};

struct ClassicalResult {
  Matrix3d stress;
  Matrix3d plastic_increment;
  double ebar_increment = 0.0;
  bool apex = false;
};

ClassicalResult classical_drucker_prager(const Matrix3d& strain, const Matrix3d& plastic_strain, double ebar,
                                         const ClassicalParameters& cp, double dt) {
  const Matrix3d I = Matrix3d::Identity();
  const Matrix3d e = 0.5 * (strain + strain.transpose()) - plastic_strain;  // mu_c = 0: skew part is stress-free
  const double bulk = cp.lambda + 2.0 * cp.mu / 3.0;
  const Matrix3d dev_e = e - e.trace() / 3.0 * I;
  const Matrix3d s_trial = 2.0 * cp.mu * dev_e;
  const double p_trial = bulk * e.trace();
  const double q_trial = std::sqrt(1.5 * s_trial.squaredNorm());
  const auto cohesion = [&](double eb) { return std::max(cp.c0 + cp.h * eb, cp.c_res); };
  ClassicalResult r;
  const double f_trial = q_trial + cp.m_phi * p_trial - cp.k_per_c * cohesion(ebar);
  if (f_trial <= 0.0) {
    r.stress = s_trial + p_trial * I;
    r.plastic_increment.setZero();
    return r;
  }
  const double viscous = cp.eta / dt;
  // Above the floor r(dgamma) = f_trial - (3 mu + K M_phi M_psi + k_c h + eta/dt) dgamma. If
  // softening makes that slope non-negative, r grows until c reaches its floor and falls
  // after it, so the only root is past the floor.
  const double slope = 3.0 * cp.mu + bulk * cp.m_phi * cp.m_psi + cp.k_per_c * cp.h + viscous;
  double dgamma = f_trial / slope;
  if (slope <= 0.0 || cp.c0 + cp.h * (ebar + dgamma) < cp.c_res) {  // on the floor: no more softening
    dgamma =
        (q_trial + cp.m_phi * p_trial - cp.k_per_c * cp.c_res) / (3.0 * cp.mu + bulk * cp.m_phi * cp.m_psi + viscous);
  }
  if (dgamma < q_trial / (3.0 * cp.mu)) {
    const Matrix3d s = (1.0 - 3.0 * cp.mu * dgamma / q_trial) * s_trial;
    r.stress = s + (p_trial - bulk * cp.m_psi * dgamma) * I;
    r.plastic_increment = dgamma * (1.5 / q_trial * s_trial + cp.m_psi / 3.0 * I);  // n = s/q is fixed by the return
    r.ebar_increment = dgamma;
    return r;
  }
  r.apex = true;
  r.ebar_increment = q_trial / (3.0 * cp.mu);  // all of the deviatoric trial strain
  dgamma =
      (cp.m_phi * p_trial - cp.k_per_c * cohesion(ebar + r.ebar_increment)) / (bulk * cp.m_phi * cp.m_psi + viscous);
  r.stress = (p_trial - bulk * cp.m_psi * dgamma) * I;
  r.plastic_increment = dev_e + cp.m_psi * dgamma / 3.0 * I;
  return r;
}

// Tolerance 1e-10 relative: both sides are closed forms up to the library's Newton (1e-13)
// and rounding; a wrong modulus, slope or floor treatment is visible at 1e-3 and above.
void compare_with_classical(double h, double eta, std::uint64_t seed, int* cone, int* apex) {
  const double phi = 30.0 * kDeg, psi = 10.0 * kDeg;
  ClassicalParameters cp{20e6,
                         15e6,
                         6.0 * std::sin(phi) / (3.0 - std::sin(phi)),
                         6.0 * std::sin(psi) / (3.0 - std::sin(psi)),
                         6.0 * std::cos(phi) / (3.0 - std::sin(phi)),
                         0.5e6,
                         h,
                         0.05e6,
                         eta};
  DruckerPragerParameters prm;
  prm.friction_angle = phi;
  prm.dilatancy_angle = psi;
  prm.cohesion = cp.c0;
  prm.hardening = h;
  prm.residual_cohesion = cp.c_res;
  prm.viscosity = eta;
  prm.length_scale = 1e-3;  // present but idle: no wryness
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(prm);
  const CosseratElasticity<3> el{cp.lambda, cp.mu, 0.0, 0.0, 0.0, 0.0};
  const double dt = 1e-5;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 300; ++n) {
    Matrix3d strain, vp;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) strain(i, j) = 0.03 * u(rng);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j <= i; ++j) vp(i, j) = vp(j, i) = 0.005 * u(rng);
    PlasticState<3> state = initial_plastic_state<3>(model);
    state.plastic_strain = vp;
    state.equivalent_plastic_strain = 0.2 * (u(rng) + 1.0);
    const ClassicalResult ref = classical_drucker_prager(strain, vp, state.equivalent_plastic_strain, cp, dt);
    const PointUpdate<3> r = drucker_prager_perzyna_update(strain, Matrix3d::Zero().eval(), state, el, model, dt);
    const double scale = ref.stress.norm() + cp.k_per_c * cp.c0;
    ASSERT_LE((r.stress - ref.stress).norm(), 1e-10 * scale) << "h " << h << " eta " << eta << " point " << n;
    EXPECT_EQ(r.apex, ref.apex);
    EXPECT_LE((r.state.plastic_strain - vp - ref.plastic_increment).norm(),
              1e-10 * (ref.plastic_increment.norm() + 1e-3));
    EXPECT_NEAR(r.state.equivalent_plastic_strain - state.equivalent_plastic_strain, ref.ebar_increment,
                1e-10 * (ref.ebar_increment + 1e-3));
    EXPECT_EQ(r.couple_stress, Matrix3d::Zero());
    if (r.plastic) (ref.apex ? *apex : *cone) += 1;
  }
}

TEST(PlasticityClassical, EqualsClassicalDruckerPragerWithoutCoupleStresses) {
  int cone = 0, apex = 0;
  std::uint64_t seed = 1;
  for (double h : {5e6, 0.0, -2e6, -40e6}) {
    for (double eta : {0.0, 1e-2, 50.0, 1e4}) compare_with_classical(h, eta, seed++, &cone, &apex);
  }
  EXPECT_GT(cone, 1000);  // both branches exercised
  EXPECT_GT(apex, 100);
}

}  // namespace
}  // namespace mppm::plasticity
