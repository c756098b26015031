// Largest eigenvalue of M^-1 K with the internal-force kernel as the operator (K v = -f(v) V).
#include "solver/critical_time_step.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "common/input_error.hpp"
#include "solver/exact_point_sums.hpp"
#include "solver/model_patch.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/point_stability.hpp"
#include "solver/shape_tensor.hpp"

namespace mppm::solver {

namespace {

enum class Block { coupled, translational, rotational };

// A deterministic start vector from the point's index in the points file (its global id): the same
// for any thread count or partition.
double start_value(std::int64_t id, int component) {
  std::uint64_t x = static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull +
                    static_cast<std::uint64_t>(component + 1) * 0xBF58476D1CE4E5B9ull;
  x ^= x >> 31;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 29;
  return static_cast<double>(x >> 11) * 0x1.0p-53 - 0.5;
}

// When the largest Ritz value counts as converged: it has moved by no more than `tolerance`
// (relative) over the last `window` iterations, after at least `least` and at most `most`.
struct Convergence {
  double tolerance;
  int window, least, most;
};
// The step: 1e-8 over the last 5 of at least 20, far finer than any safety factor (a single small
// change can be a plateau before the Krylov space reaches the top of the spectrum: on a 3-D
// sample block the value creeps by 3e-7 per iteration for 7 iterations before it climbs another
// 6e-4).
constexpr Convergence step_convergence{1e-8, 5, 20, 150};
// Naming the mode and its parameter compares block values with each other and with half of one
// another: 1e-2 over the last 3 of at least 10 decides that at half the cost or less. The values
// fall short of the converged ones (their steps are long) by up to about 5e-3 (measured in the
// step: 5e-4 on the 3-D benchmark block after 14 iterations; 4.7e-4 and 2.8e-3, translational and
// rotational, on the Kalthoff-Winkler plate; 4.6e-3 on a lattice of the shear-band material).
constexpr Convergence naming_convergence{1e-2, 3, 10, 60};

// What a Lanczos run works with: where the previous Lanczos vector lives (see largest_eigenvalue)
// and the kernel that applies the operator, chosen once per set of estimates
// (Model::linear_operator_kernel).
struct Workspace {
  std::vector<double>& prev_u;
  std::vector<double>& prev_w;
  InternalForceFunction apply;
  // A patch's own points (model_patch.hpp): the Lanczos vectors vanish elsewhere. Null: every point.
  const std::vector<std::uint8_t>* support = nullptr;
};

struct OperatorEstimate {
  double lambda = 0.0;  // omega_max^2 (a Ritz value: approaches it from below)
  int iterations = 0;
};

// Lanczos on M^-1 K, which is self-adjoint in the mass inner product <a, b>_M = a^T M b. It is
// the Krylov refinement of the power iteration: the largest Ritz value converges to omega_max^2
// in a few tens of operator applications even where the top of the spectrum is dense (a plain
// power iteration stalls there and under-estimates omega_max). Only the three-term recurrence
// is kept (no stored basis): loss of orthogonality creates duplicate Ritz values, not wrong
// extreme ones. The Lanczos vector q lives in the model's displacement and rotation (where the
// kernel reads it) and w = M^-1 K q in its force and moment (where the kernel writes it), and the
// previous q in `prev_u`, `prev_w` (the model's velocity and spin before a run: see
// critical_time_step), so that no vector of the model's size is allocated here: this runs before
// the time loop, and its vectors would otherwise set the run's peak memory.
//
// With `enough`, the iteration also stops as soon as the largest Ritz value reaches it: each
// Lanczos matrix holds the previous one as its leading block, so the largest Ritz value never
// falls (Cauchy interlacing), and the converged estimate would be at least as large. A caller
// that only asks whether the estimate lies below a threshold gets the converged run's answer.
OperatorEstimate largest_eigenvalue(Model& model, Block block, const Convergence& convergence, Workspace& ws,
                                    double enough = std::numeric_limits<double>::infinity()) {
  std::vector<double>& prev_u = ws.prev_u;
  std::vector<double>& prev_w = ws.prev_w;
  PointData& p = model.points;
  const int D = p.dimension;
  const int R = p.rotation_components;
  const std::size_t n = p.owned;
  const double rho = model.constants.density;
  const double inertia = model.constants.micro_inertia;
  const bool use_u = block != Block::rotational;
  const bool use_w = block != Block::translational && R > 0;
  std::vector<double>& q_u = p.displacement;
  std::vector<double>& q_w = p.rotation;
  std::vector<double>& w_u = p.force;
  std::vector<double>& w_w = p.moment;
  prev_u.assign(q_u.size(), 0.0);
  prev_w.assign(q_w.size(), 0.0);
  const auto outside = [&](std::size_t i) { return ws.support && !(*ws.support)[i]; };
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t id = p.global_index(i);
    for (int c = 0; c < D; ++c) q_u[i * D + c] = use_u && !outside(i) ? start_value(id, c) : 0.0;
    for (int c = 0; c < R; ++c) q_w[i * R + c] = use_w && !outside(i) ? start_value(id, D + c) : 0.0;
  }
  // Summed exactly over the points (exact_point_sums.hpp): the same bits for any thread count or
  // partition.
  auto mass_dot = [&](const std::vector<double>& au, const std::vector<double>& aw, const std::vector<double>& bu,
                      const std::vector<double>& bw) {
    return exact_point_sums<1>(p, [&](std::size_t lo, std::size_t hi, ExactSums<1>& acc) {
      for (std::size_t i = lo; i < hi; ++i) {
        double su = 0.0, sw = 0.0;
        for (int c = 0; c < D; ++c) su += au[i * D + c] * bu[i * D + c];
        for (int c = 0; c < R; ++c) sw += aw[i * R + c] * bw[i * R + c];
        acc[0] += p.volume[i] * (rho * su + inertia * sw);
      }
    })[0];
  };
  double norm = std::sqrt(mass_dot(q_u, q_w, q_u, q_w));
  for (std::size_t k = 0; k < n * D; ++k) q_u[k] /= norm;
  for (std::size_t k = 0; k < n * R; ++k) q_w[k] /= norm;
  std::vector<double> alpha, beta;
  OperatorEstimate r;
  std::vector<double> history;
  for (int it = 1; it <= convergence.most; ++it) {
    // w = M^-1 K q = -(internal force of the field q) / mass density
    ws.apply(model.points, model.bonds, model.constants, nullptr);
    for (std::size_t k = 0; k < n * D; ++k) w_u[k] = use_u ? -w_u[k] / rho : 0.0;
    for (std::size_t k = 0; k < n * R; ++k) w_w[k] = use_w ? -w_w[k] / inertia : 0.0;
    if (ws.support)  // the principal submatrix of the patch's own points
      for (std::size_t i = 0; i < n; ++i)
        if (outside(i)) {
          std::fill_n(&w_u[i * D], D, 0.0);
          if (R > 0) std::fill_n(&w_w[i * R], R, 0.0);
        }
    const double a = mass_dot(w_u, w_w, q_u, q_w);
    const double b_prev = beta.empty() ? 0.0 : beta.back();
    for (std::size_t k = 0; k < n * D; ++k) w_u[k] -= a * q_u[k] + b_prev * prev_u[k];
    for (std::size_t k = 0; k < n * R; ++k) w_w[k] -= a * q_w[k] + b_prev * prev_w[k];
    alpha.push_back(a);
    // Largest eigenvalue of the tridiagonal Lanczos matrix.
    const int m = static_cast<int>(alpha.size());
    Eigen::MatrixXd t = Eigen::MatrixXd::Zero(m, m);
    for (int k = 0; k < m; ++k) {
      t(k, k) = alpha[k];
      if (k + 1 < m) t(k, k + 1) = t(k + 1, k) = beta[k];
    }
    const double ritz = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(t, Eigen::EigenvaluesOnly).eigenvalues()(m - 1);
    r.lambda = ritz;
    r.iterations = it;
    history.push_back(ritz);
    if (ritz >= enough) break;
    if (it >= convergence.least &&
        std::abs(ritz - history[history.size() - 1 - static_cast<std::size_t>(convergence.window)]) <=
            convergence.tolerance * std::abs(ritz))
      break;
    const double b = std::sqrt(mass_dot(w_u, w_w, w_u, w_w));
    if (!(b > 1e-14 * std::abs(ritz))) break;  // invariant subspace: the Ritz values are exact
    beta.push_back(b);
    prev_u.swap(q_u);
    prev_w.swap(q_w);
    for (std::size_t k = 0; k < n * D; ++k) q_u[k] = w_u[k] / b;
    for (std::size_t k = 0; k < n * R; ++k) q_w[k] = w_w[k] / b;
  }
  return r;
}

// The explicit scheme's step of a mode of frequency omega (omega^2 given), 2 / omega, and back.
double step_of(double omega_squared) { return 2.0 / std::sqrt(omega_squared); }
double omega_squared_of(double step) { return 4.0 / (step * step); }

std::string number(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

// Lends the model's state to the Lanczos iteration (its vectors live there, see
// largest_eigenvalue) and puts it back afterwards. Before a run the state is the reference
// configuration at rest (all +0.0, as allocated): then nothing is copied, and the velocity and spin
// hold the previous Lanczos vector, so no vector of the model's size is made.
// Pore fluid: the operator is the kernel's response at the fluid content held (undrained, the
// stiffening lambda + b^2 M of docs/theory.md section 12); the content is set to n0 (no change)
// for it, so that the response is linear in the Lanczos vector (no pressure at zero strain).
template <typename Estimates>
void with_operator(Model& model, Estimates&& estimates) {
  PointData& p = model.points;
  auto zero = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0 && !std::signbit(x); });
  };
  const bool rest = zero(p.displacement) && zero(p.rotation) && zero(p.velocity) && zero(p.spin);
  std::vector<double> saved_u, saved_w, own_prev_u, own_prev_w;
  if (!rest) {
    saved_u = p.displacement;
    saved_w = p.rotation;
  }
  std::vector<double> saved_fluid_content;
  if (!p.fluid_content_change.empty()) {
    saved_fluid_content = p.fluid_content_change;
    for (std::size_t i = 0; i < p.owned; ++i)
      if (p.region[i] == 0) p.fluid_content_change[i] = 0.0;
  }
  Workspace ws{rest ? p.velocity : own_prev_u, rest ? p.spin : own_prev_w, model.linear_operator_kernel()};
  estimates(ws);
  if (rest) {
    for (auto* v : {&p.displacement, &p.rotation, &p.velocity, &p.spin}) std::fill(v->begin(), v->end(), 0.0);
  } else {
    p.displacement = saved_u;
    p.rotation = saved_w;
  }
  if (!saved_fluid_content.empty()) p.fluid_content_change = std::move(saved_fluid_content);
  model.compute_internal_forces(false);
}

