#include "tests/verification/problems/crack_initiation.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bond_breakage.hpp"
#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "tests/verification/problems/periodic_lattice.hpp"

namespace mppm::verification {

namespace {

constexpr int kTop = 1, kBottom = 2;  // boundary ids of the loaded rows
constexpr int kEnergyEvery = 100;     // steps between energy evaluations (the balance error is the last one's)

// Bisection for f(x) = 0 on [lo, hi] with f(lo) < 0 < f(hi) (monotone f).
template <class F>
double bisect(F f, double lo, double hi) {
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Rayleigh speed from the Rayleigh equation (2 - x^2)^2 = 4 sqrt(1 - k x^2) sqrt(1 - x^2), x = c / c_s,
// k = (c_s / c_p)^2; the root in (0, 1).
double rayleigh_speed(double shear_speed, double p_speed) {
  const double k = shear_speed * shear_speed / (p_speed * p_speed);
  auto f = [k](double x) {  // negative below the root, positive above it
    const double x2 = x * x;
    return (2.0 - x2) * (2.0 - x2) - 4.0 * std::sqrt(1.0 - k * x2) * std::sqrt(1.0 - x2);
  };
  return shear_speed * bisect(f, 0.5, 1.0 - 1e-12);
}

int rows_of(double height, double dx) {
  const int rows = static_cast<int>(std::lround(height / dx));
  return rows + rows % 2;  // even: the crack plane lies between two rows
}

// On a cell face plus 0.01 dx: the diagonal bonds that cross the crack plane exactly at the face are cut
// (docs/theory.md section 8: a bond touching a pre-crack is cut) whatever the rounding of the coordinates.
double tip_position(const StressWavePlate& plate, double dx) {
  return (std::round(plate.crack_length / dx) + 0.01) * dx;
}

struct Lattice {
  PointCloud cloud;
  double y_crack = 0.0, x_tip = 0.0;
  int columns = 0, rows = 0;
};

// The plate's lattice, its loaded top and bottom rows (traction, loaded depth dx) and the pre-crack
// from outside the left edge to the tip on the mid-plane, half-way between two rows.
Lattice plate_lattice(const Scene& scene, const StressWavePlate& plate) {
  const double dx = scene.geometry.spacing;
  Lattice l;
  l.columns = static_cast<int>(std::lround(plate.length / dx));
  l.rows = rows_of(plate.height, dx);
  l.cloud = make_lattice(2, {l.columns, l.rows, 1}, dx, scene.thickness);
  std::int64_t top = 0, bottom = 0;
  for (std::size_t i = 0; i < l.cloud.size(); ++i) {
    const int row = static_cast<int>(std::floor(l.cloud.y[i] / dx));
    if (row == l.rows - 1) {
      l.cloud.boundary_id[i] = kTop;
      ++top;
    } else if (row == 0) {
      l.cloud.boundary_id[i] = kBottom;
      ++bottom;
    }
  }
  const double face = l.columns * dx * scene.thickness;
  l.cloud.boundaries = {BoundaryInfo{"top", "traction", face, top, "", dx},
                        BoundaryInfo{"bottom", "traction", face, bottom, "", dx}};
  l.y_crack = 0.5 * l.rows * dx;
  l.x_tip = tip_position(plate, dx);
  l.cloud.precrack_vertices = {-dx, l.y_crack, 0.0, l.x_tip, l.y_crack, 0.0};
  return l;
}

BoundaryCondition traction_condition(const char* name, double value, double ramp, double dx) {
  BoundaryCondition bc;
  bc.name = name;
  bc.type = BoundaryType::traction;
  bc.value.times = {0.0, ramp};
  bc.value.values = {{0.0, 0.0}, {0.0, value}};
  bc.constrained.assign(2, true);
  bc.traction_depth = dx;
  return bc;
}

// The crossing pairs (bond at the lower index end) across the crack plane that the pre-crack left acting (those
// right of the tip), and where each crosses it, from the tip.
struct CrossingPairs {
  std::vector<std::int64_t> bond;
  std::vector<double> x;
};

CrossingPairs crossing_pairs(const solver::Model& model, double y_crack, double x_tip) {
  const solver::PointData& p = model.points;
  const solver::BondFamilies& f = model.bonds;
  CrossingPairs c;
  for (std::size_t i = 0; i < p.owned; ++i)
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      if (f.neighbor_of(b) <= i) continue;
      double xi[3];
      solver::bond_vector(f, p, i, b, xi);
      const double yi = p.position[i * 2 + 1], yj = yi + xi[1];
      if ((yi < y_crack) == (yj < y_crack)) continue;
      if (!f.acting(b)) continue;  // cut by the pre-crack: every crossing pair left of the tip
      const double x = p.position[i * 2] + (y_crack - yi) / xi[1] * xi[0];
      c.bond.push_back(b);
      c.x.push_back(x - x_tip);
    }
  return c;
}

// The mid-plane strain (u_y above minus below, over dx) in the column half-way between the tip and the
// right edge, far from both until well after the arrival, and the front's equal-area arrival there:
// t_a = T - integral_0^T strain dt / final strain, the arrival of the step whose time integral up to T is
// the measured one (the front's centroid; its half-value point lags behind it by the dispersion of the
// lattice). T: the computed arrival plus 0.9 of the time the right edge's loaded corners need to disturb
// the probe. The final strain is the uncracked plate's, 2 sigma0 / (lambda + 2 mu).
class ArrivalProbe {
 public:
  ArrivalProbe(const Lattice& l, const solver::Model& model, const FreundPrediction& freund, double traction)
      : dx_(l.cloud.spacing) {
    const int column = (static_cast<int>(std::lround(l.x_tip / dx_)) + l.columns) / 2;
    below_ = static_cast<std::size_t>((l.rows / 2 - 1) * l.columns + column);
    above_ = below_ + static_cast<std::size_t>(l.columns);
    const double x = model.points.position[below_ * 2], h = l.y_crack;
    end_ = freund.arrival_time + 0.9 * (std::hypot(l.columns * dx_ - x, h) - h) / freund.wave_speed;
    final_strain_ = 2.0 * traction / (model.constants.lambda + 2.0 * model.constants.mu);
  }
  // After the step that ended at t.
  void update(const solver::PointData& p, double t, double dt) {
    const double strain = (p.displacement[above_ * 2 + 1] - p.displacement[below_ * 2 + 1]) / dx_;
    if (t <= end_) {
      integral_ += 0.5 * dt * (strain + previous_);
      arrival_ = t - integral_ / final_strain_;
    }
    previous_ = strain;
  }
  double arrival() const { return arrival_; }

