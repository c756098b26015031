// Calibration of the energy-based bond breakage (docs/theory.md section 7; a verification case): a straight
// crack driven through a strip (2-D) and a slab (3-D) by fixed grips (Rice's strip:
// tests/verification/problems/crack_energy.hpp).
//
// What is measured per unit new crack area, and what each should be:
//  - the work W_ij absorbed by the broken bonds across the crack plane: G_cr, within 10 % (the
//    calibration of w_cr on the lattice's own crossing sum). Its excess over G_cr is the work of
//    each bond's last step before it breaks, O(dt): 3 % at 0.1 x the critical step, 17 % at 0.4
//    (2-D, horizon factor 3.05), hence the step of these tests;
//  - the energy the breaks remove from the model (energy.csv fracture dissipation: stored energy
//    released plus the kick term, bond_breakage.hpp): positive and below that work. The rest is
//    handed back to the elastic field: a correspondence point that loses bonds renormalizes its
//    shape tensor and keeps the strain of its remaining family, so it keeps part of the energy
//    the broken bonds carried, which then leaves as waves. Measured: 0.64-0.86 of G_cr depending
//    on the horizon factor and G_s (not on dx, dt, the material or the micropolar constants);
//  - the energy balance of the run (kinetic + stored + dissipated - external work): closed to
//    round-off.
#include <gtest/gtest.h>

#include <cstdio>

#include "common/input_error.hpp"
#include "solver/bond_breakage.hpp"
#include "tests/verification/problems/crack_energy.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

// The material of the crack-branching plate (workflows/crack-branching/README.md) with a chosen horizon factor.
Scene crack_scene(int dimension, double horizon_factor) {
  Scene s = testing::make_scene(dimension, true, 0.5e-3, horizon_factor);
  verification::set_crack_branching_material(s);
  return s;
}

void check(const char* what, const verification::CrackEnergyResult& r) {
  const double crossing = r.crossing_bond_work / r.crack_area / r.critical_g;
  const double all = r.broken_bond_work / r.crack_area / r.critical_g;
  std::printf(
      "%s: per unit new crack area / G_cr: work of the broken crossing bonds %.4f (all broken bonds %.4f), "
      "energy removed (fracture dissipation) %.4f; separated at %.4g s after %lld steps of %.3g s; crossing "
      "pairs %zu/%zu broken, other pairs %zu; balance error %.2g; %.2f s\n",
      what, crossing, all, r.ratio(), r.separation_time, static_cast<long long>(r.steps), r.time_step,
      r.crossing_bonds_broken, r.crossing_bonds, r.other_bonds_broken, r.balance_error, r.solve_seconds);
  ASSERT_TRUE(r.separated);
  EXPECT_EQ(r.crossing_bonds_broken, r.crossing_bonds);
  EXPECT_NEAR(crossing, 1.0, 0.10);
  // The crack stays a crack: few broken bonds off the crossing set (branching would multiply them).
  EXPECT_LT(r.other_bonds_broken, r.crossing_bonds / 2);
  EXPECT_GT(r.ratio(), 0.0);
  EXPECT_LT(r.ratio(), all);
  // Energy conservation with the breaks' dissipation accounted: round-off only (1e-9 of the work).
  EXPECT_LT(std::abs(r.balance_error), 1e-9);
}

TEST(SolverCrackEnergy, StripBrokenBondsAbsorbCriticalEnergyReleaseRate2d) {
  verification::CrackStrip strip;  // 80 x 20 points, notch 20, W H = 1.2 G_cr
  strip.overload = 1.2;
  strip.safety = 0.1;
  check("2-D strip, horizon factor 3.05", verification::drive_crack(crack_scene(2, 3.05), strip));
}

TEST(SolverCrackEnergy, SlabBrokenBondsAbsorbCriticalEnergyReleaseRate3d) {
  verification::CrackStrip strip;
  strip.length = 30;
  strip.height = 10;
  strip.depth = 6;  // periodic through z: more than twice the horizon factor
  strip.notch = 8;
  strip.overload = 1.5;
  strip.safety = 0.15;
  const verification::CrackEnergyResult r = verification::drive_crack(crack_scene(3, 2.55), strip);
  check("3-D slab, horizon factor 2.55", r);
  // The crack area the broken bonds span (solver/crack_area.hpp, the 3-D crack metrics' measure)
  // is the running crack's new area: 1.031 of it (the crossing pairs, all broken, count within 1 %
  // as for a planar cut, tests/unit/test_solver_crack_area.cpp; the 216 other pairs broken, 4 % of
  // the 5016 crossing ones, add to it). 5 %: the planar cut's bar.
  const double area_ratio = r.broken_bond_area / r.crack_area;
  std::printf("3-D slab: crack area of the broken bonds / new crack area %.4f\n", area_ratio);
  EXPECT_NEAR(area_ratio, 1.0, 0.05);
}

// With `calibration: dissipation` (w_cr = lattice value / rho, solver/damage_calibration.hpp) the
// energy the breaks remove from the model is G_cr per unit new crack area, the literal statement
// of docs/theory.md section 7's verification. rho was measured with the crack-branching material at
// dx = 0.5 mm and W H = 1.5 G_cr (lattice calibration); these runs change what the table assumes
// does not matter: the material (Poisson ratio 0.1 instead of 0.25, mu_c = mu instead of mu / 3),
// the spacing, G_cr and the drive (W H = 2.2 G_cr here, about 1.6 G_cr / rho). Tolerance 10 %:
// the measured rho lies up to 6.6 % from the table's across horizon factors (2-D at 2.55, G_s 0.1;
// workflows/damage-calibration/results.md), within 2.5 % at the settings run here.
Scene dissipation_scene(int dimension, double horizon_factor, double stabilization, double dx) {
  Scene s = crack_scene(dimension, horizon_factor);
  s.geometry.spacing = dx;
  s.material.lambda = 0.25 * s.material.mu;  // Poisson ratio 0.1
  s.material.mu_c = s.material.mu;
  s.material.damage = DamageParameters{300.0, 0.0, DamageCalibration::dissipation, std::nullopt};
  s.numerics.stabilization = stabilization;
  return s;
}

