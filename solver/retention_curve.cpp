#include "solver/retention_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mppm::solver {

namespace {

// (s/p_e)^n at the pressure p (0 at p >= 0).
double scaled_suction_power(const RetentionCurve& c, double p) {
  if (p >= 0.0) return 0.0;
  return std::pow(-p / c.air_entry_pressure, c.n);
}

// 1 - S_e = 1 - (1 + x^n)^(-m), without the cancellation near S_e = 1.
double effective_desaturation(const RetentionCurve& c, double p) {
  if (p >= 0.0) return 0.0;
  return -std::expm1(-c.m() * std::log1p(scaled_suction_power(c, p)));
}

}  // namespace

double effective_saturation(const RetentionCurve& c, double p) {
  if (p >= 0.0) return 1.0;
  return std::pow(1.0 + scaled_suction_power(c, p), -c.m());
}

double saturation(const RetentionCurve& c, double p) {
  if (p >= 0.0) return 1.0;
  return c.residual_saturation + (1.0 - c.residual_saturation) * effective_saturation(c, p);
}

double saturation_derivative(const RetentionCurve& c, double p) {
  if (p >= 0.0) return 0.0;
  // dS_e/dp = m n x^(n-1) (1 + x^n)^(-m-1) / p_e with x = s/p_e (ds/dp = -1).
  const double x = -p / c.air_entry_pressure;
  const double m = c.m();
  const double dse =
      m * c.n * std::pow(x, c.n - 1.0) * std::pow(1.0 + std::pow(x, c.n), -m - 1.0) / c.air_entry_pressure;
  return (1.0 - c.residual_saturation) * dse;
}

double relative_permeability(const RetentionCurve& c, double p) {
  if (p >= 0.0) return 1.0;
  // S_e^(1/m) = 1 / (1 + x^n), so 1 - S_e^(1/m) = x^n / (1 + x^n) without the cancellation near S_e = 1.
  const double xn = scaled_suction_power(c, p);
  const double m = c.m();
  const double se = std::pow(1.0 + xn, -m);
  const double bracket = 1.0 - std::pow(xn / (1.0 + xn), m);
  return std::sqrt(se) * bracket * bracket;
}

std::optional<RetentionCurve> retention_curve(const PoreFluidParameters& fluid) {
  if (!fluid.retention) return std::nullopt;
  const RetentionParameters& r = *fluid.retention;
  return RetentionCurve{r.air_entry_pressure, r.n, r.residual_saturation};
}

double start_saturation(const PoreFluidParameters& fluid) {
  const auto curve = retention_curve(fluid);
  return curve && !fluid.free_surface ? saturation(*curve, fluid.initial_pressure) : 1.0;
}

double fluid_content(const RetentionCurve& c, const FluidStorage& f, double p, double eps_v) {
  return saturation(c, p) * (f.porosity + f.biot_coefficient * eps_v + p / f.biot_modulus);
}

double fluid_content_change(const RetentionCurve& c, const FluidStorage& f, double p, double eps_v) {
  // zeta - n0 = (b eps_v + p/M) - (1 - S_r) (n0 + b eps_v + p/M): no n0 - n0 cancellation, so that
  // the content keeps its digits near saturation as the saturated solver's stored change does.
  const double liquid = f.porosity + f.biot_coefficient * eps_v + p / f.biot_modulus;
  return (f.biot_coefficient * eps_v + p / f.biot_modulus) -
         (1.0 - c.residual_saturation) * effective_desaturation(c, p) * liquid;
}

double fluid_content_derivative(const RetentionCurve& c, const FluidStorage& f, double p, double eps_v) {
  const double liquid = f.porosity + f.biot_coefficient * eps_v + p / f.biot_modulus;
  return saturation_derivative(c, p) * liquid + saturation(c, p) / f.biot_modulus;
}

