#include "tests/verification/problems/wave_problems.hpp"

#include <cmath>
#include <numbers>

namespace mppm::verification {

namespace {
// Periods integrated: enough for 4 zero crossings of the acoustic waves; the optical branch and
// the cut-off oscillate faster than the step limit cares about, so 6.3 periods cost little and
// average the crossing times better.
constexpr double kAcousticPeriods = 2.3, kOpticalPeriods = 6.3;
constexpr double kDisplacementAmplitude = 1e-6;  // [m]; linear model, any value works
constexpr double kRotationAmplitude = 1e-4;      // [rad]

int rotation_components(const solver::Model& m) { return m.dimension() == 2 ? 1 : 3; }
int z_rotation(const solver::Model& m) { return m.dimension() == 2 ? 0 : 2; }
}  // namespace

double p_wave_speed(const solver::CosseratConstants& c) { return std::sqrt((c.lambda + 2 * c.mu) / c.density); }

std::array<double, 2> coupled_branches(const solver::CosseratConstants& c, double k) {
  const double a = (c.mu + c.mu_c) * k * k / c.density;
  const double b = (c.bending_modulus * k * k + 4 * c.mu_c) / c.micro_inertia;
  const double coupling = 4 * c.mu_c * c.mu_c * k * k / (c.density * c.micro_inertia);
  const double root = std::sqrt((a - b) * (a - b) + 4 * coupling);
  return {0.5 * (a + b - root), 0.5 * (a + b + root)};
}

double cutoff_frequency(const solver::CosseratConstants& c) { return 2 * std::sqrt(c.mu_c / c.micro_inertia); }

WaveMeasurement measure_p_wave(solver::Model& m, double k, TimeStepChoice choice, double duration_factor) {
  const int D = m.dimension();
  for (std::size_t i = 0; i < m.points.owned; ++i)
    m.points.displacement[i * D] = kDisplacementAmplitude * std::sin(k * m.points.position[i * D]);
  const auto projection = [k, D](const solver::Model& mm) {
    double a = 0.0;
    for (std::size_t i = 0; i < mm.points.owned; ++i)
      a += mm.points.displacement[i * D] * std::sin(k * mm.points.position[i * D]);
    return a;
  };
  WaveMeasurement w;
  w.analytic_omega = k * p_wave_speed(m.constants);
  w.measured = measure_frequency(m, w.analytic_omega, kAcousticPeriods * duration_factor, projection, choice);
  return w;
}

WaveMeasurement measure_coupled_wave(solver::Model& m, double k, int branch, TimeStepChoice choice,
                                     double duration_factor) {
  const int D = m.dimension(), R = rotation_components(m), wz = z_rotation(m);
  const solver::CosseratConstants& c = m.constants;
  const double w2 = coupled_branches(c, k)[branch];
  // The branch's mode: (rho W^2 - (mu + mu_c) k^2) U = -2 mu_c k Rw.
  const double U = kDisplacementAmplitude;
  const double Rw = -(c.density * w2 - (c.mu + c.mu_c) * k * k) * U / (2 * c.mu_c * k);
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double x = m.points.position[i * D];
    m.points.displacement[i * D + 1] = U * std::sin(k * x);
    m.points.rotation[i * R + wz] = Rw * std::cos(k * x);
  }
  // Probe the dominant motion of the branch: u_y for the acoustic, w_z for the optical one.
  const auto projection = [=](const solver::Model& mm) {
    double a = 0.0;
    for (std::size_t i = 0; i < mm.points.owned; ++i) {
      const double x = mm.points.position[i * D];
      a += branch == 0 ? mm.points.displacement[i * D + 1] * std::sin(k * x)
                       : mm.points.rotation[i * R + wz] * std::cos(k * x);
    }
    return a;
  };
  WaveMeasurement w;
  w.analytic_omega = std::sqrt(w2);
  const double periods = (branch == 0 ? kAcousticPeriods : kOpticalPeriods) * duration_factor;
  w.measured = measure_frequency(m, w.analytic_omega, periods, projection, choice);
  return w;
}

WaveMeasurement measure_cutoff(solver::Model& m, TimeStepChoice choice, double duration_factor) {
  const int R = rotation_components(m), wz = z_rotation(m);
  for (std::size_t i = 0; i < m.points.owned; ++i) m.points.rotation[i * R + wz] = kRotationAmplitude;
  const auto mean_rotation = [R, wz](const solver::Model& mm) {
    double a = 0.0;
    for (std::size_t i = 0; i < mm.points.owned; ++i) a += mm.points.rotation[i * R + wz];
    return a;
  };
  WaveMeasurement w;
  w.analytic_omega = cutoff_frequency(m.constants);
  w.measured = measure_frequency(m, w.analytic_omega, kOpticalPeriods * duration_factor, mean_rotation, choice);
  return w;
}

}  // namespace mppm::verification
