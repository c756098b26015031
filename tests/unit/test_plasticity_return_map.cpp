// The micro-polar Drucker-Prager Perzyna material point update (docs/theory.md section 6): elastic
// states, the rate-independent limit, backward-Euler normality, the overstress law, apex
// states, softening with tiny viscosity, non-negative dissipation, 2-D = embedded 3-D,
// and bitwise-identical results for any number of threads.
// Every check recomputes the invariants and gradients here, independently of the library.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "solver/plasticity/drucker_prager_perzyna.hpp"
#include "tests/unit/shear_band_material.hpp"

namespace mppm::plasticity {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector2d;
constexpr double kDeg = std::numbers::pi / 180.0;

// The shear-band case (workflows/shear-band): the material the model is built for.
struct Case1 {
  CosseratElasticity<2> elastic = testing::shear_band_elasticity();
  DruckerPragerParameters prm = testing::shear_band_parameters();
};

double tri_compression_slope(double angle) { return 6.0 * std::sin(angle) / (3.0 - std::sin(angle)); }
double tri_compression_k(double c, double phi) { return 6.0 * c * std::cos(phi) / (3.0 - std::sin(phi)); }

// q = sqrt(3 J2), J2 = 1/4 s:s + 1/4 s:s^T + 1/2 m.m / l^2 (docs/theory.md section 6).
double q_of(const Matrix3d& sigma, const Vector2d& m, double l) {
  const Matrix3d s = sigma - sigma.trace() / 3.0 * Matrix3d::Identity();
  const double j2 =
      0.25 * (s.cwiseProduct(s).sum() + s.cwiseProduct(s.transpose()).sum()) + 0.5 * m.squaredNorm() / (l * l);
  return std::sqrt(3.0 * j2);
}

double f_of(const Matrix3d& sigma, const Vector2d& m, double c, const DruckerPragerParameters& p) {
  return q_of(sigma, m, p.length_scale) + tri_compression_slope(p.friction_angle) * sigma.trace() / 3.0 -
         tri_compression_k(c, p.friction_angle);
}

Matrix3d elastic_stress(const Matrix3d& e, const CosseratElasticity<2>& el) {
  return el.lambda * e.trace() * Matrix3d::Identity() + (el.mu + el.mu_c) * e + (el.mu - el.mu_c) * e.transpose();
}

struct RandomPoint {
  Matrix3d strain;
  Vector2d wryness;
  PlasticState<2> state;
};

// Plane-strain strain (z components zero), wryness of the same order times 1/l, and a random
// earlier plastic state (eps_vp has a zz part: plastic flow is 3-D even in plane strain).
RandomPoint random_point(std::mt19937_64& rng, double strain_size, double l, const DruckerPragerPerzyna& model) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomPoint rp;
  rp.strain.setZero();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) rp.strain(i, j) = strain_size * u(rng);
  rp.wryness = Vector2d(u(rng), u(rng)) * strain_size / l;
  rp.state = initial_plastic_state<2>(model);
  Matrix3d vp = Matrix3d::Zero();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) vp(i, j) = 0.2 * strain_size * u(rng);
  vp(2, 2) = 0.2 * strain_size * u(rng);
  // An elastic hydrostatic part (from tension to compression) through eps_zz^vp, so that
  // trial states near and beyond the apex occur too.
  const double hydrostatic = strain_size * (0.5 * u(rng) + 0.3);
  rp.strain(0, 0) += hydrostatic;
  rp.strain(1, 1) += hydrostatic;
  vp(2, 2) -= hydrostatic;
  rp.state.plastic_strain = vp;
  rp.state.plastic_wryness = Vector2d(u(rng), u(rng)) * 0.2 * strain_size / l;
  rp.state.equivalent_plastic_strain = 0.05 * (u(rng) + 1.0);
  rp.state.cohesion = model.cohesion_at(rp.state.equivalent_plastic_strain);
  return rp;
}