// The translational and rotational block steps, the limiting mode and the parameter that drives
// it, for the model whose coupled step is in `out`.
// The density that a translational step is credited over (the mixture's with the pore fluid).
std::string density_text(const Model& model) {
  const CosseratConstants& c = model.constants;
  const bool fluid = !model.points.fluid_content_change.empty();
  return (!fluid        ? " over the density rho = solid_fraction * density = "
          : c.retention ? " over the mixture density rho = solid_fraction * density + porosity * S_r * fluid_density "
                          "(S_r of the start) = "
                        : " over the mixture density rho = solid_fraction * density + porosity * fluid_density = ") +
         number(c.density) + " kg/m^3";
}

// The translational block's step from its omega_max^2, named as the limiting mode and credited to
// lambda and mu (stiffened by the pore fluid held in the pores, if any); name_mode may credit it to
// another modulus, or the rotational block, afterwards.
void name_translational(const Model& model, CriticalTimeStep& out, double trans_lambda) {
  const CosseratConstants& c = model.constants;
  const std::string undrained = !model.points.fluid_content_change.empty()
                                    ? ", stiffened by the pore fluid held in the pores: undrained lambda + b^2 M = " +
                                          number(c.lambda + c.biot_coefficient * c.biot_coefficient * c.biot_modulus) +
                                          " Pa with material.pore_fluid.biot_modulus M = " + number(c.biot_modulus) +
                                          " Pa and biot_coefficient b = " + number(c.biot_coefficient)
                                    : std::string();
  out.translational = step_of(trans_lambda);
  out.limiting_mode = "translational";
  out.driver = "material.lambda and material.mu (P-wave modulus lambda + 2 mu = " + number(c.lambda + 2.0 * c.mu) +
               " Pa, with numerics.stabilization G_s = " + number(c.stabilization) + undrained + ")" +
               density_text(model);
}

