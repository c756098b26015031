#include "tests/verification/problems/layer_shear.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "tests/verification/problems/periodic_lattice.hpp"

namespace mppm::verification {

namespace {

// Period of at least 8 columns and above 2 horizons (the family search needs it); layers at
// least a horizon deep.
int layer_columns(double horizon_factor) { return std::max(8, static_cast<int>(std::floor(2 * horizon_factor)) + 2); }
int layer_rows(double horizon_factor) { return static_cast<int>(std::ceil(horizon_factor - 1e-9)); }

constexpr double kShift = 1e-6;            // U [m]; linear model, any value works
constexpr double kCgTolerance = 1e-10;     // relative, in the M^-1 norm of the residual
constexpr int kCgMaxIterationsPerDof = 4;  // CG converges in at most n steps in exact arithmetic

}  // namespace

double bending_for(double lam_h, double h, double mu, double mu_c) {
  const double lam = lam_h / h;
  return 4 * mu * mu_c / (lam * lam * (mu + mu_c));
}

LayerShearResult shear_layer(const Scene& s, int body_rows, double height, StaticSolver solver) {
  const double dx = s.geometry.spacing;
  const int columns = layer_columns(s.geometry.horizon_factor);
  const int layers = layer_rows(s.geometry.horizon_factor);
  const bool polar = s.effects.micropolar;
  const int rows = body_rows + 2 * layers;
  solver::Model m = make_model(make_lattice(2, {columns, rows, 1}, dx, s.thickness), s, {columns * dx, 0.0, 0.0});
  const std::size_t n = m.points.owned;
  LayerShearResult r;
  r.points = n;
  r.bonds = m.bonds.bond_count();
  const auto start = std::chrono::steady_clock::now();
  auto row_of = [&](std::size_t i) { return static_cast<int>(std::floor(m.points.position[i * 2 + 1] / dx)); };
  const int per_point = polar ? 3 : 2;  // ux, uy(, w)
  std::vector<int> free_dofs;
  for (std::size_t i = 0; i < n; ++i) {
    const int row = row_of(i);
    if (row >= layers && row < rows - layers)
      for (int d = 0; d < per_point; ++d) free_dofs.push_back(static_cast<int>(i) * per_point + d);
  }
  const int nf = static_cast<int>(free_dofs.size());
  auto set_dof = [&](int dof, double v) {
    const auto i = static_cast<std::size_t>(dof / per_point);
    if (dof % per_point < 2)
      m.points.displacement[i * 2 + dof % per_point] = v;
    else
      m.points.rotation[i] = v;
  };
  auto generalized_force = [&](int dof) {  // f V (force or moment on the point)
    const auto i = static_cast<std::size_t>(dof / per_point);
    const double f = dof % per_point < 2 ? m.points.force[i * 2 + dof % per_point] : m.points.moment[i];
    return f * m.points.volume[i];
  };
  auto clear = [&] {
    std::fill(m.points.displacement.begin(), m.points.displacement.end(), 0.0);
    std::fill(m.points.rotation.begin(), m.points.rotation.end(), 0.0);
  };
  auto prescribe_layers = [&] {  // bottom held, top moved by U along x, rotations 0 on both
    for (std::size_t i = 0; i < n; ++i)
      if (row_of(i) >= rows - layers) m.points.displacement[i * 2] = kShift;
  };
  auto evaluate = [&] {
    m.compute_internal_forces();
    ++r.force_evaluations;
  };
  // Right-hand side: the force on the free dofs from the prescribed layers alone.
  clear();
  prescribe_layers();
  evaluate();
  Eigen::VectorXd rhs(nf);
  for (int a = 0; a < nf; ++a) rhs(a) = generalized_force(free_dofs[a]);

  Eigen::VectorXd x = Eigen::VectorXd::Zero(nf);
  if (solver == StaticSolver::dense_cholesky) {
    // Stiffness of the free dofs, column by column: K e_b = -f(e_b) V.
    Eigen::MatrixXd K(nf, nf);
    for (int b = 0; b < nf; ++b) {
      clear();
      set_dof(free_dofs[b], 1.0);
      evaluate();
      for (int a = 0; a < nf; ++a) K(a, b) = -generalized_force(free_dofs[a]);
    }
    r.symmetry_defect = (K - K.transpose()).norm() / K.norm();
    const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (K + K.transpose()));
    r.positive_definite = llt.info() == Eigen::Success;
    if (r.positive_definite) x = llt.solve(rhs);
  } else {
    // K v = -f(v) V with the layers at rest; preconditioner M = diag(rho V, I V).
    auto apply = [&](const Eigen::VectorXd& v) {
      clear();
      for (int a = 0; a < nf; ++a) set_dof(free_dofs[a], v(a));
      evaluate();
      Eigen::VectorXd out(nf);
      for (int a = 0; a < nf; ++a) out(a) = -generalized_force(free_dofs[a]);
      return out;
    };
    Eigen::VectorXd inverse_mass(nf);
    for (int a = 0; a < nf; ++a) {
      const auto i = static_cast<std::size_t>(free_dofs[a] / per_point);
      const double inertia = free_dofs[a] % per_point < 2 ? m.constants.density : m.constants.micro_inertia;
      inverse_mass(a) = 1.0 / (inertia * m.points.volume[i]);
    }
    Eigen::VectorXd residual = rhs;
    Eigen::VectorXd z = inverse_mass.cwiseProduct(residual);
    Eigen::VectorXd direction = z;
    double rz = residual.dot(z);
    const double target = kCgTolerance * kCgTolerance * rz;
    r.converged = false;
    for (int it = 0; it < kCgMaxIterationsPerDof * nf; ++it) {
      const Eigen::VectorXd Kd = apply(direction);
      const double alpha = rz / direction.dot(Kd);
      x += alpha * direction;
      residual -= alpha * Kd;
      z = inverse_mass.cwiseProduct(residual);
      const double rz_next = residual.dot(z);
      r.iterations = it + 1;
      if (rz_next <= target) {
        r.converged = true;
        break;
      }
      direction = z + (rz_next / rz) * direction;
      rz = rz_next;
    }
  }
  // Final state: layers prescribed, free dofs at equilibrium; reaction of the top layer.
  clear();
  prescribe_layers();
  for (int a = 0; a < nf; ++a) set_dof(free_dofs[a], x(a));
  evaluate();
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double reaction = 0.0, worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (row_of(i) >= rows - layers) reaction -= m.points.force[i * 2] * m.points.volume[i];
  for (int a = 0; a < nf; ++a) {
    worst = std::max(worst, std::abs(generalized_force(free_dofs[a])));
    scale = std::max(scale, std::abs(rhs(a)));
  }
  r.residual = worst / scale;
  const double tau = reaction / (columns * dx * s.thickness);
  const solver::CosseratConstants& c = m.constants;
  r.stiffness = tau / (kShift / height);
  r.classical = c.mu;
  if (polar) {
    const double lam = std::sqrt(4 * c.mu * c.mu_c / (c.bending_modulus * (c.mu + c.mu_c)));
    r.analytic = c.mu / (1 - 2 * c.mu_c * std::tanh(lam * height / 2) / ((c.mu + c.mu_c) * lam * height));
  } else {
    r.analytic = c.mu;
  }
  return r;
}

}  // namespace mppm::verification