TEST(PlasticityReturnMap, ElasticStatesKeepTrialStressAndState) {
  Case1 c1;
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
  // Small non-symmetric strain under compression: well inside the cone.
  Matrix3d eps = Matrix3d::Zero();
  eps << -1e-3, 2e-4, 0, -1e-4, -8e-4, 0, 0, 0, 0;
  const Vector2d kap(0.01, -0.02);
  const PlasticState<2> s0 = initial_plastic_state<2>(model);
  const PointUpdate<2> r = drucker_prager_perzyna_update(eps, kap, s0, c1.elastic, model, 7e-6);
  EXPECT_FALSE(r.plastic);
  EXPECT_LT(f_of(r.stress, r.couple_stress, s0.cohesion, c1.prm), 0.0);
  const Matrix3d expected = elastic_stress(eps, c1.elastic);
  EXPECT_LE((r.stress - expected).norm(), 1e-15 * expected.norm());
  EXPECT_EQ(r.couple_stress, c1.elastic.bending_modulus * kap);
  EXPECT_EQ(r.state.plastic_strain, s0.plastic_strain);
  EXPECT_EQ(r.state.equivalent_plastic_strain, 0.0);
  EXPECT_EQ(r.dissipation, 0.0);
}

// eta -> 0: the updated state lands on the yield surface; for eta > 0 the overstress is
// exactly eta * dgamma / dt (the backward-Euler Perzyna condition). Tolerance 1e-9 of the
// trial stress magnitude: the Newton stops at 1e-13 relative and the rest is rounding, while
// any modelling error (wrong gradient, wrong k) shows at the 1e-3 level or above.
TEST(PlasticityReturnMap, RateIndependentLimitLandsOnYieldSurface) {
  Case1 c1;
  std::mt19937_64 rng(42);
  const double dt = 7e-6;
  for (double eta : {0.0, 1e-8 * 1e6, 1e-4 * 1e6, 1e-2 * 1e6, 1.0e6}) {
    c1.prm.viscosity = eta;
    const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
    int plastic = 0, apex = 0;
    for (int n = 0; n < 400; ++n) {
      const RandomPoint rp = random_point(rng, 0.02, c1.prm.length_scale, model);
      const PointUpdate<2> r = drucker_prager_perzyna_update(rp.strain, rp.wryness, rp.state, c1.elastic, model, dt);
      const Matrix3d trial = elastic_stress(rp.strain - rp.state.plastic_strain, c1.elastic);
      const double tol = 1e-9 * trial.norm();
      ASSERT_TRUE(r.stress.allFinite());
      if (!r.plastic) {
        EXPECT_LE(f_of(r.stress, r.couple_stress, r.state.cohesion, c1.prm), tol);
        continue;
      }
      ++plastic;
      apex += r.apex;
      const double f = f_of(r.stress, r.couple_stress, r.state.cohesion, c1.prm);
      EXPECT_NEAR(f, eta * r.multiplier / dt, tol) << "eta " << eta << " point " << n;
      EXPECT_NEAR(r.overstress, f, tol);
      EXPECT_GE(r.multiplier, 0.0);
    }
    EXPECT_GT(plastic, 100) << "the random states must exercise the return";
    // With eta/dt well above the elastic moduli a step cannot flow far enough to reach the apex.
    if (eta / dt < c1.elastic.mu) {
      EXPECT_GT(apex, 0) << "and some of them the apex, eta " << eta;
    }
  }
}