// Where a block's naming estimates run: a model (the whole one, or a patch) and the workspace lent
// to it (with_operator).
struct BlockOperator {
  Model* model;
  Workspace* ws;
};

// Names the mode of a model with micro-rotations (without them the translational block is the
// coupled operator: name_translational alone), each block estimated on its operator, or given
// (`known`: the translational and the rotational omega^2).
void name_mode(CriticalTimeStep& out, const Convergence& convergence, BlockOperator translational,
               BlockOperator rotational, const std::optional<std::array<double, 2>>& known = std::nullopt) {
  out.naming_iterations = 0;
  auto on = [&](Block b) { return b == Block::rotational ? rotational : translational; };
  auto estimate = [&](Block b, double enough = std::numeric_limits<double>::infinity()) {
    const OperatorEstimate e = largest_eigenvalue(*on(b).model, b, convergence, *on(b).ws, enough);
    out.naming_iterations += e.iterations;
    return e;
  };
  const double trans_lambda = known ? (*known)[0] : estimate(Block::translational).lambda;
  name_translational(*translational.model, out, trans_lambda);
  const CosseratConstants& c = translational.model->constants;  // (the same on every operator)
  // Which stiffness drives a block is told by the same estimate with a modulus switched off: the
  // operator is linear in the moduli, and each term of the energy is positive semi-definite, so
  // switching one off can only lower omega_max^2; the block is credited to the modulus without
  // which less than half of omega_max^2 is left. These extra estimates run only for the limiting
  // block. Each gives the fraction of the block's omega_max^2 left without the modulus, and stops
  // once that reaches the half (`enough` of largest_eigenvalue: the converged estimate would not be
  // below it either), so a fraction is exact only below the half, the one case where it is quoted.
  // The stabilization tensors C:K^-1 that a switch may zero are rebuilt from K^-1 and the restored
  // constants afterwards (the same bits), not copied: a copy would cost 9 doubles per point.
  constexpr double credit = 0.5;
  auto fraction_left_without = [&](Block b, double block_lambda, auto&& switch_off) {
    Model& m = *on(b).model;
    const CosseratConstants saved = m.constants;
    switch_off(m.constants, m.points);
    const OperatorEstimate e = estimate(b, credit * block_lambda);
    m.constants = saved;
    update_stabilization_tensors(m.points, m.constants);
    return e.lambda / block_lambda;
  };
  const std::string inertia = " over the micro-inertia I = 1/2 pi rho l^2 = " + number(c.micro_inertia) +
                              " kg/m (material.length_scale l = " + number(c.length_scale) + " m)";
  const double rot_lambda = known ? (*known)[1] : estimate(Block::rotational).lambda;
  out.rotational = step_of(rot_lambda);
  if (out.rotational < out.translational) {
    out.limiting_mode = "rotational";
    // Three stiffnesses act on a micro-rotation: the bending modulus B_w (couple stress and its
    // stabilization), mu_c on the skew strain -[w]_x, and, at the lattice scale, lambda and mu
    // through the 1/2 (w_i + w_j) x xi term of the composite state (for a rotation pattern of high
    // wave number the family average of w_i + w_j is anisotropic: it has a symmetric strain part)
    // and the stabilization of U. First the bending modulus alone (lambda = mu = mu_c = 0, the
    // translational stabilization C:K^-1 off); if that is not it, the estimate without mu_c tells
    // mu_c from lambda and mu.
    const double bending = fraction_left_without(Block::rotational, rot_lambda, [](CosseratConstants& k, PointData& p) {
      k.lambda = k.mu = k.mu_c = 0.0;
      std::fill(p.stabilization_ck.begin(), p.stabilization_ck.end(), 0.0);
    });
    if (bending >= credit) {
      out.driver = std::string("material.couple_moduli (bending modulus B_w = ") + (c.dimension == 2 ? "a3" : "a2") +
                   " = " + number(c.bending_modulus) + " N)" + inertia;
    } else if (c.mu_c > 0.0 && fraction_left_without(Block::rotational, rot_lambda,
                                                     [](CosseratConstants& k, PointData&) { k.mu_c = 0.0; }) < credit) {
      out.driver = "material.mu_c = " + number(c.mu_c) + " Pa" + inertia;
    } else {
      out.driver =
          "material.lambda and material.mu (lambda + 2 mu = " + number(c.lambda + 2.0 * c.mu) +
          " Pa) acting on the micro-rotation through the composite state U = (u_j - u_i) - 1/2 (w_i + w_j) x xi "
          "(the bending modulus B_w = " +
          number(c.bending_modulus) + " N alone gives " + number(bending) + " of omega_max^2)" + inertia;
    }
  } else if (c.mu_c > 0.0 && fraction_left_without(Block::translational, trans_lambda,
                                                   [](CosseratConstants& k, PointData&) { k.mu_c = 0.0; }) < credit) {
    // mu_c stiffens the translational waves too: sigma has (mu + mu_c) eps + (mu - mu_c) eps^T, so
    // the skew part of grad u (the shear waves' rotation) costs 2 mu_c.
    out.driver = "material.mu_c = " + number(c.mu_c) +
                 " Pa (the couple modulus stiffens the shear waves: mu + mu_c = " + number(c.mu + c.mu_c) +
                 " Pa against the P-wave modulus lambda + 2 mu = " + number(c.lambda + 2.0 * c.mu) + " Pa)" +
                 density_text(*translational.model);
  }
}

