// Crack initiation under a stress wave against Freund's dynamic stress intensity factor (a verification
// case; tests/verification/problems/crack_initiation.hpp, the full form with three horizons is
// workflows/crack-initiation): a 160 x 56 mm plate with an 80 mm pre-crack along its mid-plane, a step
// traction of 8 MPa on the top and bottom edges, so that the crack plane carries sigma = 16 MPa once
// the two waves meet there; Freund's start time t_c = 5.05 us after that arrival. The short form: the
// coarse level (dx = 1 mm, horizon factor 3.05, non-polar), one thread, a few seconds per run.
//
// What is checked, and why each bound:
//  - the wave arrives at the crack plane when c_p says: the centroid of the front in the mid-plane
//    strain within half a spacing's travel of H / (2 c_p) + half the ramp (the traction is a body force
//    on the loaded row, one spacing deep: where in it the load acts is uncertain by dx / 2);
//  - the first bond to break crosses the plane within one horizon ahead of the tip, after the arrival,
//    and the crack stays on its plane (broken pairs off it: fewer than half those across it);
//  - the first break lies within delta / (c_R t_c) of t_c (28 % here): the model's tip is blunt over
//    about one horizon, so its energy flux is the sharp crack's only once the region the K field
//    dominates, which grows with the waves the tip scatters (about c_R t), is much larger than delta;
//    the relative error of the flux, hence of G ~ K^2 ~ t at the start, is of the order of their ratio.
//    Measured +19 % (lattice) and +17 % (continuum). The band does not hold at the finer levels of the
//    case (dx = 0.5 and 0.25 mm: +17 % and +24 % with the lattice calibration against 14 % and 7 %): the
//    difference does not shrink with the horizon (workflows/crack-initiation/results.md). The
//    dissipation calibration is not held to the band: its w_cr is the lattice one / 0.702 by design,
//    so that a running crack dissipates G_cr, and it starts 57 % after t_c here;
//  - the start orders with the critical bond work: continuum (5 % below lattice at horizon factor 3.05)
//    no later than lattice, dissipation (lattice / 0.702) later;
//  - the energy balance closes to round-off.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/verification/problems/crack_energy.hpp"
#include "tests/verification/problems/crack_initiation.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

Scene plate_scene(DamageCalibration calibration) {
  Scene s = testing::make_scene(2, false, 1e-3, 3.05);
  verification::set_crack_branching_material(s);
  s.effects.micropolar = false;
  s.material.damage->calibration = calibration;
  return s;
}

struct PlateRun {
  verification::FreundPrediction freund;
  verification::CrackInitiationResult result;
};

PlateRun run_plate(DamageCalibration calibration, const char* name) {
  const Scene scene = plate_scene(calibration);
  const verification::StressWavePlate plate;
  PlateRun r{verification::freund_prediction(scene, plate), verification::run_stress_wave_plate(scene, plate)};
  const auto& m = r.result;
  std::printf(
      "%s: arrival %.4g us (computed %.4g us); first break %.4g us after it, %.3g mm ahead of the tip (Freund's "
      "t_c %.4g us: %+.1f %%); advance of one horizon at %.4g us (Freund %.4g us); pairs broken off the plane %zu; "
      "balance error %.2g; %lld steps of %.3g us, %.2f s\n",
      name, m.measured_arrival * 1e6, r.freund.arrival_time * 1e6, (m.first_break - r.freund.arrival_time) * 1e6,
      m.first_break_x * 1e3, r.freund.initiation_time * 1e6,
      100.0 * ((m.first_break - r.freund.arrival_time) / r.freund.initiation_time - 1.0),
      (m.advance_time(m.horizon) - r.freund.arrival_time) * 1e6, r.freund.advance_time(m.horizon) * 1e6,
      m.other_pairs_broken, m.balance_error, static_cast<long long>(m.steps), m.time_step * 1e6, m.solve_seconds);
  return r;
}

// Time of the first break after the wave's arrival [s].
double start(const PlateRun& r) { return r.result.first_break - r.freund.arrival_time; }

void check_start(const PlateRun& r) {
  const auto& m = r.result;
  const auto& f = r.freund;
  ASSERT_TRUE(m.finite);
  EXPECT_NEAR(m.measured_arrival, f.arrival_time, 0.5 * m.spacing / f.wave_speed);
  ASSERT_GT(m.first_break, f.arrival_time);
  EXPECT_LT(m.first_break_x, m.horizon);
  EXPECT_LT(start(r), f.window());
  const double band = m.horizon / (f.rayleigh_speed * f.initiation_time);
  EXPECT_NEAR(start(r) / f.initiation_time, 1.0, band);
  const double crossing = static_cast<double>(m.broken.back());
  EXPECT_LT(static_cast<double>(m.other_pairs_broken), crossing / 2);
  EXPECT_LT(std::abs(m.balance_error), 1e-9);
}

TEST(SolverCrackInitiation, LatticeCalibratedCrackStartsWithinTheHorizonBandOfFreund) {
  check_start(run_plate(DamageCalibration::lattice, "lattice"));
}

TEST(SolverCrackInitiation, ContinuumCalibratedCrackStartsWithinTheHorizonBandOfFreund) {
  check_start(run_plate(DamageCalibration::continuum, "continuum"));
}

TEST(SolverCrackInitiation, StartOrdersWithTheCriticalBondWork) {
  const PlateRun continuum = run_plate(DamageCalibration::continuum, "continuum");
  const PlateRun lattice = run_plate(DamageCalibration::lattice, "lattice");
  const PlateRun dissipation = run_plate(DamageCalibration::dissipation, "dissipation");
  ASSERT_GT(continuum.result.first_break, 0.0);
  EXPECT_LE(start(continuum), start(lattice));
  EXPECT_LT(start(lattice), start(dissipation));
  EXPECT_LT(start(dissipation), dissipation.freund.window());
}

}  // namespace
}  // namespace mppm::solver