// Backward Euler: the plastic increments are dgamma times the potential's gradient at the
// END of the step, d eps_vp = dgamma (3/(2q) sym(s) + M_psi/3 1), d kap_vp = dgamma 3 m /(2 q l^2),
// and d ebar = dgamma (work conjugacy of the default weights, README). Cone returns only.
TEST(PlasticityReturnMap, ConeReturnFollowsPotentialGradientAtEndOfStep) {
  Case1 c1;
  std::mt19937_64 rng(7);
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
  const double m_psi = tri_compression_slope(c1.prm.dilatancy_angle);
  const double l = c1.prm.length_scale;
  int checked = 0;
  for (int n = 0; n < 400; ++n) {
    const RandomPoint rp = random_point(rng, 0.02, l, model);
    const PointUpdate<2> r = drucker_prager_perzyna_update(rp.strain, rp.wryness, rp.state, c1.elastic, model, 7e-6);
    if (!r.plastic || r.apex) continue;
    ++checked;
    const Matrix3d s = r.stress - r.stress.trace() / 3.0 * Matrix3d::Identity();
    const double q = q_of(r.stress, r.couple_stress, l);
    const Matrix3d flow = 3.0 / (2.0 * q) * 0.5 * (s + s.transpose()) + m_psi / 3.0 * Matrix3d::Identity();
    const Vector2d couple_flow = 3.0 * r.couple_stress / (2.0 * q * l * l);
    const Matrix3d d_eps = r.state.plastic_strain - rp.state.plastic_strain;
    const Vector2d d_kap = r.state.plastic_wryness - rp.state.plastic_wryness;
    EXPECT_LE((d_eps - r.multiplier * flow).norm(), 1e-9 * d_eps.norm());
    EXPECT_LE((d_kap - r.multiplier * couple_flow).norm(), 1e-9 * d_kap.norm() + 1e-300);
    EXPECT_NEAR(r.state.equivalent_plastic_strain - rp.state.equivalent_plastic_strain, r.multiplier,
                1e-9 * r.multiplier);
    // Elastic law holds with the updated plastic strain: the stress is not invented.
    const Matrix3d elastic = elastic_stress(rp.strain - r.state.plastic_strain, c1.elastic);
    EXPECT_LE((r.stress - elastic).norm(), 1e-9 * elastic.norm());
    EXPECT_LE((r.couple_stress - c1.elastic.bending_modulus * (rp.wryness - r.state.plastic_wryness)).norm(),
              1e-9 * r.couple_stress.norm() + 1e-300);
  }
  EXPECT_GT(checked, 100);
}

// Steady loading: a constant isochoric shear rate D plus a wryness rate, with psi = 0 and
// h = 0, drives the point to a steady state where all of the strain rate is plastic. There
// the Perzyna law reads f = eta * ebar', and ebar' is fixed by the loading:
// ebar' = sqrt(2/3 D:D + 2/3 l^2 kap':kap'). Two transients: the viscous one, time eta / G
// for each block (G = 3 mu for the stress, 3 B_w / (2 l^2) = 1.5 mu for the couple stress
// here), and the turning of the stress direction toward the loading direction, which decays
// like exp(-G ebar / q) with the accumulated ebar. After 300 tau (ebar ~ 0.9, G ebar / q > 25
// for the slower block) both are below 1e-10, so the tolerance is 1e-8 relative.
TEST(PlasticityReturnMap, SteadyViscousOverstressEqualsViscosityTimesRate) {
  Case1 c1;
  c1.prm.dilatancy_angle = 0.0;
  c1.prm.hardening = 0.0;
  const double l = c1.prm.length_scale;
  for (double eta : {0.002e6, 0.01e6, 0.05e6}) {
    c1.prm.viscosity = eta;
    const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
    const double tau = eta / (3.0 * c1.elastic.mu);
    // Over the 300 tau of the run the shear reaches 1, ~100 yield strains: well into flow.
    const double rate = 1.0 / (300.0 * tau);  // [1/s]
    Matrix3d d_rate = Matrix3d::Zero();
    d_rate(0, 1) = d_rate(1, 0) = 0.5 * rate;
    d_rate(0, 0) = 0.3 * rate;
    d_rate(1, 1) = -0.3 * rate;
    const Vector2d kap_rate = Vector2d(0.4, -0.7) * rate / l;
    const double ebar_rate = std::sqrt(2.0 / 3.0 * d_rate.squaredNorm() + 2.0 / 3.0 * l * l * kap_rate.squaredNorm());
    Matrix3d confinement = Matrix3d::Zero();
    confinement(0, 0) = confinement(1, 1) = -2e-3;  // p < 0, constant because psi = 0
    const double dt = tau / 10.0;
    const int steps = 3000;  // 300 tau
    PlasticState<2> state = initial_plastic_state<2>(model);
    PointUpdate<2> r;
    for (int n = 1; n <= steps; ++n) {
      const double t = n * dt;
      r = drucker_prager_perzyna_update(confinement + d_rate * t, kap_rate * t, state, c1.elastic, model, dt);
      state = r.state;
    }
    ASSERT_TRUE(r.plastic);
    const double f = f_of(r.stress, r.couple_stress, state.cohesion, c1.prm);
    EXPECT_NEAR(f, eta * ebar_rate, 1e-8 * eta * ebar_rate) << "eta " << eta;
    EXPECT_NEAR(r.multiplier / dt, ebar_rate, 1e-8 * ebar_rate);
  }
}

