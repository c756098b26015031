// Verification of the pore fluid (docs/theory.md section 12) against Mandel's problem: a specimen of
// width 2a in plane strain between rigid, frictionless, impermeable plates carrying a total force
// 2F from t = 0, its sides x = +-a drained and traction-free. The undrained load gives a uniform
// pressure p0; as the sides drain the rigid plates shift the load to the core and the centre's
// pressure rises above p0 (the Mandel-Cryer effect) before it decays.
// - the series (Abousleiman et al. 1996, Cheng & Detournay's form) against its own limits: p0 at
//   t -> 0, 0 at the drained faces and late, the plates' approach undrained and drained, and the known peak 1.13 p0
//   near T = c t / a^2 = 0.08 for nu = 0, nu_u = 0.44;
// - the model (nu = 0, nu_u = 0.44, a square specimen of half-width a = 40.5 dx, delta = 3.05 dx,
//   rigid plates on its top and bottom rows): the centre's pressure peak within 0.02 p0 of the
//   series' and its time within 0.01 in T (a quarter of the half-width of the band where the series
//   is within 0.02 p0 of its peak), the centre's pressure within 0.02 p0 of the series over
//   T = 0.01-0.3, the plates' approach within 2 % of the series' over those times, the peak's
//   error falling with dx / a (a = 20.5 dx against 40.5 dx), and the undrained start (no flow)
//   within 0.01 p0 of p0 at the centre.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/pore_fluid.hpp"
#include "tests/verification/solver_fluid_column.hpp"