void check_dissipation(const char* what, const verification::CrackEnergyResult& r) {
  std::printf(
      "%s, dissipation calibration: energy removed per unit new crack area %.4g J/m^2 = %.4f G_cr; work of the "
      "crossing bonds %.4f G_cr; separated at %.4g s; other pairs %zu; balance error %.2g; %.2f s\n",
      what, r.measured_g, r.ratio(), r.crossing_bond_work / r.crack_area / r.critical_g, r.separation_time,
      r.other_bonds_broken, r.balance_error, r.solve_seconds);
  ASSERT_TRUE(r.separated);
  EXPECT_NEAR(r.ratio(), 1.0, 0.10);
  EXPECT_LT(std::abs(r.balance_error), 1e-9);
}

TEST(SolverCrackEnergy, StripDissipatesCriticalEnergyReleaseRate2d) {
  verification::CrackStrip strip;
  strip.overload = 2.2;
  strip.safety = 0.4;
  check_dissipation("2-D strip, horizon factor 4.05, G_s 0.1, dx 0.25 mm",
                    verification::drive_crack(dissipation_scene(2, 4.05, 0.1, 0.25e-3), strip));
}

TEST(SolverCrackEnergy, SlabDissipatesCriticalEnergyReleaseRate3d) {
  verification::CrackStrip strip;
  strip.length = 30;
  strip.height = 10;
  strip.depth = 6;
  strip.notch = 8;
  strip.overload = 2.2;
  strip.safety = 0.4;
  check_dissipation("3-D slab, horizon factor 2.55, G_s 0.2, dx 1 mm",
                    verification::drive_crack(dissipation_scene(3, 2.55, 0.2, 1e-3), strip));
}

// Outside the measured ranges the dissipation calibration is refused, naming the key.
TEST(SolverCrackEnergy, DissipationCalibrationOutsideItsRangeIsRefused) {
  Scene s = dissipation_scene(2, 2.05, 0.1, 1e-3);
  s.key_lines["material.damage.calibration"] = 12;
  try {
    (void)cosserat_constants(s);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("solver-test.yaml:12: material.damage.calibration"), std::string::npos) << m;
    EXPECT_NE(m.find("horizon factor 2.55 to 5.05"), std::string::npos) << m;
  }
  s.numerics.stabilization = 0.7;
  s.geometry.horizon_factor = 3.05;
  EXPECT_THROW((void)cosserat_constants(s), InputError);
}

// Below the threshold nothing breaks: at W H = 0.8 G_cr the grips open the strip and hold it; the
// bonds at the notch tip are loaded (their work is a good part of w_cr) but none reaches it.
TEST(SolverCrackEnergy, NoBondBreaksBelowTheThreshold) {
  verification::CrackStrip strip;
  strip.overload = 0.8;
  strip.end_time = 120e-6;
  strip.safety = 0.4;
  const auto r = verification::drive_crack(crack_scene(2, 3.05), strip);
  std::printf("below threshold: largest bond work %.4f w_cr, broken pairs %zu, dissipation %.3g J\n",
              r.largest_bond_work_ratio, r.crossing_bonds_broken + r.other_bonds_broken, r.fracture_dissipation);
  EXPECT_FALSE(r.separated);
  EXPECT_EQ(r.crossing_bonds_broken + r.other_bonds_broken, 0u);
  EXPECT_EQ(r.fracture_dissipation, 0.0);
  EXPECT_GT(r.largest_bond_work_ratio, 0.3);
  EXPECT_LT(r.largest_bond_work_ratio, 1.0);
}

// The lattice calibration against the continuum formula of docs/theory.md section 7, which it approaches
// for a large horizon (the crossing sum of a disc / ball of lattice points).
TEST(SolverCrackEnergy, LatticeCalibrationTendsToTheContinuumFormula) {
  for (int d : {2, 3})
    for (double m : {2.05, 3.05, 4.05, 8.05, 16.05}) {
      DamageParameters lattice{160.0, 0.0, DamageCalibration::lattice, std::nullopt};
      const double dx = 1e-3, t = 2e-3;
      const double ratio =
          critical_bond_work(lattice, d, dx, m, t, 0.1) / continuum_critical_bond_work(d, 160.0, m * dx, t);
      std::printf("dimension %d, horizon factor %.2f: lattice / continuum w_cr = %.4f\n", d, m, ratio);
      // The lattice points within the horizon fill the disc / ball up to a boundary layer of
      // about one spacing: a relative difference of the order of 1/m (measured: at most 0.26 at
      // 2.05, 0.14 at 4.05, 0.05 at 8.05).
      EXPECT_NEAR(ratio, 1.0, 0.6 / m);
      if (m > 15) {
        EXPECT_NEAR(ratio, 1.0, 0.03);
      }
    }
  DamageParameters continuum{160.0, 0.0, DamageCalibration::continuum, std::nullopt};
  EXPECT_DOUBLE_EQ(critical_bond_work(continuum, 2, 1e-3, 3.05, 2e-3, 0.1),
                   continuum_critical_bond_work(2, 160.0, 3.05e-3, 2e-3));
}

}  // namespace
}  // namespace mppm::solver
