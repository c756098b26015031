// Backward-Euler Perzyna return map of the micro-polar Drucker-Prager model.
//
// Why blocks: the generalized deviatoric stress splits into blocks X_g (symmetric deviatoric
// stress, skew stress, and the isotropic parts of the couple stress) on each of which both
// the elastic law (X_g = E_g * elastic strain) and the J2 gradient (3 c_g X_g / q) are
// multiples of X_g. Backward Euler then scales every block of the trial state by its own
// factor q / (q + G_g dgamma), G_g = 3 E_g c_g, and q solves
//     sum_g 3 c_g |X_g^trial|^2 / (q + G_g dgamma)^2 = 1.
// With a single G (classical DP) this is q = q_trial - G dgamma; with couple stresses the
// blocks have different G, hence the inner solve. README.md has the derivation.
#include "solver/plasticity/drucker_prager_perzyna.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mppm::plasticity {

double DruckerPragerPerzyna::cohesion_at(double ebar) const {
  return std::max(parameters.cohesion + parameters.hardening * ebar, parameters.residual_cohesion);
}

double DruckerPragerPerzyna::cohesion_slope_at(double ebar) const {
  return parameters.cohesion + parameters.hardening * ebar > parameters.residual_cohesion ? parameters.hardening : 0.0;
}

DruckerPragerPerzyna make_drucker_prager_perzyna(const DruckerPragerParameters& p) {
  const auto fail = [](const std::string& key, const std::string& problem) {
    throw std::invalid_argument(key + ": " + problem);
  };
  const double right_angle = 2.0 * std::atan(1.0);
  if (!(p.friction_angle >= 0.0 && p.friction_angle < right_angle))
    fail("viscoplasticity.friction_angle", "must be in [0, 90) deg");
  if (!(p.dilatancy_angle >= 0.0 && p.dilatancy_angle < right_angle))
    fail("viscoplasticity.dilatancy_angle", "must be in [0, 90) deg");
  if (!(p.cohesion >= 0.0 && std::isfinite(p.cohesion)))
    fail("viscoplasticity.cohesion", "must be a finite value >= 0");
  if (!std::isfinite(p.hardening)) fail("viscoplasticity.hardening", "must be finite");
  if (!(p.residual_cohesion >= 0.0 && p.residual_cohesion <= p.cohesion))
    fail("viscoplasticity.residual_cohesion", "must be in [0, cohesion]");
  if (!(p.viscosity >= 0.0 && std::isfinite(p.viscosity)))
    fail("viscoplasticity.viscosity", "must be a finite value >= 0 (0 = rate-independent)");
  if (!(p.length_scale >= 0.0 && std::isfinite(p.length_scale))) fail("length_scale", "must be a finite value >= 0");
  // The blocks' weights must keep J2 and ebar non-negative: symmetric and skew weights
  // a1 + a2 and a1 - a2 (b1 + b2, b1 - b2) must not be negative.
  if (!(p.j2.a1 + p.j2.a2 > 0.0 && p.j2.a1 >= p.j2.a2 && p.j2.a3 >= 0.0))
    fail("viscoplasticity.j2_weights", "need a1 + a2 > 0, a1 >= a2, a3 >= 0 (default 1/4, 1/4, 1/2)");
  if (!(p.equivalent_strain.b1 + p.equivalent_strain.b2 > 0.0 && p.equivalent_strain.b1 >= p.equivalent_strain.b2 &&
        p.equivalent_strain.b3 >= 0.0))
    fail("viscoplasticity.equivalent_strain_weights", "need b1 + b2 > 0, b1 >= b2, b3 >= 0 (default 1/3, 1/3, 2/3)");
  DruckerPragerPerzyna model;
  model.parameters = p;
  model.cone = cone_coefficients(p.friction_angle, p.dilatancy_angle, p.cone_match);
  return model;
}