namespace mppm::solver {
namespace {

using testing::boundary_info;
using testing::condition;
using testing::saturated_scene;

// ----------------------------------------------------------------------------- the series

constexpr double kNu = 0.0, kNuU = 0.44;

// The roots alpha_n of tan(alpha) = (1 - nu) / (nu_u - nu) alpha, one in each (n pi, n pi + pi/2)
// (n = 0 included: the slope exceeds 1 for nu_u < 1/2), by bisection.
std::vector<double> mandel_roots(double nu, double nu_u, int count) {
  const double slope = (1.0 - nu) / (nu_u - nu);
  std::vector<double> roots;
  for (int n = 0; n < count; ++n) {
    double lo = n * std::numbers::pi + 1e-9, hi = n * std::numbers::pi + 0.5 * std::numbers::pi - 1e-9;
    for (int k = 0; k < 100; ++k) {  // tan - slope alpha: negative at lo, positive at hi
      const double mid = 0.5 * (lo + hi);
      (std::tan(mid) - slope * mid < 0.0 ? lo : hi) = mid;
    }
    roots.push_back(0.5 * (lo + hi));
  }
  return roots;
}

// p(x, t) / p0 with p0 = F B (1 + nu_u) / (3 a), the undrained pressure of the total force 2F on
// the width 2a: p = 2 F B (1 + nu_u) / (3 a) sum_n sin(alpha_n) / (alpha_n - sin alpha_n cos alpha_n)
// (cos(alpha_n x / a) - cos alpha_n) exp(-alpha_n^2 T), T = c t / a^2.
double mandel_pressure(const std::vector<double>& roots, double x_over_a, double tv) {
  double p = 0.0;
  for (const double al : roots)
    p += std::sin(al) / (al - std::sin(al) * std::cos(al)) * (std::cos(al * x_over_a) - std::cos(al)) *
         std::exp(-al * al * tv);
  return 2.0 * p;
}

// The plates' approach, the strain -eps_yy in units of F / (2 mu a): (1 - nu) - 2 (1 - nu_u) sum_n sin alpha_n cos
// alpha_n / (alpha_n - sin alpha_n cos alpha_n) exp(-alpha_n^2 T) (the same source), from 1 - nu_u undrained to 1 - nu
// drained.
double mandel_settlement(const std::vector<double>& roots, double tv) {
  double sum = 0.0;
  for (const double al : roots)
    sum += std::sin(al) * std::cos(al) / (al - std::sin(al) * std::cos(al)) * std::exp(-al * al * tv);
  return (1.0 - kNu) - 2.0 * (1.0 - kNuU) * sum;
}

// The series' peak at the centre: its largest value over a grid of T refined by ternary search.
struct Peak {
  double value = 0.0, tv = 0.0;
};
Peak centre_peak(const std::vector<double>& roots) {
  Peak best;
  for (double tv = 0.001; tv < 0.5; tv += 0.001)
    if (const double p = mandel_pressure(roots, 0.0, tv); p > best.value) best = {p, tv};
  double lo = best.tv - 0.001, hi = best.tv + 0.001;
  for (int k = 0; k < 60; ++k) {
    const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    if (mandel_pressure(roots, 0.0, m1) < mandel_pressure(roots, 0.0, m2))
      lo = m1;
    else
      hi = m2;
  }
  const double tv = 0.5 * (lo + hi);
  return {mandel_pressure(roots, 0.0, tv), tv};
}

TEST(SolverPoreFluidMandel, SeriesKnowsItsLimitsAndTheMandelCryerPeak) {
  const std::vector<double> roots = mandel_roots(kNu, kNuU, 400);
  for (const double al : roots)
    EXPECT_NEAR(std::tan(al), (1.0 - kNu) / (kNuU - kNu) * al, 1e-8 * std::abs(std::tan(al)) + 1e-8);
  // Undrained at the start: p0 everywhere inside. The series converges slowly at T = 0, and the
  // centre's rise starts at once (about 0.5 p0 sqrt(T)): at T = 1e-6, 2000 roots (alpha^2 T > 39
  // beyond them) and 5.0e-4 p0 of rise, the same at x = 0, 0.5 a and 0.9 a.
  const std::vector<double> many = mandel_roots(kNu, kNuU, 2000);
  for (const double x : {0.0, 0.5, 0.9}) EXPECT_NEAR(mandel_pressure(many, x, 1e-6), 1.0, 1e-3) << "x/a " << x;
  EXPECT_NEAR(mandel_pressure(roots, 1.0, 0.05), 0.0, 1e-12);  // the drained face
  EXPECT_NEAR(mandel_pressure(roots, 0.0, 10.0), 0.0, 1e-6);   // drained at last
  // The plates' approach: undrained 1 - nu_u, drained 1 - nu (in units of F / (2 mu a)).
  EXPECT_NEAR(mandel_settlement(many, 1e-6), 1.0 - kNuU, 1e-3);
  EXPECT_NEAR(mandel_settlement(roots, 10.0), 1.0 - kNu, 1e-6);
  // The Mandel-Cryer peak: about 1.13 p0 near T = 0.08 for these Poisson ratios (measured 1.1313 p0
  // at T = 0.0775).
  const Peak peak = centre_peak(roots);
  EXPECT_NEAR(peak.value, 1.13, 0.005);
  EXPECT_NEAR(peak.tv, 0.08, 0.005);
  std::ostringstream s;
  s << peak.value << " at T = " << peak.tv;
  RecordProperty("series_peak", s.str());
}

// ----------------------------------------------------------------------------- the model

constexpr double kDx = 1e-3;
constexpr double kFactor = 3.05;  // horizon / dx
constexpr int kLayerRows = 3;     // rows of the drained layers: the lattice rows within the horizon

// The specimen: nx x ny body points centred on the origin (odd counts: a point at the centre) and
// the drained layers outside its sides x = -a (region 1) and x = +a (region 2), as deep as the
// horizon and as high as the specimen: beyond its top and bottom edges the plates, wider than
// the specimen, cover the corners (no drain there).
PointCloud specimen_cloud(int nx, int ny, double thickness) {
  const double a = 0.5 * nx * kDx, b = 0.5 * ny * kDx;
  PointCloud c;
  c.dimension = 2;
  c.spacing = kDx;
  c.thickness = thickness;
  c.horizon = kFactor * kDx;
  for (int j = 0; j < ny; ++j)
    for (int i = -kLayerRows; i < nx + kLayerRows; ++i) {
      const std::size_t n = c.size();
      c.resize(n + 1);
      c.x[n] = (i + 0.5) * kDx - a;
      c.y[n] = (j + 0.5) * kDx - b;
      c.volume[n] = kDx * kDx * thickness;
      c.region[n] = c.boundary_id[n] = i < 0 ? 1 : (i >= nx ? 2 : 0);
    }
  return c;
}

// The material: make_scene's shear modulus mu, lambda from the drained Poisson ratio nu, and b = 1
// with the Biot modulus that makes the undrained one nu_u. The model's fluid at a fixed content adds
// b^2 M to lambda (docs/theory.md section 12: p = M (zeta - n0 - b eps_v), sigma = sigma' - b p 1)
// and in plane strain the in-plane trace it takes is the volumetric strain, so the 3-D Biot
// relations hold: nu = lambda / (2 (lambda + mu)), nu_u = lambda_u / (2 (lambda_u + mu)) with
// lambda_u = lambda + b^2 M, Skempton's B = b M / K_u (K_u = lambda_u + 2 mu / 3), and the
// consolidation coefficient c = k' M (lambda + 2 mu) / (lambda_u + 2 mu) (k' over the storage of
// uniaxial strain, 1 / M + b^2 / (lambda + 2 mu)). nu = 0, nu_u = 0.44: lambda = 0, M = 22/3 mu,
// B = 11/12, p0 = 0.44 F / a, c = 11/7 k' mu.
struct Specimen {
  Scene scene;
  PointCloud cloud;
  int nx = 0, ny = 0;
  double a = 0.0, b = 0.0;  // half-width, half-height
  double mu = 0.0, lambda = 0.0, lambda_u = 0.0, biot_modulus = 0.0;
  double sigma0 = 1e6;                   // the plates' mean stress F / a [Pa]
  double p0 = 0.0;                       // F B (1 + nu_u) / (3 a)
  double rho = 0.0, c_u = 0.0, c = 0.0;  // mixture density, undrained P-wave speed, consolidation coefficient
  double t_c = 0.0;                      // a^2 / c
  double plate_force = 0.0;              // 2F [N]
  double ramp = 0.0;                     // the load's rise time
};

// transits: t_c = a^2 / c in units of a / c_u, the undrained wave's time across the half-width.
Specimen mandel_specimen(int nx, int ny, double transits) {
  Specimen sp;
  sp.nx = nx;
  sp.ny = ny;
  sp.a = 0.5 * nx * kDx;
  sp.b = 0.5 * ny * kDx;
  Scene& s = sp.scene;
  s = saturated_scene(kDx, kFactor, 1e-12, 1e9);
  sp.mu = s.material.mu;
  sp.lambda = 2.0 * kNu * sp.mu / (1.0 - 2.0 * kNu);
  sp.lambda_u = 2.0 * kNuU * sp.mu / (1.0 - 2.0 * kNuU);
  sp.biot_modulus = sp.lambda_u - sp.lambda;  // b = 1
  s.material.lambda = sp.lambda;
  PoreFluidParameters& f = *s.material.pore_fluid;
  f.biot_coefficient = 1.0;
  f.biot_modulus = sp.biot_modulus;
  sp.rho = s.material.partial_density() + s.material.porosity() * f.fluid_density;
  sp.c_u = std::sqrt((sp.lambda_u + 2.0 * sp.mu) / sp.rho);
  sp.t_c = transits * sp.a / sp.c_u;
  sp.c = sp.a * sp.a / sp.t_c;
  const double mobility = sp.c * (sp.lambda_u + 2.0 * sp.mu) / (sp.biot_modulus * (sp.lambda + 2.0 * sp.mu));
  f.permeability = mobility * f.fluid_viscosity;
  const double skempton = f.biot_coefficient * sp.biot_modulus / (sp.lambda_u + 2.0 * sp.mu / 3.0);
  const double force = sp.sigma0 * sp.a * s.thickness;  // F
  sp.plate_force = 2.0 * force;
  sp.p0 = force * skempton * (1.0 + kNuU) / (3.0 * sp.a * s.thickness);
  sp.ramp = 4.0 * sp.b / sp.c_u;  // two transits of the height
  // The conditions: the drained sides only. The plates are the test's (RigidPlates below); the
  // faces they press carry no fluid condition, so they are impermeable (docs/theory.md section 12:
  // the families the face cuts carry no flux).
  const BoundaryCondition left = condition("left_pore_pressure", BoundaryType::pore_pressure, {0.0}, "left");
  const BoundaryCondition right = condition("right_pore_pressure", BoundaryType::pore_pressure, {0.0}, "right");
  s.boundary_conditions = {left, right};
  sp.cloud = specimen_cloud(nx, ny, s.thickness);
  const double height = ny * kDx * s.thickness;
  auto layer_points = [&](int region) {
    return static_cast<std::int64_t>(std::count(sp.cloud.region.begin(), sp.cloud.region.end(), region));
  };
  sp.cloud.boundaries = {boundary_info(left, height, layer_points(1), sp.cloud.horizon),
                         boundary_info(right, height, layer_points(2), sp.cloud.horizon)};
  return sp;
}

// The rigid, frictionless plates. Our conditions prescribe a motion or a traction, not a rigid body
// carrying a force; and a roller layer (a kinematic layer with x free) is a band of material
// without pore pressure (docs/theory.md section 12: the fictitious layers carry no fluid) that the
// specimen's lateral expansion stretches: a skin in tension along each plate, which held the
// centre's peak 0.015 p0 above the series at a = b = 20.5 dx (0.10 p0 at b = a / 2: it falls only as
// 1 / b with the height). So the plates here press the specimen's own top and bottom rows, which keep their pore
// pressure: the top row moves as one rigid body in y under the load (its points' vertical force
// densities replaced by one, (sum_row f_y V - load) / sum_row V: the force the specimen exerts on
// the row less the load, spread evenly; starting at rest together, its points then move together,
// to the last bit) and the bottom row is held in y (its vertical force densities zeroed). In x each
// point of both rows moves with its own forces: no horizontal force, the specimen slides on the
// plates. The rows below the top one have families cut by the free face (the surface effect of
// the nonlocal model, as at any free face); the checks below show it is a boundary layer: at
// a = b = 20.5 dx a rigid block of the top three rows instead of the top row moved the peak by
// 0.012 p0, at b = 2a by 0.0005 p0.
struct RigidPlates {
  std::vector<std::size_t> top, bottom;
  double load = 0.0;  // on the top row, downwards [N]
  void after_forces(PointData& p) const {
    double force = 0.0, volume = 0.0;
    for (const std::size_t i : top) {
      force += p.force[2 * i + 1] * p.volume[i];
      volume += p.volume[i];
    }
    for (const std::size_t i : top) p.force[2 * i + 1] = (force - load) / volume;
    for (const std::size_t i : bottom) p.force[2 * i + 1] = 0.0;
  }
  // After a step: a flow update corrected the forces pointwise by the pressure change
  // (docs/theory.md section 12); the plate's force is the sum of the corrected ones, and the load
  // is in it already.
  void after_step(PointData& p) const {
    double force = 0.0, volume = 0.0;
    for (const std::size_t i : top) {
      force += p.force[2 * i + 1] * p.volume[i];
      volume += p.volume[i];
    }
    for (const std::size_t i : top) p.force[2 * i + 1] = force / volume;
    for (const std::size_t i : bottom) p.force[2 * i + 1] = 0.0;
  }
};

// The conditions, the model (built as mppm-solve builds them) and the plates' rows.
struct SpecimenModel {
  BoundaryConditions conditions;
  Model model;
  RigidPlates plates;
  explicit SpecimenModel(const Specimen& sp)
      : conditions(sp.scene, sp.cloud, "mandel.vtp"), model(build(sp.scene, sp.cloud, conditions)) {
    for (std::size_t i = 0; i < model.points.owned; ++i) {
      if (model.points.region[i] != 0) continue;
      const double y = model.points.position[2 * i + 1];
      if (y > sp.b - kDx) plates.top.push_back(i);
      if (y < kDx - sp.b) plates.bottom.push_back(i);
    }
  }
  static Model build(const Scene& scene, const PointCloud& cloud, const BoundaryConditions& conditions) {
    ModelOptions o = model_options(scene);
    o.fluid_boundaries = conditions.fluid_layout();
    return build_model(cloud, o);
  }
};

// The body point nearest (x, y).
std::size_t nearest_body_point(const Model& m, double x, double y) {
  std::size_t best = 0;
  double d_best = 1e300;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    if (m.points.region[i] != 0) continue;
    const double d = std::hypot(m.points.position[2 * i] - x, m.points.position[2 * i + 1] - y);
    if (d < d_best) {
      d_best = d;
      best = i;
    }
  }
  return best;
}

struct Sample {
  double tv = 0.0, pressure = 0.0, series = 0.0;     // pressures / p0
  double settlement = 0.0, settlement_series = 0.0;  // -eps_yy / (F / (2 mu a))
};

// omega_1 of the specimen's slowest mode (quasi_static).
double slowest_mode(const Specimen& sp) {
  const double bar_speed = std::sqrt(4.0 * sp.mu * (sp.lambda + sp.mu) / (sp.lambda + 2.0 * sp.mu) / sp.rho);
  return std::numbers::pi * bar_speed / (4.0 * sp.b);
}

// The quasi-static dynamics of a specimen model.
ExplicitDynamics quasi_static(SpecimenModel& sm, const Specimen& sp) {
  Model& m = sm.model;
  const double dt = 0.8 * critical_time_step(m).step;
  ExplicitDynamics dynamics(m, sm.conditions, dt);
  // Mass-proportional damping c = 2 omega_1, critical for the specimen's slowest mode (the column
  // of height 2b held at its base under the top row, a quarter wave at the drained bar speed
  // sqrt(E' / rho), E' = 4 mu (lambda + mu) / (lambda + 2 mu) the plane-strain modulus of uniaxial
  // stress; the undrained one is faster). The skeleton then lags the static response by about
  // 2 / omega_1 = 5.5 b / c_u, 0.0027 in T at t_c = 2000 a / c_u and b = a.
  dynamics.set_damping(2.0 * slowest_mode(sp));
  // The solver's schedule: a flow update at most every kLongestFlowInterval = 4 steps. With longer
  // batches (every 9 steps at a = 20.5 dx) each batch's force correction rang the skeleton and the
  // centre's pressure carried a ripple of about +-0.009 p0; at 4 the peak is within 0.0005 p0 of an
  // update every step.
  const FlowSchedule schedule = flow_schedule(fluid_step_limit(m.points, m.bonds, *m.fluid, &m.drains), dt);
  dynamics.set_flow_schedule(schedule);
  return dynamics;
}

// One step under the plates with their load ramped to 2F over sp.ramp.
void plate_step(ExplicitDynamics& dynamics, SpecimenModel& sm, const Specimen& sp) {
  dynamics.step(false, [&](PointData& p, std::int64_t) {
    sm.plates.load = sp.plate_force * std::min(1.0, dynamics.time() / sp.ramp);
    sm.plates.after_forces(p);
  });
  sm.plates.after_step(sm.model.points);
}

// The undrained response: the specimen with a permeability of 1e-40 (no flow within the run) at rest
// under the load, 20 / omega_1 after the ramp (the slowest mode decayed by e^-20); the centre's
// pressure and the body's mean pressure over p0.
struct Undrained {
  double centre = 0.0, mean = 0.0;
};
Undrained undrained_response(Specimen sp) {
  sp.scene.material.pore_fluid->permeability = 1e-40;
  SpecimenModel sm(sp);
  ExplicitDynamics dynamics = quasi_static(sm, sp);
  dynamics.initialize();
  while (dynamics.time() < sp.ramp + 20.0 / slowest_mode(sp)) plate_step(dynamics, sm, sp);
  const Model& m = sm.model;
  Undrained u;
  u.centre = m.points.pore_pressure[nearest_body_point(m, 0.0, 0.0)] / sp.p0;
  double n = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    if (m.points.region[i] == 0) {
      u.mean += m.points.pore_pressure[i] / sp.p0;
      n += 1.0;
    }
  u.mean /= n;
  return u;
}

// Runs the specimen to T = tv_end, sampling the centre's pressure every dtv. T counts from the
// middle of the load's ramp: for a process as slow as the consolidation a ramp of length t_r acts
// as a step at t_r / 2 (to first order in t_r / t_c).
std::vector<Sample> run_mandel(const Specimen& sp, double tv_end, double dtv, const std::vector<double>& roots) {
  SpecimenModel sm(sp);
  Model& m = sm.model;
  ExplicitDynamics dynamics = quasi_static(sm, sp);
  dynamics.initialize();
  const std::size_t centre = nearest_body_point(m, 0.0, 0.0);
  EXPECT_LT(std::hypot(m.points.position[2 * centre], m.points.position[2 * centre + 1]), 1e-9 * kDx);
  std::vector<Sample> samples;
  const double t_start = 0.5 * sp.ramp;
  for (int k = 1; k * dtv <= tv_end + 1e-12; ++k) {
    while (dynamics.time() < t_start + k * dtv * sp.t_c) plate_step(dynamics, sm, sp);
    const double tv = (dynamics.time() - t_start) / sp.t_c;
    const double strain = -m.points.displacement[2 * sm.plates.top.front() + 1] / (2.0 * sp.b - kDx);
    samples.push_back({tv, m.points.pore_pressure[centre] / sp.p0, mandel_pressure(roots, 0.0, tv),
                       strain * 2.0 * sp.mu / sp.sigma0, mandel_settlement(roots, tv)});
  }
  EXPECT_TRUE(dynamics.finite());
  return samples;
}

// The samples' peak: the largest sample and the parabola through it and its neighbours.
Peak sampled_peak(const std::vector<Sample>& s) {
  std::size_t k = 0;
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i].pressure > s[k].pressure) k = i;
  if (k == 0 || k + 1 == s.size()) return {s[k].pressure, s[k].tv};
  const double y0 = s[k - 1].pressure, y1 = s[k].pressure, y2 = s[k + 1].pressure;
  const double h = 0.5 * (s[k + 1].tv - s[k - 1].tv);
  const double shift = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2);  // in units of h
  return {y1 - 0.25 * (y0 - y2) * shift, s[k].tv + shift * h};
}

