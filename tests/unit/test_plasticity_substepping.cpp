// Consistency of the algorithmic (backward-Euler) update with the Perzyna ODE it integrates:
// along a loading-unloading strain path, with a moderate viscosity, the implicit update with
// N steps converges at first order to a forward-Euler integration of
//   eps_vp' = <f>/eta dg/dsigma,  kap_vp' = <f>/eta dg/dm,
//   ebar' = sqrt(1/3 e':e' + 1/3 e':e'^T + 2/3 l^2 kap_vp':kap_vp'),  c = max(c0 + h ebar, c_res)
// written here independently and run with steps 1000x finer than the finest implicit one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "solver/plasticity/drucker_prager_perzyna.hpp"
#include "tests/unit/shear_band_material.hpp"

namespace mppm::plasticity {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector2d;
constexpr double kDeg = std::numbers::pi / 180.0;

struct PathSetup {
  CosseratElasticity<2> el = testing::shear_band_elasticity();
  DruckerPragerParameters prm = testing::shear_band_parameters();
  double tau = 0.0;       // eta / (3 mu): the viscous relaxation time
  double duration = 0.0;  // of the path
  PathSetup() {
    prm.hardening = -2.0e6;  // twice the case's softening
    tau = prm.viscosity / (3.0 * el.mu);
    duration = 20.0 * tau;
  }
  // Piecewise-linear path: confined shear with wryness to t = T/2, then partial reversal.
  void path(double t, Matrix3d* eps, Vector2d* kap) const {
    const double s = t / duration;
    const double a = s <= 0.5 ? 2.0 * s : 1.0 - 0.8 * (s - 0.5);  // 0 -> 1 -> 0.6
    const double b = std::min(s, 0.5) * 2.0;                      // 0 -> 1, then held
    eps->setZero();
    (*eps)(0, 0) = -2e-3 * b;
    (*eps)(1, 1) = -6e-3 * b;
    (*eps)(0, 1) = 0.03 * a;
    (*eps)(1, 0) = 0.02 * a;
    *kap = Vector2d(8.0, -3.0) * a;
  }
};

struct Result {
  Matrix3d stress;
  Vector2d couple;
};

Result implicit_run(const PathSetup& su, const DruckerPragerPerzyna& model, int steps) {
  PlasticState<2> state = initial_plastic_state<2>(model);
  const double dt = su.duration / steps;
  PointUpdate<2> r;
  for (int n = 1; n <= steps; ++n) {
    Matrix3d eps;
    Vector2d kap;
    su.path(n * dt, &eps, &kap);
    r = drucker_prager_perzyna_update(eps, kap, state, su.el, model, dt);
    state = r.state;
  }
  return {r.stress, r.couple_stress};
}

Result explicit_run(const PathSetup& su, int steps) {
  const DruckerPragerParameters& p = su.prm;
  const double m_phi = 6.0 * std::sin(p.friction_angle) / (3.0 - std::sin(p.friction_angle));
  const double m_psi = 6.0 * std::sin(p.dilatancy_angle) / (3.0 - std::sin(p.dilatancy_angle));
  const double k_per_c = 6.0 * std::cos(p.friction_angle) / (3.0 - std::sin(p.friction_angle));
  const double l2 = p.length_scale * p.length_scale;
  const Matrix3d I = Matrix3d::Identity();
  Matrix3d eps_vp = Matrix3d::Zero();
  Vector2d kap_vp = Vector2d::Zero();
  double ebar = 0.0;
  const double dt = su.duration / steps;
  Matrix3d sigma;
  Vector2d m;
  for (int n = 0; n <= steps; ++n) {
    Matrix3d eps;
    Vector2d kap;
    su.path(n * dt, &eps, &kap);
    const Matrix3d e = eps - eps_vp;
    sigma = su.el.lambda * e.trace() * I + (su.el.mu + su.el.mu_c) * e + (su.el.mu - su.el.mu_c) * e.transpose();
    m = su.el.bending_modulus * (kap - kap_vp);
    if (n == steps) break;
    const Matrix3d s = sigma - sigma.trace() / 3.0 * I;
    const double j2 =
        0.25 * (s.cwiseProduct(s).sum() + s.cwiseProduct(s.transpose()).sum()) + 0.5 * m.squaredNorm() / l2;
    const double q = std::sqrt(3.0 * j2);
    const double c = std::max(p.cohesion + p.hardening * ebar, p.residual_cohesion);
    const double f = q + m_phi * sigma.trace() / 3.0 - k_per_c * c;
    if (f <= 0.0) continue;
    const double rate = f / p.viscosity;
    const Matrix3d d_eps = rate * (1.5 / q * 0.5 * (s + s.transpose()) + m_psi / 3.0 * I);
    const Vector2d d_kap = rate * 1.5 / q * m / l2;
    const Matrix3d dev = d_eps - d_eps.trace() / 3.0 * I;
    const double d_ebar =
        std::sqrt(1.0 / 3.0 * (dev.cwiseProduct(dev).sum() + dev.cwiseProduct(dev.transpose()).sum()) +
                  2.0 / 3.0 * l2 * d_kap.squaredNorm());
    eps_vp += dt * d_eps;
    kap_vp += dt * d_kap;
    ebar += dt * d_ebar;
  }
  return {sigma, m};
}

double distance(const Result& a, const Result& b, double l) {
  return std::sqrt((a.stress - b.stress).squaredNorm() + (a.couple - b.couple).squaredNorm() / (l * l));
}

// First order: halving dt halves the error (ratios within [1.6, 2.4]: the leading term
// dominates once dt is a fraction of tau), and at dt = T/400 = tau/20 the error is below
// 1 % of the stress. The explicit reference (dt = tau/20000) is ~1000x more accurate than
// the finest implicit run, so it does not pollute the ratios.
TEST(PlasticitySubstepping, ImplicitUpdateConvergesToFinelySubsteppedExplicitIntegration) {
  PathSetup su;
  const DruckerPragerPerzyna model = make_drucker_prager_perzyna(su.prm);
  const Result reference = explicit_run(su, 400000);
  const double l = su.prm.length_scale;
  const double size = std::sqrt(reference.stress.squaredNorm() + reference.couple.squaredNorm() / (l * l));
  std::vector<double> errors;
  for (int steps : {50, 100, 200, 400}) {
    errors.push_back(distance(implicit_run(su, model, steps), reference, l) / size);
    std::printf("  %3d steps (dt = %.3f tau): relative error %.3e\n", steps, su.duration / steps / su.tau,
                errors.back());
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double ratio = errors[i - 1] / errors[i];
    EXPECT_GT(ratio, 1.6) << "errors " << errors[i - 1] << " -> " << errors[i];
    EXPECT_LT(ratio, 2.4) << "errors " << errors[i - 1] << " -> " << errors[i];
  }
  EXPECT_LT(errors.back(), 1e-2);
  // The path yields: the end state is far from the elastic one.
  PathSetup elastic = su;
  elastic.prm.cohesion = elastic.prm.residual_cohesion = 1e12;
  const Result no_flow = implicit_run(elastic, make_drucker_prager_perzyna(elastic.prm), 50);
  EXPECT_GT(distance(no_flow, reference, l), 0.3 * size);
}

}  // namespace
}  // namespace mppm::plasticity
