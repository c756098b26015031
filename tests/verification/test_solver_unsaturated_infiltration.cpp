// Verification of the unsaturated pore fluid (docs/theory.md section 12, "Unsaturated (retention)"):
// 1-D infiltration into a column under suction, on the lattice (periodic across, a 1-D problem along
// y, gravity along -y, the skeleton held still: eps_v = 0), against the fine 1-D finite-difference
// solution of Richards' equation (tests/verification/problems/richards_column). The lattice runs the
// solver's own flow: the unsaturated schedule chosen again before every span (explicit substeps or an
// RKL2 super step), k_r averaged over each bond's ends, p from the fluid content by the retention inverse.
// - fed at half the saturated conductivity through the top row: the wetting front within 3 dx of the
//   reference's, the row saturations as close to it on average as a front 3 dx off, the mass balance to 1e-10;
// - ponded (a drained layer at p = 0 above the top): the cumulative inflow within 5 % of the
//   reference's, the front within 3 dx, the mass balance to 1e-10.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/flow_super_step.hpp"
#include "solver/pore_fluid.hpp"
#include "solver/unsaturated_coupling.hpp"
#include "tests/verification/problems/richards_column.hpp"
#include "tests/verification/solver_fluid_column.hpp"

namespace mppm::solver {
namespace {

using testing::boundary_info;
using testing::column_cloud;
using testing::ColumnModel;
using testing::ColumnTags;
using testing::condition;
using testing::count_tagged;
using testing::saturated_scene;

constexpr int kNx = 8;            // the period along x exceeds twice the horizon
constexpr double kFactor = 3.05;  // horizon / dx
constexpr int kLayerRows = 3;     // the rows of a layer: the lattice rows within the horizon
constexpr int kRows = 40;         // body rows: dx = 25 mm on the 1 m column
constexpr double kLength = 1.0, kDx = kLength / kRows;
constexpr double kGravity = 9.81;

// The loam of the Richards reference's own tests: p_e = 10 kPa, n = 2, S_res = 0.1, n0 = 0.4,
// k = 1e-12 m^2 with water (k' = 1e-9 m^2/(Pa s)), at 5 p_e of suction to start (S_r = 0.28). The
// Biot modulus is 1e7 Pa rather than 1 GPa: near saturation the capacity is 1/M, and the explicit
// flow's limit with it; both solutions take the same M.
const RetentionCurve kCurve{1e4, 2.0, 0.1};
constexpr double kPorosity = 0.4, kBiotModulus = 1e7, kMobility = 1e-9, kInitialPressure = -5e4;

verification::RichardsColumn reference_column(double end_time) {
  verification::RichardsColumn c;
  c.length = kLength;
  c.cells = 400;  // dz = 2.5 mm, a tenth of the lattice's dx
  c.curve = kCurve;
  c.storage = FluidStorage{kPorosity, 1.0, kBiotModulus};
  c.mobility = kMobility;
  c.gravity = kGravity;
  c.initial_pressure = kInitialPressure;
  c.end_time = end_time;
  c.steps = 1600;
  return c;
}

struct LatticeResult {
  verification::RichardsResult profile;  // row means of S_r, the column's front
  double inflow = 0.0;                   // per unit area [m]
  double stored = 0.0;                   // sum V (zeta - zeta_0) per unit area [m]
  double mass_balance_error = 0.0;       // |stored - inflow| / inflow
  std::int64_t rate_evaluations = 0;
};

// The column on the lattice, fed through its top row at `top_flux` [m/s] or, with `ponded`, drained
// at p = 0 by a layer above it; the flow advanced in spans of `span` seconds to end_time.
LatticeResult lattice_column(bool ponded, double top_flux, double end_time, double span) {
  Scene s = saturated_scene(kDx, kFactor, kMobility * 1e-3, kBiotModulus);
  s.material.solid_fraction = 1.0 - kPorosity;
  s.material.pore_fluid->initial_pressure = kInitialPressure;
  s.material.pore_fluid->retention =
      RetentionParameters{"van_genuchten", kCurve.air_entry_pressure, kCurve.n, kCurve.residual_saturation};
  const double area = kNx * kDx * s.thickness;
  BoundaryCondition top = ponded ? condition("pond", BoundaryType::pore_pressure, {0.0}, "top")
                                 : condition("rain", BoundaryType::fluid_flux, {top_flux}, "top");
  top.traction_depth = kDx;
  // Condition 1 holds the layer below the column (ColumnTags), which the flow does not enter.
  const BoundaryCondition base = condition("base", BoundaryType::velocity, {0.0, 0.0}, "base");
  s.boundary_conditions = {base, top};
  PointCloud c = column_cloud(kNx, kRows, kLayerRows, kDx, s.thickness, ColumnTags{ponded ? 2 : 0, ponded ? 0 : 2, 0});
  c.horizon = kFactor * kDx;
  c.boundaries = {boundary_info(base, area, count_tagged(c, 1, 0), c.horizon),
                  ponded ? boundary_info(top, area, count_tagged(c, 2, 0), c.horizon)
                         : boundary_info(top, area, count_tagged(c, 0, 2), kDx)};
  ColumnModel cm(s, c, kNx * kDx);
  Model& m = cm.model;
  m.fluid->gravity = {0.0, -kGravity, 0.0};  // the flow's potential only: the skeleton stays still
  PointData& p = m.points;
  const std::vector<double> start = p.fluid_content_change;
  FlowBoundaries boundaries{&m.drains, {}};
  for (const solver::FedSurface& f : cm.conditions.fed())
    boundaries.sources.push_back({&f.points, top_flux * f.area / f.volume_sum});
  FlowSuperStepWork work;
  std::vector<double> before;
  LatticeResult r;
  double inflow_volume = 0.0;
  for (double t = 0.0; t < end_time * (1.0 - 1e-12); t += span) {
    cm.conditions.prescribe_pore_pressure(p, t);
    const FlowSchedule plan =
        unsaturated_flow_schedule(fluid_step_limit(p, m.bonds, *m.fluid, &m.drains), span, FlowIntegration::automatic);
    if (plan.stages > 1) {
      before = p.pore_pressure;
      flow_super_step(p, m.bonds, *m.fluid, span, plan.stages, &boundaries, before, work);
      for (double v : m.drains.outflow) inflow_volume -= v;
      r.rate_evaluations += plan.stages;
    } else {
      const double h = span / static_cast<double>(plan.substeps);
      for (std::int64_t k = 0; k < plan.substeps; ++k) {
        flow_update(p, m.bonds, *m.fluid, h, &boundaries);
        for (double v : m.drains.outflow) inflow_volume -= v;
      }
      r.rate_evaluations += plan.substeps;
    }
    for (const FluidSource& f : boundaries.sources)
      for (std::int32_t i : *f.points) inflow_volume += span * f.rate * p.volume[static_cast<std::size_t>(i)];
  }
  // Row means of S_r, the stored fluid per area.
  std::vector<double> row_saturation(kRows, 0.0);
  double stored_volume = 0.0;
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (p.region[i] != 0) continue;
    EXPECT_TRUE(std::isfinite(p.pore_pressure[i])) << "point " << i;
    const double y = p.position[2 * i + 1];
    const auto row = static_cast<std::size_t>(std::lround(y / kDx - 0.5));
    row_saturation[row] += saturation(kCurve, p.pore_pressure[i]) / kNx;
    const double change = p.volume[i] * (p.fluid_content_change[i] - start[i]);
    stored_volume += change;
  }
  for (int row = 0; row < kRows; ++row) r.profile.z.push_back((row + 0.5) * kDx);
  r.profile.saturation = row_saturation;
  r.profile.initial_saturation = saturation(kCurve, kInitialPressure);
  r.inflow = inflow_volume / area;
  r.stored = stored_volume / area;
  r.mass_balance_error = std::abs(stored_volume - inflow_volume) / std::abs(inflow_volume);
  r.profile.front_depth = verification::wetting_front_depth(r.profile, kLength);
  return r;
}

// The mean absolute difference between the lattice's row saturations and the reference's over the same
// rows (the means of its cells in each row).
double mean_saturation_difference(const LatticeResult& lat, const verification::RichardsResult& ref) {
  const std::size_t cells = ref.saturation.size() / lat.profile.saturation.size();
  double sum = 0.0;
  for (std::size_t row = 0; row < lat.profile.saturation.size(); ++row) {
    double mean = 0.0;
    for (std::size_t k = row * cells; k < (row + 1) * cells; ++k)
      mean += ref.saturation[k] / static_cast<double>(cells);
    sum += std::abs(lat.profile.saturation[row] - mean);
  }
  return sum / static_cast<double>(lat.profile.saturation.size());
}

TEST(SolverUnsaturatedInfiltration, FedColumnFollowsRichardsEquation) {
  const double flux = 0.5 * kMobility * 1000.0 * kGravity, end = 1.6e4;
  verification::RichardsColumn rc = reference_column(end);
  rc.top_flux = flux;
  const verification::RichardsResult ref = verification::solve_richards_column(rc);
  ASSERT_TRUE(ref.converged);
  const LatticeResult lat = lattice_column(false, flux, end, 20.0);
  const double difference = mean_saturation_difference(lat, ref);
  std::printf(
      "fed: front %.4f m (reference %.4f m), mean row saturation difference %.5f, inflow %.5e m, "
      "mass balance %.2e, %lld rate evaluations\n",
      lat.profile.front_depth, ref.front_depth, difference, lat.inflow, lat.mass_balance_error,
      static_cast<long long>(lat.rate_evaluations));
  EXPECT_NEAR(lat.inflow, flux * end, 1e-12 * flux * end);  // the source is the condition's flux exactly
  // Conservation: the pair fluxes are antisymmetric and the contents are the state: round-off.
  EXPECT_LT(lat.mass_balance_error, 1e-10);
  EXPECT_NEAR(lat.profile.front_depth, ref.front_depth, 3.0 * kDx);
  // The profile: a front 3 dx off with the same jump in S_r would differ by 3 dx (S_top - S_0) / L on
  // average over the column; the whole profile is held to that.
  const double jump = ref.saturation.back() - ref.initial_saturation;
  EXPECT_LT(difference, 3.0 * kDx * jump / kLength);
}

TEST(SolverUnsaturatedInfiltration, PondedColumnTakesRichardsInflow) {
  const double end = 4e3;
  verification::RichardsColumn rc = reference_column(end);
  rc.top_pressure_given = true;
  rc.top_pressure = 0.0;
  const verification::RichardsResult ref = verification::solve_richards_column(rc);
  ASSERT_TRUE(ref.converged);
  const LatticeResult lat = lattice_column(true, 0.0, end, 10.0);
  std::printf(
      "ponded: inflow %.5e m (reference %.5e m), front %.4f m (reference %.4f m), mass balance %.2e, "
      "%lld rate evaluations\n",
      lat.inflow, ref.inflow, lat.profile.front_depth, ref.front_depth, lat.mass_balance_error,
      static_cast<long long>(lat.rate_evaluations));
  EXPECT_LT(lat.mass_balance_error, 1e-10);
  EXPECT_NEAR(lat.inflow, ref.inflow, 0.05 * ref.inflow);
  EXPECT_NEAR(lat.profile.front_depth, ref.front_depth, 3.0 * kDx);
}

}  // namespace
}  // namespace mppm::solver