// The coupled estimate sets the step (step_convergence).
void estimate_coupled(Model& model, CriticalTimeStep& out, Workspace& ws) {
  const OperatorEstimate coupled = largest_eigenvalue(model, Block::coupled, step_convergence, ws);
  out.step = step_of(coupled.lambda);
  out.iterations = coupled.iterations;
}

// The patch's radii, in horizons, tried in turn: on the 3-D benchmark block (60^3, horizon factor
// 2.05, corner modes) the patch's coupled estimate falls short of the whole model's by 6e-4 at 2
// horizons, 1.4e-5 at 3 and 2.6e-7 at 4 (825 points with their neighbours); on the crack-branching
// plate by 8e-4, 6e-5, 1.7e-6 and 1e-8 at 2, 3, 4 and 6.
constexpr double patch_radii[] = {4.0, 8.0};
// The patch names the mode when its limiting block's omega^2 is the critical step's coupled one within
// this: the highest mode is then that block's and lives in the patch, and the other block, whose
// omega^2 is at most the coupled one, could limit only in a tie within it. 2e-3 is 1e-3 in the
// step, about the accuracy of the whole model's naming (naming_convergence). Where the highest mode mixes
// translation and rotation (both blocks' steps well above the coupled one), the whole model names it.
constexpr double patch_tolerance = 2e-3;
// A patch's estimate above the whole model's by more than this (far above step_convergence) means
// that the whole model's Lanczos run stopped short of the top.
constexpr double patch_above_whole = 1e-6;
// A patch with its neighbours larger than this share of the model is not tried: its estimates
// (60-110 applications) would cost a third of what the whole model's naming costs (20-40) or more.
constexpr double patch_largest_share = 0.1;

