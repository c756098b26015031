// mppm-crack-initiation: the start of a crack under a plane stress wave against Freund's dynamic
// stress intensity factor (tests/verification/problems/crack_initiation.hpp; the case
// workflows/crack-initiation runs it per horizon and calibration). Not a test: it prints one CSV
// row per run, and with --history the count of broken crossing pairs at every step where it changed.
#include "tests/verification/problems/crack_initiation.hpp"

#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "tests/verification/problems/crack_energy.hpp"

using namespace mppm;

namespace {

const char* kUsage =
    R"(usage: mppm-crack-initiation --spacing DX --horizon-factor M --calibration lattice|continuum|dissipation
                             [--traction SIGMA0] [--safety S] [--micropolar] [--history FILE] [--threads N]

A 160 x 56 mm plane-strain plate (crack-branching material, non-polar unless --micropolar, G_cr =
160 N/m) with an 80 mm pre-crack from its left edge along the mid-plane; a traction SIGMA0 [Pa]
(default 8e6) on the top and bottom edges rises over 2 dx / c_p; the time step is S (default 0.3)
times the damage run's critical step. Prints a header and one CSV row:
Freund's predictions (times after the wave's arrival at the crack plane) and what the run measured
(first break ahead of the tip, advances of dx, 2 dx and one horizon, all after the computed arrival).
)";

double number(const CommandLine& cl, const std::string& option, double fallback) {
  const auto text = cl.option(option);
  if (!text) return fallback;
  char* end = nullptr;
  const double v = std::strtod(text->c_str(), &end);
  if (text->empty() || *end != '\0' || !(v > 0.0))
    throw InputError(option + ": expected a positive number, got '" + *text + "'");
  return v;
}

DamageCalibration calibration(const std::string& name) {
  if (name == "lattice") return DamageCalibration::lattice;
  if (name == "continuum") return DamageCalibration::continuum;
  if (name == "dissipation") return DamageCalibration::dissipation;
  throw InputError("--calibration: expected lattice, continuum or dissipation, got '" + name + "'");
}

Scene plate_scene(const CommandLine& cl) {
  Scene s;
  s.path = "crack-initiation.yaml";
  s.dimension = 2;
  s.thickness = 1e-3;
  s.geometry.spacing = number(cl, "--spacing", 0.5e-3);
  s.geometry.horizon_factor = number(cl, "--horizon-factor", 3.05);
  verification::set_crack_branching_material(s);
  s.effects.micropolar = cl.has_flag("--micropolar");
  s.material.damage->calibration = calibration(cl.option("--calibration").value_or("lattice"));
  s.numerics.stabilization = 0.1;
  return s;
}

// Times from the wave's arrival at the crack plane (the computed centroid); -1 stays -1 (not reached).
double after(double t, double arrival) { return t < 0.0 ? -1.0 : t - arrival; }

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{"mppm-crack-initiation",
                             kUsage,
                             {"--spacing", "--horizon-factor", "--calibration", "--traction", "--safety", "--history"},
                             {"--micropolar"}};
  return run_stage(argc, argv, spec, [](const CommandLine& cl) -> int {
    const Scene scene = plate_scene(cl);
    verification::StressWavePlate plate;
    plate.traction = number(cl, "--traction", plate.traction);
    plate.safety = number(cl, "--safety", plate.safety);
    plate.threads = omp_get_max_threads();
    const auto f = verification::freund_prediction(scene, plate);
    const auto r = verification::run_stress_wave_plate(scene, plate);
    const double dx = r.spacing, a0 = f.arrival_time;
    std::printf(
        "spacing_m,horizon_factor,horizon_m,calibration,micropolar,traction_Pa,points,bonds,time_step_s,ramp_s,"
        "wave_speed_m_per_s,rayleigh_speed_m_per_s,critical_intensity_Pa_sqrtm,predicted_arrival_s,measured_arrival_s,"
        "predicted_start_s,predicted_advance_dx_s,predicted_advance_2dx_s,predicted_advance_horizon_s,"
        "first_break_s,first_break_x_m,advance_dx_s,advance_2dx_s,advance_horizon_s,window_loaded_edges_s,"
        "window_left_corners_s,window_right_corners_s,end_time_s,steps,other_pairs_broken,balance_error,finite,"
        "wall_s\n");
    std::printf(
        "%g,%g,%g,%s,%d,%g,%zu,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,"
        "%.6g,%.6g,%.6g,%.6g,%lld,%zu,%.3g,%d,%.2f\n",
        dx, scene.geometry.horizon_factor, r.horizon, cl.option("--calibration").value_or("lattice").c_str(),
        scene.effects.micropolar ? 1 : 0, plate.traction, r.points, r.bonds, r.time_step, f.ramp_time, f.wave_speed,
        f.rayleigh_speed, f.critical_intensity, f.arrival_time, r.measured_arrival, f.initiation_time,
        f.advance_time(dx), f.advance_time(2 * dx), f.advance_time(r.horizon), after(r.first_break, a0),
        r.first_break_x, after(r.advance_time(dx), a0), after(r.advance_time(2 * dx), a0),
        after(r.advance_time(r.horizon), a0), f.window_loaded_edges, f.window_left_corners, f.window_right_corners,
        r.end_time, static_cast<long long>(r.steps), r.other_pairs_broken, r.balance_error, r.finite ? 1 : 0,
        r.solve_seconds);
    if (const auto path = cl.option("--history")) {
      std::ofstream out(*path);
      if (!out) throw InputError("--history: cannot write '" + *path + "'");
      out << "time_after_arrival_s,broken_crossing_pairs,advance_m\n";
      for (std::size_t k = 0; k < r.times.size(); ++k)
        out << r.times[k] - a0 << ',' << r.broken[k] << ',' << r.broken[k] / r.crossing_per_length << '\n';
    }
    return r.finite ? 0 : 3;
  });
}