namespace {

constexpr int kMaxBlocks = 5;  // sym dev stress, skew stress, up to 3 couple-stress parts

// One block of the generalized deviatoric stress, scaled as a whole by the return.
struct Block {
  double squared_norm = 0.0;   // A = |X_trial|^2
  double j2_weight = 0.0;      // c: contributes c |X|^2 to J2
  double modulus = 0.0;        // E: X = E * (elastic strain of the block)
  double strain_weight = 0.0;  // beta: contributes beta |dP|^2 to debar^2
  bool active() const { return j2_weight > 0.0 && squared_norm > 0.0 && modulus > 0.0; }
};

// The scalar problem left once the trial state is known (Dim-independent).
struct ScalarProblem {
  std::array<Block, kMaxBlocks> blocks{};
  int count = 0;
  double q_trial = 0.0, p_trial = 0.0, bulk = 0.0;
  double friction_slope = 0.0, dilatancy_slope = 0.0, cohesion_factor = 0.0;
  double ebar_start = 0.0, eta_over_dt = 0.0;
  const DruckerPragerPerzyna* model = nullptr;
  // Per active block: w = 3 c A, G = 3 E c, v = 9 beta c^2 A.
  std::array<double, kMaxBlocks> w{}, g{}, v{};
  int active = 0;
  double g_min = 0.0, g_max = 0.0;
};

struct ScalarSolution {
  double multiplier = 0.0;  // dgamma
  double q = 0.0;           // q_{n+1}
  double volumetric = 0.0;  // tr(d eps_vp)
  double debar = 0.0;       // d ebar
  bool apex = false;
  int iterations = 0;
  std::array<double, kMaxBlocks> scale{};  // X_g = scale_g * X_g^trial (for every block)
};

struct ConeEvaluation {
  double q = 0.0, dq = 0.0;          // q(dgamma) and dq/ddgamma
  double debar = 0.0, ddebar = 0.0;  // d ebar(dgamma) and its derivative
  double residual = 0.0, dresidual = 0.0;
};

// q(dgamma) on the cone: the root of h(q) = 1 - sum w / (q + G dgamma)^2. h increases and is
// concave in q, so Newton started left of the root climbs monotonically to it without
// overshoot. Left starts: q_trial - G_max dgamma always; better, any tangent of q(dgamma),
// which is convex (q' is minus a weighted mean of the G's whose weights shift to the
// smaller G as dgamma grows), so the tangent at the previous Newton iterate is a lower bound
// within O(step^2) of the root: one or two iterations.
double cone_q(const ScalarProblem& sp, double dgamma, double tangent_start) {
  if (dgamma <= 0.0) return sp.q_trial;
  const double lower = std::max(0.0, sp.q_trial - sp.g_max * dgamma);
  if (sp.g_max == sp.g_min) return lower;  // one modulus: closed form
  const double upper = std::max(0.0, sp.q_trial - sp.g_min * dgamma);
  double q = std::clamp(tangent_start, lower, upper);
  for (int it = 0; it < 100; ++it) {
    double s2 = 0.0, s3 = 0.0;
    for (int k = 0; k < sp.active; ++k) {
      const double d = q + sp.g[k] * dgamma;
      s2 += sp.w[k] / (d * d);
      s3 += sp.w[k] / (d * d * d);
    }
    const double h = 1.0 - s2;
    if (h >= 0.0) {
      // Right of the root by more than rounding: the start was not a lower bound after all
      // (cannot happen in exact arithmetic); restart from the guaranteed one.
      if (it == 0 && h > 1e-12 && q > lower) {
        q = lower;
        continue;
      }
      break;
    }
    const double next = std::min(q - h / (2.0 * s3), upper);
    if (!(next > q)) break;
    const double step = next - q;
    q = next;
    if (step <= 4.0 * std::numeric_limits<double>::epsilon() * sp.q_trial) break;
  }
  return q;
}

// `from` is the previous evaluation (at dgamma `from_dgamma`), whose tangent starts the q solve.
ConeEvaluation evaluate_cone(const ScalarProblem& sp, double dgamma, const ConeEvaluation& from, double from_dgamma) {
  ConeEvaluation e;
  e.q = cone_q(sp, dgamma, from.q + from.dq * (dgamma - from_dgamma));
  double s3w = 0.0, s3wg = 0.0, rho2 = 0.0;
  for (int k = 0; k < sp.active; ++k) {
    const double d = e.q + sp.g[k] * dgamma;
    s3w += sp.w[k] / (d * d * d);
    s3wg += sp.w[k] * sp.g[k] / (d * d * d);
    rho2 += sp.v[k] / (d * d);
  }
  e.dq = s3w > 0.0 ? -s3wg / s3w : 0.0;  // implicit differentiation of h(q, dgamma) = 0
  double drho2 = 0.0;
  for (int k = 0; k < sp.active; ++k) {
    const double d = e.q + sp.g[k] * dgamma;
    drho2 -= 2.0 * sp.v[k] * (e.dq + sp.g[k]) / (d * d * d);
  }
  const double rho = std::sqrt(rho2);
  const double drho = rho > 0.0 ? drho2 / (2.0 * rho) : 0.0;
  e.debar = dgamma * rho;  // = dgamma exactly for the default weights (work conjugacy)
  e.ddebar = rho + dgamma * drho;
  const double ebar = sp.ebar_start + e.debar;
  const double p = sp.p_trial - sp.bulk * sp.dilatancy_slope * dgamma;
  e.residual = e.q + sp.friction_slope * p - sp.cohesion_factor * sp.model->cohesion_at(ebar) - sp.eta_over_dt * dgamma;
  e.dresidual = e.dq - sp.friction_slope * sp.bulk * sp.dilatancy_slope -
                sp.cohesion_factor * sp.model->cohesion_slope_at(ebar) * e.ddebar - sp.eta_over_dt;
  return e;
}

ScalarSolution solve_return(ScalarProblem& sp) {
  ScalarSolution sol;
  sol.scale.fill(1.0);
  for (int b = 0; b < sp.count; ++b) {
    const Block& blk = sp.blocks[b];
    if (!blk.active()) continue;
    const int k = sp.active++;
    sp.w[k] = 3.0 * blk.j2_weight * blk.squared_norm;
    sp.g[k] = 3.0 * blk.modulus * blk.j2_weight;
    sp.v[k] = 9.0 * blk.strain_weight * blk.j2_weight * blk.j2_weight * blk.squared_norm;
  }
  double multiplier_max_sq = 0.0, debar_apex_sq = 0.0;
  sp.g_min = std::numeric_limits<double>::infinity();
  sp.g_max = 0.0;
  for (int k = 0; k < sp.active; ++k) {
    multiplier_max_sq += sp.w[k] / (sp.g[k] * sp.g[k]);
    debar_apex_sq += sp.v[k] / (sp.g[k] * sp.g[k]);
    sp.g_min = std::min(sp.g_min, sp.g[k]);
    sp.g_max = std::max(sp.g_max, sp.g[k]);
  }
  // dgamma_max brings q to zero: beyond it the cone return has no solution (the apex).
  const double multiplier_max = std::sqrt(multiplier_max_sq);
  const double debar_apex = std::sqrt(debar_apex_sq);
  const double cohesion_apex = sp.model->cohesion_at(sp.ebar_start + debar_apex);
  const double apex_residual = sp.friction_slope * (sp.p_trial - sp.bulk * sp.dilatancy_slope * multiplier_max) -
                               sp.cohesion_factor * cohesion_apex - sp.eta_over_dt * multiplier_max;
  const auto mark_active_scale = [&](auto scale_of) {
    for (int b = 0, k = 0; b < sp.count; ++b) {
      if (sp.blocks[b].active()) sol.scale[b] = scale_of(k++);
    }
  };

  if (sp.active == 0 || apex_residual >= 0.0) {
    // Apex: every block in J2 vanishes; the deviatoric plastic strain is the whole trial
    // deviatoric elastic strain (so d ebar is fixed), and p follows the volumetric flow
    // M_psi dgamma with the same overstress law, linear in dgamma.
    sol.apex = true;
    sol.q = 0.0;
    sol.debar = debar_apex;
    mark_active_scale([](int) { return 0.0; });
    const double denominator = sp.friction_slope * sp.bulk * sp.dilatancy_slope + sp.eta_over_dt;
    const double excess = sp.friction_slope * sp.p_trial - sp.cohesion_factor * cohesion_apex;
    if (denominator > 0.0) {
      sol.multiplier = std::max(multiplier_max, excess / denominator);
      sol.volumetric = sp.dilatancy_slope * sol.multiplier;
    } else {
      // Rate-independent and non-dilatant (eta = 0, psi = 0): no flow along the potential can
      // lower p, so the excess mean stress is cut off by volumetric plastic strain
      // (a tension cut-off at the apex) instead of leaving the stress outside the cone.
      sol.multiplier = multiplier_max;
      const double p_apex =
          sp.friction_slope > 0.0 ? sp.cohesion_factor * cohesion_apex / sp.friction_slope : sp.p_trial;
      sol.volumetric = std::max(0.0, (sp.p_trial - p_apex) / sp.bulk);
    }
    return sol;
  }

  // Cone: bracketed Newton on dgamma in (0, dgamma_max). r(0) = f_trial > 0 and
  // r(dgamma_max) = apex_residual < 0; a Newton step that leaves the bracket (possible with
  // strong softening, where r is not monotone) is replaced by bisection.
  const double stress_scale =
      sp.q_trial + std::abs(sp.friction_slope * sp.p_trial) + sp.cohesion_factor * sp.model->cohesion_at(sp.ebar_start);
  const double tolerance = 1e-13 * stress_scale;
  double lo = 0.0, hi = multiplier_max;
  double x = 0.0;
  ConeEvaluation e = evaluate_cone(sp, x, ConeEvaluation{}, 0.0);
  for (int it = 1; it <= 200; ++it) {
    double next = e.dresidual < 0.0 ? x - e.residual / e.dresidual : lo - 1.0;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    e = evaluate_cone(sp, next, e, x);
    x = next;
    sol.iterations = it;
    if (e.residual > 0.0)
      lo = x;
    else
      hi = x;
    if (std::abs(e.residual) <= tolerance || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * hi) break;
  }
  sol.multiplier = x;
  sol.q = e.q;
  sol.debar = e.debar;
  sol.volumetric = sp.dilatancy_slope * x;
  mark_active_scale([&](int k) { return e.q / (e.q + sp.g[k] * x); });
  return sol;
}

// The couple stress split into parts on which the isotropic couple law is a multiple.
template <int Dim>
struct CoupleParts;
template <>
struct CoupleParts<2> {
  static constexpr int count = 1;
  std::array<Eigen::Vector2d, 1> part;
  std::array<double, 1> modulus;
};
template <>
struct CoupleParts<3> {
  static constexpr int count = 3;
  std::array<Eigen::Matrix3d, 3> part;  // volumetric, symmetric deviatoric, skew
  std::array<double, 3> modulus;
};

CoupleParts<2> split_couple(const Eigen::Vector2d& m, const CosseratElasticity<2>& e) {
  return {{m}, {e.bending_modulus}};
}

CoupleParts<3> split_couple(const Eigen::Matrix3d& m, const CosseratElasticity<3>& e) {
  const Eigen::Matrix3d vol = (m.trace() / 3.0) * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d sym = 0.5 * (m + m.transpose());
  return {{vol, sym - vol, 0.5 * (m - m.transpose())}, {3.0 * e.a1 + e.a2 + e.a3, e.a2 + e.a3, e.a2 - e.a3}};
}

template <int Dim>
PointUpdate<Dim> update(const Eigen::Matrix3d& strain, const Curvature<Dim>& wryness, const PlasticState<Dim>& state,
                        const CosseratElasticity<Dim>& elasticity, const DruckerPragerPerzyna& model, double dt) {
  const DruckerPragerParameters& prm = model.parameters;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d stress_trial = cosserat_stress(strain - state.plastic_strain, elasticity);
  const Curvature<Dim> couple_trial = couple_stress(Curvature<Dim>(wryness - state.plastic_wryness), elasticity);
  const double p_trial = stress_trial.trace() / 3.0;
  const Eigen::Matrix3d dev = stress_trial - p_trial * identity;
  const Eigen::Matrix3d sym_dev = 0.5 * (dev + dev.transpose());
  const Eigen::Matrix3d skew = 0.5 * (dev - dev.transpose());
  const CoupleParts<Dim> couple = split_couple(couple_trial, elasticity);

  ScalarProblem sp;
  sp.model = &model;
  const GeneralizedJ2Weights& a = prm.j2;
  const EquivalentStrainWeights& b = prm.equivalent_strain;
  sp.blocks[0] = {sym_dev.squaredNorm(), a.a1 + a.a2, 2.0 * elasticity.mu, b.b1 + b.b2};
  sp.blocks[1] = {skew.squaredNorm(), a.a1 - a.a2, 2.0 * elasticity.mu_c, b.b1 - b.b2};
  const double l2 = prm.length_scale * prm.length_scale;
  for (int k = 0; k < CoupleParts<Dim>::count; ++k) {
    // Without a length scale the couple stress does not enter J2 and stays elastic.
    sp.blocks[2 + k] = {couple.part[k].squaredNorm(), l2 > 0.0 ? a.a3 / l2 : 0.0, couple.modulus[k], b.b3 * l2};
  }
  sp.count = 2 + CoupleParts<Dim>::count;
  double j2_trial = 0.0;
  for (int k = 0; k < sp.count; ++k) {
    if (sp.blocks[k].active()) j2_trial += sp.blocks[k].j2_weight * sp.blocks[k].squared_norm;
  }
  sp.q_trial = std::sqrt(3.0 * j2_trial);
  sp.p_trial = p_trial;
  sp.bulk = bulk_modulus(elasticity);
  sp.friction_slope = model.cone.friction_slope;
  sp.dilatancy_slope = model.cone.dilatancy_slope;
  sp.cohesion_factor = model.cone.cohesion_factor;
  sp.ebar_start = state.equivalent_plastic_strain;
  sp.eta_over_dt = prm.viscosity > 0.0 ? prm.viscosity / dt : 0.0;

  PointUpdate<Dim> out;
  out.state = state;
  out.state.cohesion = model.cohesion_at(state.equivalent_plastic_strain);
  const double f_trial = sp.q_trial + sp.friction_slope * p_trial - model.cone_strength(out.state.cohesion);
  // A viscous material has no time to flow in a step of zero length: the trial stands.
  const bool no_time_to_flow = !(dt > 0.0) && prm.viscosity > 0.0;
  if (!(f_trial > 0.0) || no_time_to_flow) {
    out.stress = stress_trial;
    out.couple_stress = couple_trial;
    out.overstress = 0.0;
    return out;
  }

  const ScalarSolution sol = solve_return(sp);
  const double p = p_trial - sp.bulk * sol.volumetric;
  out.stress = sol.scale[0] * sym_dev + sol.scale[1] * skew + p * identity;
  out.couple_stress.setZero();
  for (int k = 0; k < CoupleParts<Dim>::count; ++k) out.couple_stress += sol.scale[2 + k] * couple.part[k];

  // Plastic increments: what each block lost, through its elastic compliance.
  Eigen::Matrix3d d_strain = (sol.volumetric / 3.0) * identity;
  if (sol.scale[0] != 1.0) d_strain += ((1.0 - sol.scale[0]) / sp.blocks[0].modulus) * sym_dev;
  if (sol.scale[1] != 1.0) d_strain += ((1.0 - sol.scale[1]) / sp.blocks[1].modulus) * skew;
  Curvature<Dim> d_wryness = Curvature<Dim>::Zero();
  for (int k = 0; k < CoupleParts<Dim>::count; ++k) {
    if (sol.scale[2 + k] != 1.0) d_wryness += ((1.0 - sol.scale[2 + k]) / couple.modulus[k]) * couple.part[k];
  }

  out.plastic = true;
  out.apex = sol.apex;
  out.iterations = sol.iterations;
  out.multiplier = sol.multiplier;
  out.state.plastic_strain += d_strain;
  out.state.plastic_wryness += d_wryness;
  out.state.equivalent_plastic_strain += sol.debar;
  out.state.cohesion = model.cohesion_at(out.state.equivalent_plastic_strain);
  out.dissipation = contract(out.stress, d_strain) + contract(out.couple_stress, d_wryness);
  out.overstress = sol.q + sp.friction_slope * p - model.cone_strength(out.state.cohesion);
  return out;
}

}  // namespace

PointUpdate<2> drucker_prager_perzyna_update(const Eigen::Matrix3d& strain, const Eigen::Vector2d& wryness,
                                             const PlasticState<2>& state, const CosseratElasticity<2>& elasticity,
                                             const DruckerPragerPerzyna& model, double dt) {
  return update<2>(strain, wryness, state, elasticity, model, dt);
}

PointUpdate<3> drucker_prager_perzyna_update(const Eigen::Matrix3d& strain, const Eigen::Matrix3d& wryness,
                                             const PlasticState<3>& state, const CosseratElasticity<3>& elasticity,
                                             const DruckerPragerPerzyna& model, double dt) {
  return update<3>(strain, wryness, state, elasticity, model, dt);
}

}  // namespace mppm::plasticity
