// The 3-D update with a full couple-stress law (three distinct couple moduli) and
// non-default J2 / equivalent-strain weights (the skew stress then enters J2): the general
// block decomposition of the return must still give backward Euler exactly, i.e.
//   f(sigma_{n+1}, m_{n+1}, c_{n+1}) = eta dgamma / dt,
//   d eps_vp = dgamma (dq/dsigma + M_psi/3 1),  d kap_vp = dgamma dq/dm   (at n+1),
//   d ebar   = sqrt(b1 de:de + b2 de:de^T + b3 l^2 dkap:dkap),
// with the elastic laws holding for the updated plastic parts. All recomputed here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "solver/plasticity/drucker_prager_perzyna.hpp"
#include "solver/plasticity/generalized_invariants.hpp"
#include "solver/plasticity/plastic_strain_measures.hpp"

namespace mppm::plasticity {
namespace {

using Eigen::Matrix3d;
constexpr double kDeg = std::numbers::pi / 180.0;

double dot(const Matrix3d& a, const Matrix3d& b) { return a.cwiseProduct(b).sum(); }

TEST(PlasticityThreeDimensional, GeneralCoupleLawAndWeightsKeepBackwardEulerExact) {
  const CosseratElasticity<3> el{15e6, 10e6, 4e6, 20.0, 60.0, 25.0};  // 3a1+a2+a3, a2+a3, a2-a3 > 0
  DruckerPragerParameters prm;
  prm.friction_angle = 30.0 * kDeg;
  prm.dilatancy_angle = 10.0 * kDeg;
  prm.cohesion = 0.2e6;
  prm.hardening = -0.5e6;
  prm.residual_cohesion = 0.02e6;
  prm.length_scale = 1.5e-3;
  prm.j2 = {0.3, 0.1, 0.4};
  prm.equivalent_strain = {0.4, 0.2, 0.5};
  const double l = prm.length_scale;
  const GeneralizedJ2Weights& a = prm.j2;
  const EquivalentStrainWeights& b = prm.equivalent_strain;
  const double m_phi = 6.0 * std::sin(prm.friction_angle) / (3.0 - std::sin(prm.friction_angle));
  const double m_psi = 6.0 * std::sin(prm.dilatancy_angle) / (3.0 - std::sin(prm.dilatancy_angle));
  const double k_per_c = 6.0 * std::cos(prm.friction_angle) / (3.0 - std::sin(prm.friction_angle));
  const Matrix3d I = Matrix3d::Identity();
  const auto stress_law = [&](const Matrix3d& e) {
    return el.lambda * e.trace() * I + (el.mu + el.mu_c) * e + (el.mu - el.mu_c) * e.transpose();
  };
  const auto couple_law = [&](const Matrix3d& k) { return el.a1 * k.trace() * I + el.a2 * k + el.a3 * k.transpose(); };
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double dt = 1e-5;
  int cone = 0, apex = 0;
  for (double eta : {0.0, 30.0, 300.0}) {
    prm.viscosity = eta;
    const DruckerPragerPerzyna model = make_drucker_prager_perzyna(prm);
    for (int n = 0; n < 300; ++n) {
      Matrix3d eps, kap;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          eps(i, j) = 0.02 * u(rng);
          kap(i, j) = 0.02 * u(rng) / l;
        }
      eps += 0.01 * (u(rng) + 0.3) * I;  // from compression to tension, so the apex occurs
      PlasticState<3> s0 = initial_plastic_state<3>(model);
      s0.equivalent_plastic_strain = 0.1 * (u(rng) + 1.0);
      const PointUpdate<3> r = drucker_prager_perzyna_update(eps, kap, s0, el, model, dt);
      ASSERT_TRUE(r.stress.allFinite() && r.couple_stress.allFinite());
      const Matrix3d& sigma = r.stress;
      const Matrix3d& m = r.couple_stress;
      const Matrix3d s = sigma - sigma.trace() / 3.0 * I;
      const double q = std::sqrt(3.0 * (a.a1 * dot(s, s) + a.a2 * dot(s, s.transpose()) + a.a3 * dot(m, m) / (l * l)));
      const double f = q + m_phi * sigma.trace() / 3.0 - k_per_c * r.state.cohesion;
      const double scale = stress_law(eps).norm() + couple_law(kap).norm() / l;
      if (!r.plastic) {
        EXPECT_LE(f, 1e-10 * scale);
        continue;
      }
      EXPECT_NEAR(f, eta * r.multiplier / dt, 1e-9 * scale);
      const Matrix3d d_eps = r.state.plastic_strain;
      const Matrix3d d_kap = r.state.plastic_wryness;
      // Elastic laws with the updated plastic parts (1e-9: rounding of the block split).
      EXPECT_LE((sigma - stress_law(eps - d_eps)).norm(), 1e-9 * scale);
      EXPECT_LE((m - couple_law(kap - d_kap)).norm(), 1e-9 * scale * l);
      const Matrix3d de = d_eps - d_eps.trace() / 3.0 * I;
      const double d_ebar =
          std::sqrt(b.b1 * dot(de, de) + b.b2 * dot(de, de.transpose()) + b.b3 * l * l * dot(d_kap, d_kap));
      EXPECT_NEAR(r.state.equivalent_plastic_strain - s0.equivalent_plastic_strain, d_ebar, 1e-9 * d_ebar);
      EXPECT_NEAR(d_eps.trace(), m_psi * r.multiplier, 1e-9 * (d_eps.norm() + 1e-12));
      if (r.apex) {
        ++apex;
        EXPECT_LE(q, 1e-9 * scale);
        continue;
      }
      ++cone;
      const Matrix3d dq_dsigma = 1.5 / q * (2.0 * a.a1 * s + 2.0 * a.a2 * s.transpose());
      const Matrix3d dq_dm = 3.0 * a.a3 * m / (q * l * l);
      EXPECT_LE((d_eps - r.multiplier * (dq_dsigma + m_psi / 3.0 * I)).norm(), 1e-9 * d_eps.norm());
      EXPECT_LE((d_kap - r.multiplier * dq_dm).norm(), 1e-9 * d_kap.norm());
    }
  }
  EXPECT_GT(cone, 300);
  EXPECT_GT(apex, 20);
}

// Output measures under proportional flow: symmetric shear under constant pressure in 3-D
// keeps the deviatoric stress along the applied shear (isotropic elasticity decouples p and
// s), so the accumulated plastic shear strain equals ebar and the volumetric plastic strain
// is M_psi * ebar (dilatancy), to rounding. The library's own f agrees with the definition.
TEST(PlasticityThreeDimensional, OutputMeasuresUnderProportionalShear) {
  const CosseratElasticity<3> el{15e6, 10e6, 4e6, 20.0, 60.0, 25.0};
  DruckerPragerParameters prm;
  prm.friction_angle = 30.0 * kDeg;
  prm.dilatancy_angle = 12.0 * kDeg;
  prm.cohesion = 0.2e6;
  prm.hardening = -0.5e6;
  prm.residual_cohesion = 0.02e6;
  prm.viscosity = 100.0;
  prm.length_scale = 1.5e-3;
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(prm);
  const double m_psi = 6.0 * std::sin(prm.dilatancy_angle) / (3.0 - std::sin(prm.dilatancy_angle));
  PlasticState<3> state = initial_plastic_state<3>(model);
  PointUpdate<3> r;
  for (int n = 1; n <= 500; ++n) {
    Matrix3d eps = -2e-3 * Matrix3d::Identity();
    eps(0, 2) = eps(2, 0) = 0.1 * n / 500.0;
    r = drucker_prager_perzyna_update(eps, Matrix3d::Zero().eval(), state, el, model, 1e-4);
    state = r.state;
    const double f = yield_function(model, r.stress, r.couple_stress, state.cohesion);
    if (r.plastic) {
      EXPECT_NEAR(f, r.overstress, 1e-9 * r.stress.norm());
    } else {
      EXPECT_LE(f, 0.0);
    }
  }
  const double ebar = state.equivalent_plastic_strain;
  ASSERT_GT(ebar, 0.01);
  EXPECT_NEAR(equivalent_plastic_shear_strain(state.plastic_strain, state.plastic_wryness, prm.equivalent_strain,
                                              prm.length_scale),
              ebar, 1e-12 * ebar);
  EXPECT_NEAR(volumetric_plastic_strain(state.plastic_strain), m_psi * ebar, 1e-12 * ebar);
}

}  // namespace
}  // namespace mppm::plasticity
