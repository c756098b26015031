#include "tests/verification/problems/richards_column.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace mppm::verification {

namespace {

using solver::fluid_content_change;
using solver::fluid_content_derivative;
using solver::relative_permeability;
using solver::saturation;

// dk_r/dp by a central difference: the Jacobian only steers Newton (its converged answer is that of
// the residual, which is exact), so this needs no more than a few digits.
double relative_permeability_slope(const RichardsColumn& c, double p) {
  const double h = 1e-6 * std::max(std::abs(p), c.curve.air_entry_pressure);
  return (relative_permeability(c.curve, p + h) - relative_permeability(c.curve, p - h)) / (2.0 * h);
}

struct Face {  // the upward flux through a face and its derivatives by the pressures below (a) and above (b)
  double flux = 0.0, d_below = 0.0, d_above = 0.0;
};

Face face_flux(const RichardsColumn& c, double pa, double pb, double distance) {
  const double kra = relative_permeability(c.curve, pa), krb = relative_permeability(c.curve, pb);
  const double conductivity = c.mobility * 0.5 * (kra + krb);
  const double drive = (pb - pa) / distance + c.fluid_density * c.gravity;
  Face f;
  f.flux = -conductivity * drive;
  f.d_below = -c.mobility * 0.5 * relative_permeability_slope(c, pa) * drive + conductivity / distance;
  f.d_above = -c.mobility * 0.5 * relative_permeability_slope(c, pb) * drive - conductivity / distance;
  return f;
}

class Stepper {
 public:
  explicit Stepper(const RichardsColumn& c) : c_(c), n_(static_cast<std::size_t>(c.cells)), dz_(c.length / c.cells) {
    lower_.resize(n_);
    diag_.resize(n_);
    upper_.resize(n_);
    residual_.resize(n_);
  }

  // R_i = dz (zeta_i - zeta_i^old) / dt + F_{i+1/2} - F_{i-1/2} with its tridiagonal Jacobian;
  // returns the inflow through the top over the step per unit time (-F_top).
  double assemble(const std::vector<double>& p, const std::vector<double>& old_content, double dt) {
    const double scale = dz_ / dt;
    for (std::size_t i = 0; i < n_; ++i) {
      residual_[i] = scale * (fluid_content_change(c_.curve, c_.storage, p[i], 0.0) - old_content[i]);
      diag_[i] = scale * fluid_content_derivative(c_.curve, c_.storage, p[i], 0.0);
      lower_[i] = upper_[i] = 0.0;
    }
    for (std::size_t i = 0; i + 1 < n_; ++i) {
      const Face f = face_flux(c_, p[i], p[i + 1], dz_);
      residual_[i] += f.flux;
      diag_[i] += f.d_below;
      upper_[i] += f.d_above;
      residual_[i + 1] -= f.flux;
      lower_[i + 1] -= f.d_below;
      diag_[i + 1] -= f.d_above;
    }
    const std::size_t top = n_ - 1;
    if (!c_.top_pressure_given) {
      residual_[top] -= c_.top_flux;
      return c_.top_flux;
    }
    const Face f = face_flux(c_, p[top], c_.top_pressure, 0.5 * dz_);
    residual_[top] += f.flux;
    diag_[top] += f.d_below;
    return -f.flux;
  }

  double residual_norm() const {
    double r = 0.0;
    for (double v : residual_) r = std::max(r, std::abs(v));
    return r;
  }

  // Solves J dp = -R (Thomas' algorithm; J is diagonally dominant: storage plus conductances).
  std::vector<double> newton_step() const {
    std::vector<double> c(n_), d(n_);
    c[0] = upper_[0] / diag_[0];
    d[0] = -residual_[0] / diag_[0];
    for (std::size_t i = 1; i < n_; ++i) {
      const double m = diag_[i] - lower_[i] * c[i - 1];
      c[i] = upper_[i] / m;
      d[i] = (-residual_[i] - lower_[i] * d[i - 1]) / m;
    }
    for (std::size_t i = n_ - 1; i-- > 0;) d[i] -= c[i] * d[i + 1];
    return d;
  }