// The largest |model - series| of the pressure over the samples with T in [lo, hi], and of the
// settlement relative to the series'.
double largest_deviation(const std::vector<Sample>& s, double lo, double hi) {
  double d = 0.0;
  for (const Sample& x : s)
    if (x.tv >= lo && x.tv <= hi) d = std::max(d, std::abs(x.pressure - x.series));
  return d;
}
double largest_settlement_deviation(const std::vector<Sample>& s, double lo, double hi) {
  double d = 0.0;
  for (const Sample& x : s)
    if (x.tv >= lo && x.tv <= hi) d = std::max(d, std::abs(x.settlement / x.settlement_series - 1.0));
  return d;
}

TEST(SolverPoreFluidMandel, MandelCryerPeakAtTheCentre) {
  const std::vector<double> roots = mandel_roots(kNu, kNuU, 400);
  const Peak series = centre_peak(roots);
  // t_c = 2000 a / c_u: the skeleton's lag (2 / omega_1, 0.0027 in T) is a quarter of the time
  // tolerance (at 5000 a / c_u the peak came 0.0009 earlier at a = 20.5 dx). Square specimens: the
  // plates' boundary layers reach the centre at 0.002 p0 (b = a against b = 2a at a = 20.5 dx).
  const Specimen fine = mandel_specimen(81, 81, 2000.0), coarse = mandel_specimen(41, 41, 2000.0);
  // The undrained start: the centre's pressure p0 = F B (1 + nu_u) / (3 a), measured 1.0067 p0 (the
  // body's mean 0.988 p0: lower near the faces).
  const Undrained undrained = undrained_response(fine);
  EXPECT_NEAR(undrained.centre, 1.0, 0.01);
  const std::vector<Sample> samples = run_mandel(fine, 0.3, 0.0025, roots);
  const Peak peak = sampled_peak(samples), coarse_peak = sampled_peak(run_mandel(coarse, 0.15, 0.0025, roots));
  std::ostringstream s;
  s << "a = 40.5 dx: " << peak.value << " at T = " << peak.tv << "; a = 20.5 dx: " << coarse_peak.value
    << " at T = " << coarse_peak.tv << "; undrained centre " << undrained.centre << "; series " << series.value
    << " at T = " << series.tv
    << "; largest |p - series| / p0 for T in [0.01, 0.3]: " << largest_deviation(samples, 0.01, 0.3)
    << ", of the settlement relative to the series: " << largest_settlement_deviation(samples, 0.01, 0.3);
  RecordProperty("mandel_peak", s.str());
  // The task's tolerance on the peak value. The peak time: the series stays within 0.02 p0 of its
  // peak for T = 0.044-0.117, and a time error of 0.01 changes the value there by 0.0015 p0 only -
  // the peak's time is a weak measure, its tolerance a quarter of that band's half-width - so the
  // whole curve is checked too: within the same 0.02 p0 from T = 0.01 (after the ramp and the lag)
  // to 0.3, where on the flanks (slope 1.4 p0 per unit T at T = 0.2) a shift of 0.015 in T would
  // show.
  EXPECT_NEAR(peak.value, series.value, 0.02);
  EXPECT_NEAR(peak.tv, series.tv, 0.01);
  EXPECT_LT(largest_deviation(samples, 0.01, 0.3), 0.02);
  // The plates' approach (their load is the force the specimen carries): the strain between the
  // plates' rows against the series over the same times, within 2 %. The specimen is a little softer
  // than the continuum where the free faces cut the families (measured +0.6 % to +1.3 %; the
  // Terzaghi column's free top made it 2.0-3.8 % softer).
  EXPECT_LT(largest_settlement_deviation(samples, 0.01, 0.3), 0.02);
  // The shortfall is the discretization's and falls as dx / a: measured -0.0142 p0 at a = 20.5 dx,
  // -0.0073 p0 at 40.5 dx (peak times 0.0777 and 0.0785 against 0.0775; the largest deviation of the
  // curve 0.011 p0). A ratio below 0.7 shows the first order; a fixed offset (the plates, a wrong
  // coefficient) would not fall.
  EXPECT_LT(std::abs(peak.value - series.value), 0.7 * std::abs(coarse_peak.value - series.value));
}

}  // namespace
}  // namespace mppm::solver