enum class PatchNaming {
  named,      // the patch holds the highest mode, as its limiting block's
  too_small,  // its coupled estimate falls short of the whole model's: a larger patch may hold it
  mixed,      // it holds the highest mode, which mixes translation and rotation
  too_large,  // over patch_largest_share of the model
};

// A block's estimate (the coupled one by default) on a patch's own points.
OperatorEstimate patch_estimate(ModelPatch& patch, Block block = Block::coupled) {
  OperatorEstimate e;
  with_operator(patch.model, [&](Workspace& ws) {
    ws.support = &patch.inside;
    e = largest_eigenvalue(patch.model, block, step_convergence, ws);
  });
  return e;
}

// Names the mode (into `named`) from the blocks' omega^2 (`known`: translational, rotational),
// estimated in `iterations` applications: the modulus credits run on each block's patch (one patch
// for both, or one each).
void name_mode_from_blocks(CriticalTimeStep& named, ModelPatch& translational, ModelPatch& rotational,
                           const std::array<double, 2>& known, int iterations) {
  const auto name = [&](Workspace& on_translational, Workspace& on_rotational) {
    name_mode(named, step_convergence, {&translational.model, &on_translational}, {&rotational.model, &on_rotational},
              known);
  };
  with_operator(translational.model, [&](Workspace& on_translational) {
    on_translational.support = &translational.inside;
    if (&translational == &rotational) return name(on_translational, on_translational);
    with_operator(rotational.model, [&](Workspace& on_rotational) {
      on_rotational.support = &rotational.inside;
      name(on_translational, on_rotational);
    });
  });
  named.naming_iterations += iterations;
}

// Names the mode on a patch (into `named`): its blocks' estimates side by side, the rotational one on
// a copy of the patch (the same bits as one after the other on the patch; on one thread they are,
// without the copy), then the modulus credits on the patch.
void name_mode_on_patch_blocks(ModelPatch& patch, CriticalTimeStep& named) {
  std::optional<ModelPatch> twin;
  if (runs_side_by_side()) twin = patch;
  OperatorEstimate translational, rotational;
  side_by_side([&] { translational = patch_estimate(patch, Block::translational); },
               [&] { rotational = patch_estimate(twin ? *twin : patch, Block::rotational); });
  name_mode_from_blocks(named, patch, patch, {translational.lambda, rotational.lambda},
                        translational.iterations + rotational.iterations);
}

