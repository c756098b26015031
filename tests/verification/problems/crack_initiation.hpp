// Crack initiation under a stress wave (a verification case; workflows/crack-initiation/README.md):
// a plane-strain plate with a straight pre-crack from its left edge along the mid-plane is pulled by
// a step traction sigma0 (ramped over a few steps) on its top and bottom edges. The two plane
// tensile waves meet on the crack plane, where the uncracked plate then carries sigma = 2 sigma0;
// the crack faces cannot, and the scattered field is Freund's semi-infinite crack whose faces are
// loaded by the step -sigma (Freund, Dynamic Fracture Mechanics, 1990, section 2.5):
//   K(t) = 2 sigma sqrt(c_p t (1 - 2 nu) / pi) / (1 - nu),  t from the wave's arrival,
// until a reflection (loaded edges, the corners of the free edges) reaches the tip. The crack
// starts when K reaches K_c = sqrt(E' G_cr), E' = E / (1 - nu^2):
//   t_c = pi (1 - nu)^2 K_c^2 / (4 sigma^2 c_p (1 - 2 nu)),
// and then runs with v = c_R (1 - t_c / t) (Freund's equation of motion for stress-wave loading
// with g(v) = 1 - v / c_R), so that its tip has moved l(t) = c_R [(t - t_c) - t_c ln(t / t_c)].
// The run is measured at every step: the first break of a bond across the crack plane ahead of the
// tip, and the crack advance as the number of broken crossing bonds ahead of the tip over the
// lattice's crossing bonds per unit length (lattice_crossing_sum / dx).
#pragma once
#include <cstdint>
#include <vector>

#include "common/scene.hpp"

namespace mppm::verification {

struct StressWavePlate {
  double length = 0.160;        // L along x [m]
  double height = 0.056;        // H along y [m] (rounded to an even number of rows)
  double crack_length = 0.080;  // a: the pre-crack from the left edge along the mid-plane [m]
  double traction = 8e6;        // sigma0 on each loaded edge [Pa]
  double ramp_spacings = 2.0;   // the traction rises over ramp_spacings dx / c_p (a front 2 dx long)
  double safety = 0.3;          // time step = safety x the damage run's critical step
  double window = 13.7e-6;      // stop at the wave's arrival plus this [s] (the reflections' window) ...
  double stop_advance = 0.0;    // ... or once the advance reached this [m] (0: 1.05 max(2 dx, horizon))
  int threads = 1;
};

// Freund's predictions for a plate and a scene (material, G_cr).
struct FreundPrediction {
  double wave_speed = 0.0;            // c_p = sqrt((lambda + 2 mu) / rho) [m/s]
  double rayleigh_speed = 0.0;        // c_R [m/s]
  double poisson_ratio = 0.0;         // nu = lambda / (2 (lambda + mu))
  double plane_strain_modulus = 0.0;  // E' = E / (1 - nu^2) [Pa]
  double critical_intensity = 0.0;    // K_c = sqrt(E' G_cr) [Pa sqrt(m)]
  double crack_plane_stress = 0.0;    // sigma = 2 sigma0 [Pa]
  double initiation_time = 0.0;       // t_c after the arrival [s]
  double ramp_time = 0.0;             // [s]
  // Half the ramp plus H / (2 c_p) [s]: the centroid of the front (a load spread over the loaded row sends
  // its centroid from the free edge; the lattice's dispersion spreads the front about it)
  double arrival_time = 0.0;
  double window_loaded_edges = 0.0;         // H / c_p after the arrival: reflections from the loaded edges
  double window_left_corners = 0.0;         // (sqrt(a^2 + (H/2)^2) - H/2) / c_p: the left edge's loaded corners
  double window_right_corners = 0.0;        // the same for the right edge, distance L - a
  double window() const;                    // the smallest of the three
  double stress_intensity(double t) const;  // K(t) after the arrival, for the step
  // Time after the arrival at which the tip has moved `advance` (equation of motion above).
  double advance_time(double advance) const;
};
FreundPrediction freund_prediction(const Scene& scene, const StressWavePlate& plate);

struct CrackInitiationResult {
  double spacing = 0.0, horizon = 0.0, time_step = 0.0;
  // [s] the centroid of the front in the mid-plane strain half-way between the tip and the right edge (its
  // equal-area arrival against the uncracked value 2 sigma0 / (lambda + 2 mu)): checks arrival_time
  double measured_arrival = 0.0;
  double first_break = -1.0;         // [s] the step in which the first bond across the plane ahead of the tip broke
  double first_break_x = 0.0;        // where that bond crosses the plane, from the tip [m]
  double crossing_per_length = 0.0;  // crossing pairs per unit length of the plane [1/m]
  std::vector<double> times;         // the steps at which the count of broken crossing pairs changed [s]
  std::vector<std::int64_t> broken;  // that count then
  double end_time = 0.0;
  std::int64_t steps = 0;
  std::size_t points = 0, bonds = 0, other_pairs_broken = 0;
  double balance_error = 0.0;
  double solve_seconds = 0.0;
  bool finite = true;
  // First time the advance (broken crossing pairs / crossing_per_length) reached `advance` [s]; -1: never.
  double advance_time(double advance) const;
};

// The scene gives the material (damage parameters included), spacing, horizon factor, thickness and
// effects (damage on); geometry, loads, no-fail zone (one horizon from the loaded rows) and time
// settings are the plate's own.
CrackInitiationResult run_stress_wave_plate(const Scene& scene, const StressWavePlate& plate);

}  // namespace mppm::verification
