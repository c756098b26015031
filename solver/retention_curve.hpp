// The retention model of unsaturated pore fluid (docs/theory.md section 12, "Unsaturated
// (retention)"): the van Genuchten saturation of the suction, Mualem's relative permeability, the
// fluid content zeta(p, eps_v) = S_r(p) (n0 + b eps_v + p/M) and its inverse, p from zeta at a given
// volumetric strain. The air is at zero pressure, p is compression positive, the suction s = max(0, -p).
// The solver's use of it: solver/unsaturated_coupling.hpp and solver/pore_fluid.hpp.
#pragma once
#include <optional>

#include "common/scene.hpp"

namespace mppm::solver {

struct RetentionCurve {
  double air_entry_pressure = 0.0;   // p_e [Pa], > 0
  double n = 2.0;                    // van Genuchten n, > 1 (m = 1 - 1/n)
  double residual_saturation = 0.0;  // S_res, in [0, 1)
  double m() const { return 1.0 - 1.0 / n; }
};

// S_e = [1 + (s/p_e)^n]^(-m): 1 at p >= 0, decreasing to 0 as the suction grows.
double effective_saturation(const RetentionCurve& c, double p);
// S_r = S_res + (1 - S_res) S_e.
double saturation(const RetentionCurve& c, double p);
// dS_r/dp (analytic; 0 at p >= 0, >= 0 everywhere: the saturation grows with the pressure).
double saturation_derivative(const RetentionCurve& c, double p);
// Mualem: k_r = sqrt(S_e) [1 - (1 - S_e^(1/m))^m]^2, 1 at S_e = 1 and 0 at S_e = 0.
double relative_permeability(const RetentionCurve& c, double p);

// The curve of a scene's pore fluid, if it has one (material.pore_fluid.retention).
std::optional<RetentionCurve> retention_curve(const PoreFluidParameters& fluid);
// The saturation of the start: S_r(initial_pressure) with a retention curve and a constant start,
// else 1 (saturated, or a hydrostatic start: docs/theory.md section 12).
double start_saturation(const PoreFluidParameters& fluid);

// The constants of the fluid content: zeta = S_r(p) (n0 + b eps_v + p/M).
struct FluidStorage {
  double porosity = 0.0;          // n0
  double biot_coefficient = 1.0;  // b
  double biot_modulus = 0.0;      // M [Pa]
};

// The fluid content zeta(p, eps_v) and dzeta/dp = S_r' (n0 + b eps_v + p/M) + S_r / M, which is > 0
// wherever the liquid term n0 + b eps_v + p/M is >= 0 (the only range the inverse searches).
double fluid_content(const RetentionCurve& c, const FluidStorage& f, double p, double eps_v);
// zeta - n0, computed without cancelling n0 (the variable the solver stores and the inverse takes).
double fluid_content_change(const RetentionCurve& c, const FluidStorage& f, double p, double eps_v);
double fluid_content_derivative(const RetentionCurve& c, const FluidStorage& f, double p, double eps_v);

// The saturated branch's p = M ((zeta - n0) - b eps_v), inline so that a caller in the force kernel
// rounds it as the saturated solver's own expression does.
inline double saturated_pressure(const FluidStorage& f, double content_change, double eps_v) {
  return f.biot_modulus * (content_change - f.biot_coefficient * eps_v);
}

enum class RetentionInverseStatus { converged, no_bracket, iteration_limit };

struct RetentionInverse {
  double pressure = 0.0;
  RetentionInverseStatus status = RetentionInverseStatus::converged;
  int iterations = 0;  // safeguarded Newton iterations (0 on the saturated branch)
  bool ok() const { return status == RetentionInverseStatus::converged; }
};

struct RetentionInverseOptions {
  // The largest suction searched [Pa]; the search also stops where the liquid term
  // n0 + b eps_v + p/M reaches zero (beyond, the liquid volume would be negative).
  double max_suction = 1e300;
  int max_iterations = 200;
};

// p from the fluid content at the volumetric strain eps_v, the content given as its change
// zeta - n0 (as the solver stores it). On the saturated branch (zeta - n0 - b eps_v >= 0, i.e. p >= 0,
// S_r = 1) p = M ((zeta - n0) - b eps_v) exactly as the saturated solver computes it. Else a safeguarded
// Newton iteration in the bracket [p_lo, 0] where zeta - target changes sign (bisection when a Newton
// step leaves the bracket or does not halve the residual), to a relative tolerance near round-off.
// Returns a failure status, never throws: no_bracket when the target is below the content at the
// largest admissible suction, iteration_limit when max_iterations is exceeded.
RetentionInverse pressure_from_fluid_content(const RetentionCurve& c, const FluidStorage& f, double content_change,
                                             double eps_v, const RetentionInverseOptions& options = {});

}  // namespace mppm::solver