// Names the mode on a patch around `centre` of the given radius (into `critical` if named): the
// step's patch if it is that one (its coupled estimate known), else a patch cut here.
PatchNaming name_mode_on_patch(Model& model, CriticalTimeStep& critical, const PatchCentre& centre, double radius,
                               std::optional<StepPatch>* kept) {
  const bool reuse = kept && kept->has_value() && (*kept)->radius == radius && (*kept)->centre == centre.position;
  std::optional<ModelPatch> cut;
  if (!reuse) cut = cut_patch(model, centre.position, radius);
  ModelPatch& patch = reuse ? (*kept)->patch : *cut;
  if (static_cast<double>(patch.model.points.owned) > patch_largest_share * static_cast<double>(model_points(model)))
    return PatchNaming::too_large;
  const double whole = omega_squared_of(critical.step);
  CriticalTimeStep named = critical;
  OperatorEstimate coupled;
  if (reuse) coupled.lambda = (*kept)->coupled_lambda;  // its iterations were the step's
  // The patch costs a small fraction of the whole operator: its estimates converge as tightly
  // as the step's.
  if (!reuse) coupled = patch_estimate(patch);
  if (coupled.lambda >= (1.0 - patch_tolerance) * whole) name_mode_on_patch_blocks(patch, named);
  if (coupled.lambda > (1.0 + patch_above_whole) * whole) {
    critical.step = named.step = step_of(coupled.lambda);
    critical.step_from_patch = named.step_from_patch = true;
  }
  if (coupled.lambda < (1.0 - patch_tolerance) * whole) return PatchNaming::too_small;
  const double limiting = named.limiting_mode == "rotational" ? named.rotational : named.translational;
  if (omega_squared_of(limiting) < (1.0 - patch_tolerance) * whole) return PatchNaming::mixed;
  named.naming_iterations += coupled.iterations;
  named.naming_patch_points = patch.points_inside;
  named.naming_patch_centre = centre.position;
  critical = named;
  return PatchNaming::named;
}

// The step's patches (docs/theory.md section 9): the points within 4 horizons of a centre, checked
// against those within 3. The patches are nested principal submatrices, so their estimates rise
// with the radius toward the whole model's; the step takes the 4-horizon estimate raised by the
// rise from 3 to 4 horizons, which covers the 4-horizon patch's shortfall below the whole model's
// on every case measured (the shortfall, then the rise, around the stiffest point of all): the
// 3-D benchmark block (216 000 points) 2.6e-7, 1.4e-5; the crack-branching plate 1.7e-6, 6.3e-5;
// the Kalthoff-Winkler plate 1.3e-6, 3.5e-5 without and 1.3e-4, 4.3e-4 with micro-rotations; its
// 3-D specimen 2.2e-5, 2.6e-5; the shear-band specimen 3e-9, 6e-7.
constexpr double step_patch_radius = 4.0;
constexpr double step_check_radius = 3.0;
// The patch holds its highest mode when the rise from 3 to 4 horizons is at most this; a mode
// spread over the bulk (a periodic lattice: a plane wave) rises by far more, and takes the whole
// model's estimate.
constexpr double step_confinement = 1e-3;

struct PatchStep {
  double lambda = 0.0;
  int iterations = 0;
  std::size_t points_inside = 0;
  std::string refusal;  // why the patch cannot give the step (empty: it can)
};

// With `kept`, the outer patch and its estimate are left there (StepPatch).
// A block's estimates on the patches of 4 and 3 horizons around a centre, which check that the
// 4-horizon patch holds the block's highest mode (the step's, patch_step; a mixed mode's blocks',
// name_mixed_mode_on_block_patches). Not estimated (too_large) where that patch would hold more
// than a tenth of the model.
struct PatchPair {
  ModelPatch outer;
  bool too_large = false;
  OperatorEstimate on_outer, on_inner;
  // The rise from 3 to 4 horizons (Lanczos may leave it a hair below 0).
  double rise() const { return std::max(0.0, on_outer.lambda - on_inner.lambda); }
  bool holds_its_mode() const { return rise() <= step_confinement * on_outer.lambda; }
  // The 4-horizon estimate raised by the rise, which covers its shortfall.
  double lambda() const { return on_outer.lambda + rise(); }
  int iterations() const { return on_outer.iterations + on_inner.iterations; }
};
PatchPair estimate_on_patches(Model& model, const PatchCentre& centre, Block block) {
  PatchPair pair{cut_patch(model, centre.position, step_patch_radius * model.horizon), false, {}, {}};
  pair.too_large = static_cast<double>(pair.outer.model.points.owned) >
                   patch_largest_share * static_cast<double>(model_points(model));
  if (pair.too_large) return pair;
  ModelPatch inner = cut_patch(model, centre.position, step_check_radius * model.horizon);
  // Two models of their own: their estimates run side by side (the same bits as one after the other).
  side_by_side([&] { pair.on_outer = patch_estimate(pair.outer, block); },
               [&] { pair.on_inner = patch_estimate(inner, block); });
  return pair;
}