  // One backward Euler step of dt from p (in place); the inflow over it into `inflow`. False if
  // Newton did not converge (p is then left as it was).
  bool step(std::vector<double>& p, double dt, double& inflow, int& iterations) {
    std::vector<double> old_content(n_);
    for (std::size_t i = 0; i < n_; ++i) old_content[i] = fluid_content_change(c_.curve, c_.storage, p[i], 0.0);
    std::vector<double> q = p, trial(n_);
    double rate = assemble(q, old_content, dt);
    for (int it = 0; it < 60; ++it) {
      ++iterations;
      const std::vector<double> dp = newton_step();
      double p_scale = c_.curve.air_entry_pressure, largest = 0.0;
      for (std::size_t i = 0; i < n_; ++i) {
        p_scale = std::max(p_scale, std::abs(q[i]));
        largest = std::max(largest, std::abs(dp[i]));
      }
      // Damped: the full step unless it raises the residual (k_r is steep near saturation).
      const double before = residual_norm();
      double lambda = 1.0;
      for (int halving = 0; halving < 12; ++halving, lambda *= 0.5) {
        for (std::size_t i = 0; i < n_; ++i) trial[i] = q[i] + lambda * dp[i];
        rate = assemble(trial, old_content, dt);
        if (residual_norm() <= before || lambda * largest <= 1e-12 * p_scale) break;
      }
      q = trial;
      // Converged when the update is at 1e-13 of the pressures: Newton's quadratic convergence
      // then leaves a residual (the step's fluid imbalance) near round-off.
      if (lambda * largest <= 1e-13 * p_scale) {
        p = q;
        inflow = rate * dt;
        return true;
      }
    }
    return false;
  }

 private:
  const RichardsColumn& c_;
  std::size_t n_;
  double dz_;
  std::vector<double> lower_, diag_, upper_, residual_;
};

// A step of dt, split in halves (recursively, at most `depth` times) while Newton fails.
bool advance(Stepper& s, std::vector<double>& p, double dt, int depth, RichardsResult& r) {
  double inflow = 0.0;
  if (s.step(p, dt, inflow, r.newton_iterations)) {
    r.inflow += inflow;
    return true;
  }
  if (depth == 0) return false;
  ++r.step_splits;
  return advance(s, p, 0.5 * dt, depth - 1, r) && advance(s, p, 0.5 * dt, depth - 1, r);
}

}  // namespace

RichardsResult solve_richards_column(const RichardsColumn& c) {
  const auto n = static_cast<std::size_t>(c.cells);
  const double dz = c.length / c.cells;
  RichardsResult r;
  std::vector<double> p(n, c.initial_pressure);
  Stepper stepper(c);
  const double dt = c.end_time / c.steps;
  for (int k = 0; k < c.steps && r.converged; ++k) r.converged = advance(stepper, p, dt, 20, r);
  const double initial_content = fluid_content_change(c.curve, c.storage, c.initial_pressure, 0.0);
  r.initial_saturation = saturation(c.curve, c.initial_pressure);
  for (std::size_t i = 0; i < n; ++i) {
    r.z.push_back((static_cast<double>(i) + 0.5) * dz);
    r.pressure.push_back(p[i]);
    r.saturation.push_back(saturation(c.curve, p[i]));
    r.stored += dz * (fluid_content_change(c.curve, c.storage, p[i], 0.0) - initial_content);
  }
  r.mass_balance_error = std::abs(r.stored - r.inflow) / std::max(std::abs(r.inflow), 1e-300);
  r.front_depth = wetting_front_depth(r, c.length);
  return r;
}

double wetting_front_depth(const RichardsResult& r, double length) {
  const std::size_t n = r.saturation.size();
  if (n < 2) return 0.0;
  const double mid = 0.5 * (r.initial_saturation + r.saturation[n - 1]);
  for (std::size_t i = n - 1; i-- > 0;) {
    const double above = r.saturation[i + 1], below = r.saturation[i];
    if ((above - mid) * (below - mid) <= 0.0 && above != below) {
      const double z = r.z[i] + (r.z[i + 1] - r.z[i]) * (mid - below) / (above - below);
      return length - z;
    }
  }
  return 0.0;
}

}  // namespace mppm::verification
