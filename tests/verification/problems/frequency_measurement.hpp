// Frequency of a free vibration of the discrete model, measured by integrating it in time with
// the solver's explicit scheme from a standing wave (velocities zero) and counting the zero
// crossings of the wave's projection on its mode shape.
#pragma once
#include <cstdint>
#include <functional>

#include "solver/model.hpp"

namespace mppm::verification {

// The time step: safety x the critical step of the discrete operator (as `time.step: auto`),
// capped so that an expected period holds at least `min_steps_per_period` steps (0: no cap,
// the time-discretization error is then part of what is measured).
struct TimeStepChoice {
  double safety = 0.8;
  double min_steps_per_period = 0.0;
};

struct FrequencyMeasurement {
  double omega = 0.0;  // angular frequency [rad/s]; 0 with fewer than 2 crossings
  int crossings = 0;
  std::int64_t steps = 0;
  double time_step = 0.0;         // [s]
  double critical_step = 0.0;     // 2 / omega_max of the discrete operator [s]
  double critical_seconds = 0.0;  // wall time of the critical-step estimate
  double integration_seconds = 0.0;
};

// Integrates from the model's current state (velocities zero) over about `periods` periods of
// `expected_omega` and measures the frequency of `probe` from its zero crossings.
FrequencyMeasurement measure_frequency(solver::Model& model, double expected_omega, double periods,
                                       const std::function<double(const solver::Model&)>& probe, TimeStepChoice choice);

}  // namespace mppm::verification