// With `kept`, the outer patch and its estimate are left there (StepPatch).
PatchStep patch_step(Model& model, const PatchCentre& centre, const char* which,
                     std::optional<StepPatch>* kept = nullptr) {
  PatchStep out;
  PatchPair pair = estimate_on_patches(model, centre, Block::coupled);
  if (pair.too_large) {
    out.refusal = "the patch around the " + std::string(which) + " would hold " +
                  std::to_string(pair.outer.model.points.owned) + " of the model's " +
                  number(static_cast<double>(model_points(model))) + " points, more than a tenth";
    return out;
  }
  out.lambda = pair.lambda();
  out.iterations = pair.iterations();
  out.points_inside = pair.outer.points_inside;
  if (!pair.holds_its_mode())
    out.refusal = "the highest mode around the " + std::string(which) + " reaches beyond its patch (omega_max^2 " +
                  number(pair.rise() / pair.on_outer.lambda) + " higher on 4 horizons than on 3, above " +
                  number(step_confinement) + ")";
  if (kept)
    kept->emplace(
        StepPatch{std::move(pair.outer), centre.position, step_patch_radius * model.horizon, pair.on_outer.lambda});
  return out;
}

// A highest mode that mixes both blocks (name_mode_on_patch: PatchNaming::mixed) named from each
// block's omega^2 on the patches around that block's own stiffest point (docs/theory.md section
// 9), the credit estimates on the limiting block's 4-horizon patch. A block's omega^2 is at most
// the coupled one (a principal submatrix): the raise by the rise, which may pass it by up to
// step_confinement, is capped there. False (nothing named) where a block's patches refuse. The
// parts' stiffest points cost a pass over the point blocks, found only here: most modes are named
// on the first patch.
bool name_mixed_mode_on_block_patches(Model& model, CriticalTimeStep& critical) {
  const StiffestParts parts = stiffest_parts(model.points, model.bonds, model.constants);
  const PatchCentre translational = patch_centre(model, parts.translational);
  const PatchCentre rotational = patch_centre(model, parts.rotational);
  if (!(translational.block_eigenvalue > 0.0 && rotational.block_eigenvalue > 0.0)) return false;
  PatchPair t = estimate_on_patches(model, translational, Block::translational);
  if (t.too_large || !t.holds_its_mode()) return false;
  PatchPair r = estimate_on_patches(model, rotational, Block::rotational);
  if (r.too_large || !r.holds_its_mode()) return false;
  const double coupled = omega_squared_of(critical.step);
  const std::array<double, 2> known{std::min(t.lambda(), coupled), std::min(r.lambda(), coupled)};
  CriticalTimeStep named = critical;
  name_mode_from_blocks(named, t.outer, r.outer, known, t.iterations() + r.iterations());
  named.naming_patch_points = 0;
  named.naming_block_patch_points = {t.outer.points_inside, r.outer.points_inside};
  critical = named;
  return true;
}

}  // namespace

CriticalTimeStep estimate_critical_step(Model& model, StepEstimate where, const StiffestPoints& own,
                                        std::optional<StepPatch>* kept) {
  if (kept) kept->reset();
  auto whole_model = [&](std::string reason) {
    CriticalTimeStep out = coupled_critical_time_step(model);
    out.whole_model_reason = std::move(reason);
    return out;
  };
  if (where == StepEstimate::whole_model) return whole_model("numerics.step_estimate: whole_model");
  if (model.effects.pore_fluid) return whole_model("the pore fluid's operator is not cut into patches");
  if (!can_cut_patches(model)) return whole_model("the model holds history (broken bonds or plastic strain)");
  const PatchCentre any = patch_centre(model, own.any), body = patch_centre(model, own.body);
  if (!(any.block_eigenvalue > 0.0)) return whole_model("no point to centre a patch on");
  CriticalTimeStep out;
  PatchStep best = patch_step(model, any, "stiffest point", kept);
  if (best.refusal.empty() && body.block_eigenvalue > 0.0 && body.position != any.position) {
    const PatchStep second = patch_step(model, body, "stiffest body point");
    out.iterations = second.iterations;
    if (!second.refusal.empty())
      best.refusal = second.refusal;
    else if (second.lambda > best.lambda)
      best.lambda = second.lambda, best.points_inside = second.points_inside;
  }
  if (!best.refusal.empty()) return whole_model(best.refusal);
  out.step = step_of(best.lambda);
  out.iterations += best.iterations;
  out.step_patch_points = best.points_inside;
  return out;
}

