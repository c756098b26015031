// Verification of the viscoplastic solver (docs/theory.md section 6) through the real run
// (solve(): scene -> run directory): plane-strain compression of a specimen with tiny eta
// reaches the analytic Drucker-Prager (plane-strain match: Mohr-Coulomb) limit load, and the
// energy balance with the plastic dissipation holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/snapshot_file.hpp"
#include "solver/solve_run.hpp"
#include "tests/verification/solver_viscoplastic_cases.hpp"

namespace mppm::solver {
namespace {

using namespace testing;

struct CompressionRun {
  CompressionCase c;
  std::string dir;
  std::vector<std::vector<double>> load, energy;
};

// One run shared by the tests below (well under a second): 16 x 12 body points, compressed
// to a strain of ~1 %, about 8 times the strain at first yield. The layer speeds reach
// 0.05 m/s: the wave impedance stress rho c v is 3 % of the limit, and the smooth ramp over
// ~20 periods of the lowest mode keeps the dynamic part of the load well under the 2 % bound
// (plastic flow damps what vibration there is; no mass damping, so the energy balance is the
// scheme's own).
const CompressionRun& compression_run() {
  static const CompressionRun run = [] {
    CompressionRun r;
    const double end = 2.4e-3;
    r.c = compression_case(16, 12, end, 0.01 / (0.9 * end), 1e3);
    r.c.scene.output.load_interval = end / 400;
    // One directory per test: ctest runs the tests of this file as parallel processes.
    r.dir = fresh_run_directory(std::string("compression_") +
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
    SolveOptions o;
    o.run_directory = r.dir;
    o.points_file = "compression.vtp";
    solve(r.c.scene, r.c.cloud, o);
    r.load = read_csv_rows(r.dir + "/" + run_layout::load);
    r.energy = read_csv_rows(r.dir + "/" + run_layout::energy);
    return r;
  }();
  return run;
}

TEST(SolverViscoplasticCompression, ReachesTheAnalyticLimitLoadWithinTwoPercent) {
  const CompressionRun& r = compression_run();
  const ViscoplasticParameters& vp = *r.c.scene.material.viscoplasticity;
  // Compression: the reaction of the top layer opposes its downward motion, Fy < 0.
  const double limit = -plane_strain_limit_stress(vp, 0.0) * r.c.width * r.c.scene.thickness;
  ASSERT_GE(r.load.size(), 100u);
  const double final_load = -top_layer_force(r.c, r.load.back());
  double peak = 0.0;
  for (const auto& row : r.load) peak = std::max(peak, -top_layer_force(r.c, row));
  std::printf("plane-strain compression: limit %.6g N, final load %.6g N (error %+.3e), peak %.6g N\n", limit,
              final_load, (final_load - limit) / limit, peak);
  // 2 %: the acceptance bound; the departures are the viscous overstress (eta ebar' = 1e3 Pa s *
  // ~5/s over (1 - sin phi), 3e-3 of the limit), what is left of the exponential approach, and
  // the dynamics (measured: +0.44 %).
  EXPECT_NEAR(final_load, limit, 0.02 * limit);
  EXPECT_LE(peak, 1.02 * limit);
}

// The quasi-static solution is homogeneous, so every body point has yielded and carries nearly
// the same plastic strain, with the plane-strain out-of-plane part eps_vp,zz != 0 (the flow is
// 3-D), and the plastic shear strain field is written.
TEST(SolverViscoplasticCompression, PlasticStateIsHomogeneousWithOutOfPlaneFlow) {
  const CompressionRun& r = compression_run();
  Snapshot last;
  for (const auto& e : std::filesystem::directory_iterator(r.dir + "/" + run_layout::snapshot_dir)) {
    Snapshot s = read_snapshot(e.path().string());
    if (s.time >= last.time) last = std::move(s);
  }
  ASSERT_NEAR(last.time, r.c.scene.time.end, 1e-12);
  const SnapshotField* ebar = last.find("equivalent_plastic_strain");
  const SnapshotField* shear = last.find("plastic_shear_strain");
  const SnapshotField* eps_vp = last.find("plastic_strain");
  ASSERT_TRUE(ebar && shear && eps_vp);
  EXPECT_EQ(eps_vp->components, 9);
  double lo = 1e300, hi = 0.0, zz_lo = 1e300, zz_hi = -1e300;
  for (std::size_t i = 0; i < r.c.cloud.size(); ++i) {
    if (r.c.cloud.region[i] != 0) continue;
    lo = std::min(lo, ebar->data[i]);
    hi = std::max(hi, ebar->data[i]);
    zz_lo = std::min(zz_lo, eps_vp->data[i * 9 + 8]);
    zz_hi = std::max(zz_hi, eps_vp->data[i * 9 + 8]);
    // Proportional flow: the accumulated measure equals ebar (README of solver/plasticity).
    EXPECT_NEAR(shear->data[i], ebar->data[i], 0.05 * ebar->data[i]);
  }
  std::printf("ebar in the body: %.4g .. %.4g; eps_vp,zz %.4g .. %.4g\n", lo, hi, zz_lo, zz_hi);
  EXPECT_GT(lo, 1e-3);               // all yielded, well past first yield
  EXPECT_LT(hi - lo, 1e-3 * hi);     // homogeneous: only the transient dynamics can disturb it
  EXPECT_GT(std::abs(zz_lo), 1e-5);  // out-of-plane plastic strain is there ...
  EXPECT_EQ(zz_lo < 0, zz_hi < 0);   // ... with one sign everywhere
}

TEST(SolverViscoplasticCompression, EnergyBalanceWithPlasticDissipationBelowOnePercent) {
  const CompressionRun& r = compression_run();
  // energy.csv: time, kinetic, rotational, elastic, stabilization, plastic, fracture, work, balance.
  double worst = 0.0;
  for (const auto& row : r.energy) worst = std::max(worst, std::abs(row[8]));
  const auto& last = r.energy.back();
  std::printf("energy: work %.5g J, elastic %.5g J, plastic dissipation %.5g J, worst balance error %.3e\n", last[7],
              last[3], last[5], worst);
  // The check is on a run where dissipation dominates: most of the work went into plastic flow.
  EXPECT_GT(last[5], 0.5 * last[7]);
  EXPECT_LT(worst, 0.01);  // the acceptance bound
  // The dissipation is the trapezoid rule of the work and the force is linear in the stresses,
  // so the balance holds to round-off (measured 2e-15 at the end of the run); 1e-9 leaves room for
  // round-off and fails for a right-point dissipation or a missing sigma_zz energy (1.5 %).
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace mppm::solver