 private:
  double dx_;
  std::size_t below_ = 0, above_ = 0;
  double end_ = 0.0, final_strain_ = 0.0, integral_ = 0.0, previous_ = 0.0, arrival_ = 0.0;
};

// Counts the broken crossing pairs after each step and records the first break and every change.
void record_breaks(const solver::BondFamilies& f, const CrossingPairs& pairs, double t, CrackInitiationResult& r) {
  std::int64_t now = 0;
  double nearest = -1.0;
  for (std::size_t q = 0; q < pairs.bond.size(); ++q)
    if (!f.acting(pairs.bond[q])) {
      ++now;
      if (nearest < 0.0 || pairs.x[q] < nearest) nearest = pairs.x[q];
    }
  const std::int64_t before = r.broken.empty() ? 0 : r.broken.back();
  if (now == before) return;
  if (before == 0) {
    r.first_break = t;
    r.first_break_x = nearest;
  }
  r.times.push_back(t);
  r.broken.push_back(now);
}

}  // namespace

double FreundPrediction::window() const {
  return std::min({window_loaded_edges, window_left_corners, window_right_corners});
}

double FreundPrediction::stress_intensity(double t) const {
  if (t <= 0.0) return 0.0;
  const double nu = poisson_ratio;
  return 2.0 * crack_plane_stress * std::sqrt(wave_speed * t * (1.0 - 2.0 * nu) / std::numbers::pi) / (1.0 - nu);
}

double FreundPrediction::advance_time(double advance) const {
  if (advance <= 0.0) return initiation_time;
  const double tc = initiation_time;
  auto l = [&](double t) { return rayleigh_speed * ((t - tc) - tc * std::log(t / tc)) - advance; };
  double hi = 2.0 * tc;
  while (l(hi) < 0.0) hi *= 2.0;
  return bisect(l, tc, hi);
}

FreundPrediction freund_prediction(const Scene& scene, const StressWavePlate& plate) {
  const double lambda = scene.material.lambda, mu = scene.material.mu;
  const double rho = scene.material.density * scene.material.solid_fraction;
  const double dx = scene.geometry.spacing;
  FreundPrediction p;
  p.wave_speed = std::sqrt((lambda + 2.0 * mu) / rho);
  p.rayleigh_speed = rayleigh_speed(std::sqrt(mu / rho), p.wave_speed);
  p.poisson_ratio = lambda / (2.0 * (lambda + mu));
  p.plane_strain_modulus = 4.0 * mu * (lambda + mu) / (lambda + 2.0 * mu);
  p.critical_intensity = std::sqrt(p.plane_strain_modulus * scene.material.damage->critical_energy_release_rate);
  p.crack_plane_stress = 2.0 * plate.traction;
  const double nu = p.poisson_ratio, kc = p.critical_intensity, s = p.crack_plane_stress;
  p.initiation_time = std::numbers::pi * (1 - nu) * (1 - nu) * kc * kc / (4.0 * s * s * p.wave_speed * (1 - 2 * nu));
  p.ramp_time = plate.ramp_spacings * dx / p.wave_speed;
  const double h = 0.5 * rows_of(plate.height, dx) * dx;
  const double a = tip_position(plate, dx);
  const double length = std::lround(plate.length / dx) * dx;
  p.arrival_time = 0.5 * p.ramp_time + h / p.wave_speed;
  p.window_loaded_edges = 2.0 * h / p.wave_speed;
  p.window_left_corners = (std::hypot(a, h) - h) / p.wave_speed;
  p.window_right_corners = (std::hypot(length - a, h) - h) / p.wave_speed;
  return p;
}

double CrackInitiationResult::advance_time(double advance) const {
  const double needed = advance * crossing_per_length;
  for (std::size_t k = 0; k < times.size(); ++k)
    if (static_cast<double>(broken[k]) >= needed - 1e-9) return times[k];
  return -1.0;
}

CrackInitiationResult run_stress_wave_plate(const Scene& scene_in, const StressWavePlate& plate) {
  if (scene_in.dimension != 2 || !scene_in.effects.damage || !scene_in.material.damage)
    throw std::invalid_argument("run_stress_wave_plate: a 2-D scene with the damage effect and its parameters");
  Scene scene = scene_in;
  const double dx = scene.geometry.spacing, horizon = scene.geometry.horizon_factor * dx;
  const FreundPrediction freund = freund_prediction(scene, plate);
  const Lattice lattice = plate_lattice(scene, plate);
  scene.material.damage->no_fail_depth = horizon;
  scene.boundary_conditions = {traction_condition("top", plate.traction, freund.ramp_time, dx),
                               traction_condition("bottom", -plate.traction, freund.ramp_time, dx)};
  const double stop_advance = plate.stop_advance > 0.0 ? plate.stop_advance : 1.05 * std::max(2.0 * dx, horizon);

  omp_set_num_threads(plate.threads);
  solver::Model model = make_model(lattice.cloud, scene);
  const solver::BoundaryConditions conditions(scene, lattice.cloud, model.points, "stress-wave-plate");
  const double dt = plate.safety * model.damage_critical_step(solver::critical_time_step(model).step);
  model.set_breakage_time_step(dt);
  solver::ExplicitDynamics dynamics(model, conditions, dt);
  dynamics.initialize();

  CrackInitiationResult r;
  r.spacing = dx;
  r.horizon = horizon;
  r.time_step = dt;
  r.points = model.points.owned;
  r.bonds = model.bonds.bond_count();
  r.crossing_per_length = solver::lattice_crossing_sum(2, scene.geometry.horizon_factor) / dx;
  const CrossingPairs pairs = crossing_pairs(model, lattice.y_crack, lattice.x_tip);
  ArrivalProbe probe(lattice, model, freund, plate.traction);

  const auto start = std::chrono::steady_clock::now();
  const auto max_steps = static_cast<std::int64_t>(std::ceil((freund.arrival_time + plate.window) / dt));
  auto advanced = [&] { return !r.broken.empty() && r.broken.back() >= stop_advance * r.crossing_per_length; };
  for (std::int64_t k = 1; k <= max_steps && r.finite && !advanced(); ++k) {
    // The last step evaluates the energies for the balance (the loop may stop early: then one more).
    const bool last = k == max_steps;
    dynamics.step(k % kEnergyEvery == 0 || last);
    r.steps = k;
    r.finite = dynamics.finite();
    probe.update(model.points, dynamics.time(), dt);
    record_breaks(model.bonds, pairs, dynamics.time(), r);
  }
  if (r.finite && r.steps < max_steps) {
    dynamics.step(true);
    r.steps += 1;
    record_breaks(model.bonds, pairs, dynamics.time(), r);
  }
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.measured_arrival = probe.arrival();
  r.end_time = dynamics.time();
  r.balance_error = dynamics.balance_error();
  r.other_pairs_broken = model.broken_bonds - static_cast<std::size_t>(r.broken.empty() ? 0 : r.broken.back());
  return r;
}

}  // namespace mppm::verification