namespace {

// The suction at which van Genuchten's S_r equals `sr` (the liquid term's p/M neglected): the
// Newton iteration's first guess; 0 when sr >= 1, infinite when sr <= S_res.
double suction_at_saturation(const RetentionCurve& c, double sr) {
  if (sr >= 1.0) return 0.0;
  const double se = (sr - c.residual_saturation) / (1.0 - c.residual_saturation);
  if (se <= 0.0) return std::numeric_limits<double>::infinity();
  return c.air_entry_pressure * std::pow(std::pow(se, -1.0 / c.m()) - 1.0, 1.0 / c.n);
}

}  // namespace

RetentionInverse pressure_from_fluid_content(const RetentionCurve& c, const FluidStorage& f, double content_change,
                                             double eps_v, const RetentionInverseOptions& options) {
  RetentionInverse out;
  const double saturated = saturated_pressure(f, content_change, eps_v);
  if (saturated >= 0.0) {  // S_r = 1: today's formula, bit for bit
    out.pressure = saturated;
    return out;
  }
  // r(p) = zeta(p) - target increases with p on the admissible range (docs/theory.md section 12).
  const auto residual = [&](double p) { return fluid_content_change(c, f, p, eps_v) - content_change; };
  const double liquid = f.porosity + f.biot_coefficient * eps_v;
  const double floor_suction = std::min(options.max_suction, f.biot_modulus * liquid);
  if (!(floor_suction > 0.0)) {
    out.status = RetentionInverseStatus::no_bracket;
    return out;
  }
  double p_hi = 0.0;
  if (residual(p_hi) <= 0.0) return out;  // a target at zeta(0) to round-off: p = 0
  // The bracket's lower end: decades of suction from p_e until r < 0, at most the floor suction.
  double p_lo = -std::min(c.air_entry_pressure, floor_suction);
  double r_lo = residual(p_lo);
  while (r_lo > 0.0) {
    if (-p_lo >= floor_suction) {
      out.status = RetentionInverseStatus::no_bracket;
      return out;
    }
    p_hi = p_lo;
    p_lo = -std::min(-10.0 * p_lo, floor_suction);
    r_lo = residual(p_lo);
  }
  if (r_lo == 0.0) {
    out.pressure = p_lo;
    return out;
  }
  // First guess: van Genuchten inverted at S_r = zeta / (n0 + b eps_v), clamped into the bracket.
  double p = -suction_at_saturation(c, 1.0 + (content_change - f.biot_coefficient * eps_v) / liquid);
  if (!(p > p_lo && p < p_hi)) p = 0.5 * (p_lo + p_hi);
  constexpr double kTolerance = 4.0 * std::numeric_limits<double>::epsilon();
  double r_previous = std::numeric_limits<double>::infinity();
  for (int it = 1; it <= options.max_iterations; ++it) {
    out.iterations = it;
    const double r = residual(p);
    if (r == 0.0) {
      out.pressure = p;
      return out;
    }
    (r > 0.0 ? p_hi : p_lo) = p;
    const double newton = p - r / fluid_content_derivative(c, f, p, eps_v);
    const bool inside = newton >= p_lo && newton <= p_hi;
    if (inside && std::abs(newton - p) <= kTolerance * std::abs(newton)) {  // a step at round-off
      out.pressure = newton;
      return out;
    }
    // Newton's step when it stays inside the bracket and the last step at least halved the residual;
    // bisection otherwise (the bracket then halves, so the iteration cannot stall or leave it).
    const bool take_newton = inside && std::abs(r) <= 0.5 * std::abs(r_previous);
    r_previous = r;
    p = take_newton ? newton : 0.5 * (p_lo + p_hi);
    if (p_hi - p_lo <= kTolerance * std::abs(p_lo)) {  // the bracket itself at round-off
      out.pressure = p;
      return out;
    }
  }
  out.pressure = p;
  out.status = RetentionInverseStatus::iteration_limit;
  return out;
}

}  // namespace mppm::solver