// Apex: a trial state in hydrostatic tension beyond the cone's tip returns to q = 0,
// M_phi p = k(c) + eta dgamma / dt, with volumetric plastic strain M_psi dgamma and all of the
// trial deviatoric strain plastic. Near-apex trials with some shear go there too.
TEST(PlasticityReturnMap, ApexReturn) {
  Case1 c1;
  const double dt = 7e-6;
  const double m_phi = tri_compression_slope(c1.prm.friction_angle);
  const double m_psi = tri_compression_slope(c1.prm.dilatancy_angle);
  const double bulk = c1.elastic.lambda + 2.0 * c1.elastic.mu / 3.0;
  for (double eta : {0.0, 1e-2, 1e4}) {
    c1.prm.viscosity = eta;
    c1.prm.hardening = 0.0;
    const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
    // Plane strain keeps eps_zz = 0, so a hydrostatic trial needs an earlier plastic
    // eps_zz = -0.02: then eps - eps_vp = 0.02 * 1.
    PlasticState<2> s0 = initial_plastic_state<2>(model);
    s0.plastic_strain(2, 2) = -0.02;
    for (double shear : {0.0, 1e-4}) {
      Matrix3d eps = Matrix3d::Zero();
      eps(0, 0) = eps(1, 1) = 0.02;
      eps(0, 1) = shear;
      const Vector2d kap(shear / c1.prm.length_scale, 0.0);
      const PointUpdate<2> r = drucker_prager_perzyna_update(eps, kap, s0, c1.elastic, model, dt);
      ASSERT_TRUE(r.plastic);
      EXPECT_TRUE(r.apex);
      const double p = r.stress.trace() / 3.0;
      const double k = tri_compression_k(c1.prm.cohesion, c1.prm.friction_angle);
      EXPECT_LE(q_of(r.stress, r.couple_stress, c1.prm.length_scale), 1e-9 * k);
      EXPECT_NEAR(m_phi * p, k + eta * r.multiplier / dt, 1e-9 * k);
      const double p_trial = bulk * (eps - s0.plastic_strain).trace();
      EXPECT_NEAR(p, p_trial - bulk * m_psi * r.multiplier, 1e-9 * p_trial);
      EXPECT_NEAR((r.state.plastic_strain - s0.plastic_strain).trace(), m_psi * r.multiplier,
                  1e-9 * m_psi * r.multiplier);
      // The skew stress is not in J2 (default weights): it stays elastic.
      EXPECT_NEAR(r.stress(0, 1) - r.stress(1, 0), 2.0 * c1.elastic.mu_c * shear, 1e-9 * k);
      EXPECT_GE(r.dissipation, 0.0);
    }
  }
}

// Along a line of trial states crossing from the cone return into the apex return, the
// updated stress changes continuously: no jump larger than what the trial step explains.
TEST(PlasticityReturnMap, ConeAndApexReturnsMeetContinuously) {
  Case1 c1;
  c1.prm.viscosity = 1e2;
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
  const PlasticState<2> s0 = initial_plastic_state<2>(model);
  Matrix3d prev = Matrix3d::Zero();
  bool saw_cone = false, saw_apex = false;
  const int n = 2000;
  double largest_jump = 0.0;
  Matrix3d step = Matrix3d::Zero();
  step(0, 0) = step(1, 1) = 0.02 / n;
  const double trial_step = elastic_stress(step, c1.elastic).norm();
  for (int i = 0; i <= n; ++i) {
    Matrix3d eps = Matrix3d::Zero();
    eps(0, 0) = eps(1, 1) = 0.02 * i / n;
    eps(0, 1) = eps(1, 0) = 2e-3;
    const PointUpdate<2> r = drucker_prager_perzyna_update(eps, Vector2d(0.3, 0.1), s0, c1.elastic, model, 7e-6);
    saw_cone |= r.plastic && !r.apex;
    saw_apex |= r.apex;
    if (i > 0) largest_jump = std::max(largest_jump, (r.stress - prev).norm());
    prev = r.stress;
  }
  EXPECT_TRUE(saw_cone);
  EXPECT_TRUE(saw_apex);
  EXPECT_LT(largest_jump, 2.0 * trial_step);  // the returned stress never moves more than the trial
}