bool names_mode_on_patch(const Model& model) { return model.points.rotation_components > 0 && can_cut_patches(model); }

bool patches_need_stiffest_points(const Model& model, StepEstimate where) {
  return (where == StepEstimate::patch || model.points.rotation_components > 0) && can_cut_patches(model);
}

void name_limiting_mode(Model& model, CriticalTimeStep& critical, const PatchCentre& centre,
                        std::optional<StepPatch>* kept) {
  if (names_mode_on_patch(model) && centre.block_eigenvalue > 0.0)
    for (const double radius : patch_radii) {
      const PatchNaming tried = name_mode_on_patch(model, critical, centre, radius * model.horizon, kept);
      if (tried == PatchNaming::named) return;
      if (tried == PatchNaming::mixed && name_mixed_mode_on_block_patches(model, critical)) return;
      if (tried != PatchNaming::too_small) break;
    }
  name_limiting_mode_on_whole_model(model, critical);
}

void name_limiting_mode(Model& model, CriticalTimeStep& critical) {
  PatchCentre centre;
  if (names_mode_on_patch(model))
    centre = patch_centre(model, stiffest_points(model.points, model.bonds, model.constants).any);
  name_limiting_mode(model, critical, centre);
}

void name_limiting_mode_on_whole_model(Model& model, CriticalTimeStep& critical, NamingConvergence convergence) {
  if (model.points.rotation_components == 0) {
    // The translational block is the coupled operator: nothing is estimated, so the model's state
    // is not lent out (with_operator's force evaluation afterwards would cost a step for nothing).
    critical.naming_iterations = 0;
    name_translational(model, critical, omega_squared_of(critical.step));
    return;
  }
  const Convergence& tolerance = convergence == NamingConvergence::converged ? step_convergence : naming_convergence;
  with_operator(model, [&](Workspace& ws) { name_mode(critical, tolerance, {&model, &ws}, {&model, &ws}); });
}

CriticalTimeStep coupled_critical_time_step(Model& model) {
  CriticalTimeStep out;
  with_operator(model, [&](Workspace& ws) { estimate_coupled(model, out, ws); });
  return out;
}

CriticalTimeStep critical_time_step(Model& model, StepEstimate where) {
  const StiffestPoints own = patches_need_stiffest_points(model, where)
                                 ? stiffest_points(model.points, model.bonds, model.constants)
                                 : StiffestPoints{};
  std::optional<StepPatch> kept;
  CriticalTimeStep out = estimate_critical_step(model, where, own, &kept);
  name_limiting_mode(model, out, patch_centre(model, own.any), &kept);
  return out;
}

double choose_time_step(const Scene& scene, const CriticalTimeStep& critical, double damage_step) {
  const bool damage_bound = damage_step > 0.0 && damage_step < critical.step;
  if (!scene.time.step) return scene.time.safety * (damage_bound ? damage_step : critical.step);
  const double dt = *scene.time.step;
  if (!(dt > 0.0)) throw InputError(scene.path + ": time.step: must be positive or 'auto', got " + number(dt) + " s");
  if (damage_bound && dt > damage_step && dt <= critical.step)
    throw InputError(scene.path + ": time.step: " + number(dt) + " s is above " + number(damage_step) +
                     " s, the largest step a run with the damage effect may use (" +
                     number(damage_step / critical.step) + " of the critical step " + number(critical.step) +
                     " s: the lopsided families that broken bonds leave raise the highest frequency by up to " +
                     number(scene.numerics.damaged_frequency_ratio) +
                     "x the largest point stiffness; solver/point_stability.hpp) "
                     "(expected time.step <= " +
                     number(damage_step) + " s, or time.step: auto)");
  if (dt > critical.step) {
    const double mode_step = critical.limiting_mode == "rotational" ? critical.rotational : critical.translational;
    throw InputError(scene.path + ": time.step: " + number(dt) + " s is above the critical step " +
                     number(critical.step) + " s of the explicit scheme; the limiting mode is " +
                     critical.limiting_mode + " (its own critical step " + number(mode_step) + " s), driven by " +
                     critical.driver + " (expected time.step <= " + number(critical.step) + " s, or time.step: auto)");
  }
  return dt;
}

}  // namespace mppm::solver
