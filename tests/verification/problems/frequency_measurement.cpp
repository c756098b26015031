#include "tests/verification/problems/frequency_measurement.hpp"

#include <algorithm>
#include <chrono>
#include <numbers>
#include <vector>

#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"

namespace mppm::verification {

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

FrequencyMeasurement measure_frequency(solver::Model& model, double expected_omega, double periods,
                                       const std::function<double(const solver::Model&)>& probe,
                                       TimeStepChoice choice) {
  FrequencyMeasurement r;
  const double period = 2 * std::numbers::pi / expected_omega;
  auto start = std::chrono::steady_clock::now();
  r.critical_step = solver::critical_time_step(model).step;
  r.critical_seconds = seconds_since(start);
  r.time_step = choice.safety * r.critical_step;
  if (choice.min_steps_per_period > 0.0) r.time_step = std::min(r.time_step, period / choice.min_steps_per_period);
  const double dt = r.time_step;

  start = std::chrono::steady_clock::now();
  solver::BoundaryConditions none(model.points);
  solver::ExplicitDynamics dynamics(model, none, dt);
  dynamics.initialize();
  const auto steps = static_cast<std::int64_t>(periods * period / dt);
  double previous = probe(model);
  std::vector<double> crossings;
  for (std::int64_t k = 1; k <= steps; ++k) {
    dynamics.step(false);
    const double value = probe(model);
    // linear interpolation inside the step
    if ((previous < 0.0) != (value < 0.0)) crossings.push_back(dynamics.time() - dt * value / (value - previous));
    previous = value;
  }
  r.integration_seconds = seconds_since(start);
  r.steps = steps;
  r.crossings = static_cast<int>(crossings.size());
  if (crossings.size() >= 2) {
    const double half_period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    r.omega = std::numbers::pi / half_period;
  }
  return r;
}

}  // namespace mppm::verification