// Softening with a tiny viscosity (down to 1e-8 MPa s) and h < 0, down to the residual
// cohesion and with softening steeper than the elastic shear stiffness (3 mu + kappa h < 0,
// where the local residual is not monotone): every step stays finite, on the yield surface
// plus the overstress, with non-increasing cohesion above its floor and non-negative
// dissipation.
TEST(PlasticityReturnMap, SofteningWithTinyViscosityStaysFiniteAndOnSurface) {
  Case1 c1;
  const double dt = 7e-6;
  for (double h : {-1.0e6, -20.0e6, -300.0e6}) {
    for (double eta : {1e-8 * 1e6, 1e-4 * 1e6}) {
      c1.prm.hardening = h;
      c1.prm.viscosity = eta;
      const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
      PlasticState<2> state = initial_plastic_state<2>(model);
      const int steps = 2000;
      int max_iterations = 0;
      for (int n = 1; n <= steps; ++n) {
        const double g = 0.8 * n / steps;  // simple shear up to 80 % under lateral compression
        Matrix3d eps = Matrix3d::Zero();
        eps(0, 0) = -1e-3;
        eps(1, 1) = -1e-3;
        eps(0, 1) = g;
        const Vector2d kap(0.5 * g / c1.prm.length_scale, 0.0);
        const PointUpdate<2> r = drucker_prager_perzyna_update(eps, kap, state, c1.elastic, model, dt);
        ASSERT_TRUE(r.stress.allFinite() && r.couple_stress.allFinite()) << "h " << h << " step " << n;
        const double f = f_of(r.stress, r.couple_stress, r.state.cohesion, c1.prm);
        const double tol = 1e-9 * r.stress.norm() + 1e-9 * c1.prm.cohesion;
        EXPECT_LE(f, eta * r.multiplier / dt + tol);
        if (r.plastic) {
          EXPECT_NEAR(f, eta * r.multiplier / dt, tol);
        }
        EXPECT_LE(r.state.cohesion, state.cohesion);
        EXPECT_GE(r.state.cohesion, c1.prm.residual_cohesion);
        EXPECT_GE(r.dissipation, 0.0);
        max_iterations = std::max(max_iterations, r.iterations);
        state = r.state;
      }
      EXPECT_EQ(state.cohesion, c1.prm.residual_cohesion) << "the path must reach the floor, h " << h;
      EXPECT_LT(max_iterations, 60);
    }
  }
}

// Dissipation sigma:d eps_vp + m:d kap_vp >= 0 for psi <= phi (README), on random states,
// for both cone matches and hardening and softening.
TEST(PlasticityReturnMap, DissipationIsNonNegative) {
  Case1 c1;
  std::mt19937_64 rng(3);
  int plastic = 0;
  for (ConeMatch match : {ConeMatch::triaxial_compression, ConeMatch::plane_strain}) {
    for (double psi_deg : {0.0, 15.0, 35.0}) {
      for (double h : {-5e6, 0.0, 5e6}) {
        c1.prm.cone_match = match;
        c1.prm.dilatancy_angle = psi_deg * kDeg;
        c1.prm.hardening = h;
        const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
        for (int n = 0; n < 100; ++n) {
          const RandomPoint rp = random_point(rng, 0.02, c1.prm.length_scale, model);
          const PointUpdate<2> r =
              drucker_prager_perzyna_update(rp.strain, rp.wryness, rp.state, c1.elastic, model, 7e-6);
          plastic += r.plastic;
          const double direct = r.stress.cwiseProduct(r.state.plastic_strain - rp.state.plastic_strain).sum() +
                                r.couple_stress.dot(r.state.plastic_wryness - rp.state.plastic_wryness);
          // The direct sum differences the accumulated plastic strains: allow their rounding.
          const double cancellation = 1e-15 * (r.stress.norm() * r.state.plastic_strain.norm() +
                                               r.couple_stress.norm() * r.state.plastic_wryness.norm());
          EXPECT_NEAR(r.dissipation, direct, 1e-12 * std::abs(direct) + 10.0 * cancellation);
          EXPECT_GE(r.dissipation, 0.0);
        }
      }
    }
  }
  EXPECT_GT(plastic, 500);
}

// 2-D plane strain is the 3-D model with the wryness tensor holding only k_zx, k_zy and the
// couple law m = B_w kap (a1 = a3 = 0, a2 = B_w). Agreement to 1e-12: the two take different
// block splits of the couple stress, so only rounding may differ.
TEST(PlasticityReturnMap, TwoDimensionalUpdateEqualsEmbeddedThreeDimensional) {
  Case1 c1;
  std::mt19937_64 rng(11);
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
  const CosseratElasticity<3> el3{
      c1.elastic.lambda, c1.elastic.mu, c1.elastic.mu_c, 0.0, c1.elastic.bending_modulus, 0.0};
  const auto embed = [](const Vector2d& v) {
    Matrix3d k = Matrix3d::Zero();
    k(2, 0) = v(0);
    k(2, 1) = v(1);
    return k;
  };
  int plastic = 0;
  for (int n = 0; n < 300; ++n) {
    const RandomPoint rp = random_point(rng, 0.02, c1.prm.length_scale, model);
    PlasticState<3> s3;
    s3.plastic_strain = rp.state.plastic_strain;
    s3.plastic_wryness = embed(rp.state.plastic_wryness);
    s3.equivalent_plastic_strain = rp.state.equivalent_plastic_strain;
    s3.cohesion = rp.state.cohesion;
    const PointUpdate<2> r2 = drucker_prager_perzyna_update(rp.strain, rp.wryness, rp.state, c1.elastic, model, 7e-6);
    const PointUpdate<3> r3 = drucker_prager_perzyna_update(rp.strain, embed(rp.wryness), s3, el3, model, 7e-6);
    plastic += r2.plastic;
    EXPECT_EQ(r2.plastic, r3.plastic);
    EXPECT_EQ(r2.apex, r3.apex);
    EXPECT_LE((r2.stress - r3.stress).norm(), 1e-12 * r2.stress.norm());
    EXPECT_LE((embed(r2.couple_stress) - r3.couple_stress).norm(), 1e-12 * r2.couple_stress.norm() + 1e-300);
    EXPECT_LE((embed(r2.state.plastic_wryness) - r3.state.plastic_wryness).norm(),
              1e-12 * r2.state.plastic_wryness.norm() + 1e-300);
    EXPECT_NEAR(r2.state.equivalent_plastic_strain, r3.state.equivalent_plastic_strain,
                1e-12 * r2.state.equivalent_plastic_strain);
  }
  EXPECT_GT(plastic, 100);
}

// A per-point kernel over many points gives the same bits with 1 and 2 threads (the update
// keeps no state between calls).
TEST(PlasticityReturnMap, BitwiseIdenticalForAnyThreadCount) {
  Case1 c1;
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(c1.prm);
  std::mt19937_64 rng(5);
  std::vector<RandomPoint> points;
  for (int n = 0; n < 20000; ++n) points.push_back(random_point(rng, 0.02, c1.prm.length_scale, model));
  const auto run = [&](int threads) {
    std::vector<double> out(points.size() * 12);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64)
    for (std::size_t i = 0; i < points.size(); ++i) {
      const RandomPoint& rp = points[i];
      const PointUpdate<2> r = drucker_prager_perzyna_update(rp.strain, rp.wryness, rp.state, c1.elastic, model, 7e-6);
      std::memcpy(&out[i * 12], r.stress.data(), 9 * sizeof(double));
      out[i * 12 + 9] = r.couple_stress(0);
      out[i * 12 + 10] = r.state.equivalent_plastic_strain;
      out[i * 12 + 11] = r.dissipation;
    }
    return out;
  };
  const std::vector<double> one = run(1), two = run(2);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
}

}  // namespace
}  // namespace mppm::plasticity
