// Verification of the pore fluid's drained boundaries (docs/theory.md section 12) on columns periodic
// across (a 1-D problem along y, no lateral strain):
// - steady Darcy flow through a block between two drained faces: the outflow is k' dp A / L within
//   1 % for L = 200 dx, and the drained layer acts as a face a fixed distance a beyond the body's
//   (the same a for every L): Q = k' dp A / (L + 2 a);
// - Terzaghi's consolidation of a column loaded and drained on top, fixed and impermeable at its
//   base: the degree of consolidation from the settlement and the base pressure against the series.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/pore_fluid.hpp"
#include "tests/verification/solver_fluid_column.hpp"

namespace mppm::solver {
namespace {

using testing::boundary_info;
using testing::column_cloud;
using testing::ColumnTags;
using testing::condition;
using testing::count_tagged;
using testing::saturated_scene;

constexpr double kDx = 1e-3;
constexpr int kNx = 8;            // the period along x exceeds twice the horizon
constexpr double kFactor = 3.05;  // horizon / dx
constexpr int kLayerRows = 3;     // rows of the layers: the lattice rows within the horizon

// The conditions and the model of a column, built as mppm-solve builds them (periodic along x).
struct ColumnModel {
  BoundaryConditions conditions;
  Model model;
  ColumnModel(const Scene& scene, const PointCloud& cloud)
      : conditions(scene, cloud, "column.vtp"), model(build(scene, cloud, conditions)) {}
  static Model build(const Scene& scene, const PointCloud& cloud, const BoundaryConditions& conditions) {
    ModelOptions o = model_options(scene);
    o.period = {kNx * kDx, 0.0, 0.0};
    o.fluid_boundaries = conditions.fluid_layout();
    return build_model(cloud, o);
  }
};

// ----------------------------------------------------------------------------- steady Darcy flow

struct DarcyFlow {
  double inflow = 0.0, outflow = 0.0;  // [m^3/s]
  double darcy = 0.0;                  // k' dp A / L
};

// A block of `rows` rows between a drained face at dp (below) and one at 0 (above), from the
// linear pressure to the steady state: flow updates at 0.9 of the step limit until the outflow
// changes by less than 1e-9 of Darcy's over 500 updates and equals the inflow to 1e-8 of it.
DarcyFlow steady_darcy_flow(int rows) {
  Scene s = saturated_scene(kDx, kFactor, 1e-12, 2e9);
  const double area = kNx * kDx * s.thickness, dp = 1e5, length = rows * kDx;
  const BoundaryCondition inlet = condition("inlet", BoundaryType::pore_pressure, {dp}, "bottom");
  const BoundaryCondition outlet = condition("outlet", BoundaryType::pore_pressure, {0.0}, "top");
  s.boundary_conditions = {inlet, outlet};
  PointCloud c = column_cloud(kNx, rows, kLayerRows, kDx, s.thickness, ColumnTags{2, 0, 0});
  c.horizon = kFactor * kDx;
  c.boundaries = {boundary_info(inlet, area, count_tagged(c, 1, 0), c.horizon),
                  boundary_info(outlet, area, count_tagged(c, 2, 0), c.horizon)};
  ColumnModel cm(s, c);
  Model& m = cm.model;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    if (m.points.region[i] != 0) continue;
    m.points.pore_pressure[i] = dp * (1.0 - m.points.position[2 * i + 1] / length);
    m.points.fluid_content_change[i] = m.points.pore_pressure[i] / m.fluid->biot_modulus;
  }
  cm.conditions.prescribe_pore_pressure(m.points, 0.0);
  FlowBoundaries boundaries{&m.drains, {}};
  const double dt = 0.9 * fluid_step_limit(m.points, m.bonds, *m.fluid, &m.drains);
  DarcyFlow r;
  r.darcy = m.fluid->mobility * dp * area / length;
  double last = 0.0;
  for (int k = 1; k <= 200000; ++k) {
    flow_update(m.points, m.bonds, *m.fluid, dt, &boundaries);
    if (k % 500 != 0) continue;
    r.inflow = -m.drains.outflow[0] / dt;
    r.outflow = m.drains.outflow[1] / dt;
    if (std::abs(r.outflow - last) < 1e-9 * r.darcy && std::abs(r.inflow - r.outflow) < 1e-8 * r.darcy) return r;
    last = r.outflow;
  }
  ADD_FAILURE() << "no steady state after 200000 updates";
  return r;
}

// The distance beyond each face at which the drained layer's pressure acts: Q = k' dp A / (L + 2 a).
double face_offset(const DarcyFlow& f, int rows) { return 0.5 * rows * kDx * (f.darcy / f.outflow - 1.0); }

TEST(SolverPoreFluidBoundaries, SteadyDarcyFlowBetweenTwoDrainedFaces) {
  const DarcyFlow long_block = steady_darcy_flow(200);
  EXPECT_NEAR(long_block.inflow, long_block.outflow, 1e-8 * long_block.darcy);
  // Measured 0.9919: the 1 % the task allows holds for L >= 163 dx (below: the offset a).
  EXPECT_NEAR(long_block.outflow / long_block.darcy, 1.0, 0.01);
  // The drained layer holds its pressure over the whole horizon outside the face, so the bonds
  // that cross the face see a potential drop that a linear pressure would only reach farther out:
  // the flow is that of a block longer by a at each end, the same a for every length (measured
  // a = 0.8144 dx for delta = 3.05 dx) - a boundary layer of the nonlocal flow, not an error that
  // grows with the block. Blocks of 40 and 80 rows give a within 1e-4 dx of the long one's.
  const double a = face_offset(long_block, 200);
  const DarcyFlow short_block = steady_darcy_flow(40), middle_block = steady_darcy_flow(80);
  EXPECT_NEAR(face_offset(short_block, 40), a, 1e-4 * kDx);
  EXPECT_NEAR(face_offset(middle_block, 80), a, 1e-4 * kDx);
  EXPECT_GT(a, 0.0);
  EXPECT_LT(a, 0.5 * kFactor * kDx);
  std::ostringstream measured;
  measured << long_block.outflow / long_block.darcy << ", a = " << a / kDx << " dx";
  RecordProperty("outflow_over_darcy_L200dx", measured.str());
}

// ----------------------------------------------------------------------------- Terzaghi

// Terzaghi's series for a layer of thickness H drained at z = 0, impermeable at z = H: the degree
// of consolidation U(T_v) and the pressure p(z, T_v) / p0.
double terzaghi_degree(double tv) {
  double u = 1.0;
  for (int m = 0; m < 200; ++m) {
    const double mm = std::numbers::pi * (2 * m + 1) / 2.0;
    u -= 2.0 / (mm * mm) * std::exp(-mm * mm * tv);
  }
  return u;
}
double terzaghi_pressure(double z_over_h, double tv) {
  double p = 0.0;
  for (int m = 0; m < 200; ++m) {
    const double mm = std::numbers::pi * (2 * m + 1) / 2.0;
    p += 2.0 / mm * std::sin(mm * z_over_h) * std::exp(-mm * mm * tv);
  }
  return p;
}

// The column: 80 rows (H = 80 dx) of make_scene's skeleton (E_oed = lambda + 2 mu = 3 GPa,
// mixture density 1800 kg/m^3) saturated with b = 1 and M = E_oed, so that the undrained pressure
// is p0 = b M sigma0 / (E_oed + b^2 M) = sigma0 / 2 and c_v = k' M E_oed / (E_oed + b^2 M) =
// k' E_oed / 2. The permeability is chosen so that consolidation takes 1000 transits of the
// undrained wave, t_c = H^2 / c_v = 1000 H / c_u (c_u = sqrt((E_oed + b^2 M) / rho)): the skeleton
// is then in equilibrium at every instant to a lag of order its first mode's period, a
// thousandth of t_c.
struct Column {
  Scene scene;
  PointCloud cloud;
  double height = 80 * kDx, e_oed = 3e9, biot_modulus = 3e9, sigma0 = 1e6;
  double c_u = 0.0, c_v = 0.0, p0 = 0.0;
};

Column terzaghi_column() {
  Column col;
  Scene& s = col.scene;
  s = saturated_scene(kDx, kFactor, 1e-12, col.biot_modulus);
  const double rho = s.material.partial_density() + s.material.porosity() * s.material.pore_fluid->fluid_density;
  const double undrained = col.e_oed + col.biot_modulus;
  col.c_u = std::sqrt(undrained / rho);
  const double t_c = 1000.0 * col.height / col.c_u;
  col.c_v = col.height * col.height / t_c;
  const double mobility = col.c_v * undrained / (col.biot_modulus * col.e_oed);
  s.material.pore_fluid->permeability = mobility * s.material.pore_fluid->fluid_viscosity;
  col.p0 = col.biot_modulus * col.sigma0 / undrained;
  // The load rises over 0.002 t_c (two wave transits): T_v lags by 0.001 at most.
  const BoundaryCondition base = condition("base", BoundaryType::velocity, {0.0, 0.0}, "base");
  BoundaryCondition load = condition("top", BoundaryType::traction, {0.0, -col.sigma0}, "top", 0.002 * t_c);
  load.traction_depth = kDx;
  const BoundaryCondition drain = condition("top_pore_pressure", BoundaryType::pore_pressure, {0.0}, "top");
  s.boundary_conditions = {base, load, drain};
  const int rows = static_cast<int>(std::lround(col.height / kDx));
  col.cloud = column_cloud(kNx, rows, kLayerRows, kDx, s.thickness, ColumnTags{3, 2, 0});
  PointCloud& c = col.cloud;
  c.horizon = kFactor * kDx;
  const double area = kNx * kDx * s.thickness;
  c.boundaries = {boundary_info(base, area, count_tagged(c, 1, 0), c.horizon),
                  boundary_info(load, area, count_tagged(c, 0, 2), kDx),
                  boundary_info(drain, area, count_tagged(c, 3, 0), c.horizon)};
  return col;
}

// The settlement: minus the mean vertical displacement of the loaded top row.
double settlement(const Model& m, double height) {
  double uy = 0.0, n = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    if (m.points.region[i] == 0 && m.points.position[2 * i + 1] > height - kDx) {
      uy += m.points.displacement[2 * i + 1];
      n += 1.0;
    }
  return -uy / n;
}

// Mean pressure of the body rows with y in [lo, hi).
double mean_pressure(const Model& m, double lo, double hi) {
  double sum = 0.0, n = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double y = m.points.position[2 * i + 1];
    if (m.points.region[i] == 0 && y >= lo && y < hi) {
      sum += m.points.pore_pressure[i];
      n += 1.0;
    }
  }
  return sum / n;
}

// Quasi-static runs: mass-proportional damping c = 2 omega_1 (omega_1 = pi c / (2 H), the column's
// first mode) damps that mode critically and the higher ones more; the settlement then lags the
// static one by about c / omega_1^2 = 1.3 H / c_u, 0.0013 t_c.
ExplicitDynamics quasi_static(ColumnModel& cm, double wave_speed, double height) {
  const double dt = 0.8 * critical_time_step(cm.model).step;
  ExplicitDynamics dynamics(cm.model, cm.conditions, dt);
  dynamics.set_damping(2.0 * std::numbers::pi * wave_speed / (2.0 * height));
  const Model& m = cm.model;
  dynamics.set_flow_schedule(flow_schedule(fluid_step_limit(m.points, m.bonds, *m.fluid, &m.drains), dt));
  return dynamics;
}

// The column's static settlement under the full load: undrained (no flow: the pressure is the
// undrained one everywhere) or drained (b = 0: the skeleton alone, the end state of consolidation),
// and the undrained mean pressure of its lower half.
struct StaticState {
  double settlement = 0.0, lower_pressure = 0.0;
};
StaticState static_state(const Column& col, bool drained) {
  Scene s = col.scene;
  if (drained)
    s.material.pore_fluid->biot_coefficient = 0.0;  // the reader refuses b = 0; the model takes it
  else
    s.material.pore_fluid->permeability = 1e-40;  // no update within the run
  History& load = s.boundary_conditions[1].value;
  load = History{{0.0}, {load.values.back()}};
  ColumnModel cm(s, col.cloud);
  const double wave_speed = drained ? col.c_u * std::sqrt(col.e_oed / (col.e_oed + col.biot_modulus)) : col.c_u;
  ExplicitDynamics dynamics = quasi_static(cm, wave_speed, col.height);
  dynamics.initialize();
  // 40 transits: the critically damped first mode decays by exp(-40 pi / 2) ~ 1e-27.
  const auto steps = static_cast<int>(40.0 * col.height / wave_speed / dynamics.time_step());
  for (int k = 0; k < steps; ++k) dynamics.step(false);
  return {settlement(cm.model, col.height), mean_pressure(cm.model, 0.0, 0.5 * col.height)};
}

TEST(SolverPoreFluidBoundaries, TerzaghiConsolidationOfADrainedColumn) {
  const Column col = terzaghi_column();
  const double height = col.height;
  // The undrained and drained settlements of this discrete column (the continuum's are
  // sigma0 H / (E_oed + b^2 M) and sigma0 H / E_oed; the column's free top, whose families the
  // horizon cuts, makes it measured 3.8 % and 2.0 % softer), and the undrained pressure away from
  // the top against p0 = b M sigma0 / (E_oed + b^2 M).
  const StaticState undrained = static_state(col, false), drained = static_state(col, true);
  EXPECT_NEAR(undrained.lower_pressure / col.p0, 1.0, 0.01);  // measured 1.005
  EXPECT_NEAR(undrained.settlement / (col.sigma0 * height / (col.e_oed + col.biot_modulus)), 1.0, 0.05);
  EXPECT_NEAR(drained.settlement / (col.sigma0 * height / col.e_oed), 1.0, 0.05);

  ColumnModel cm(col.scene, col.cloud);
  ExplicitDynamics dynamics = quasi_static(cm, col.c_u, height);
  // The flow updates every other step. At this interval a kick with the forces of before the flow
  // pumped energy into the top rows' fastest modes until the run blew up near T_v = 0.13; the
  // forces refreshed after the flow keep it stable (docs/theory.md section 12).
  FlowSchedule schedule = dynamics.flow_schedule();
  ASSERT_GE(schedule.interval, 2);
  schedule.interval = 2;
  dynamics.set_flow_schedule(schedule);
  dynamics.initialize();

  // The drained layer acts as a face a = 0.8144 dx beyond the body's (SteadyDarcyFlowBetweenTwo
  // DrainedFaces): the column drains as one of height H + a whose top a holds no body, so that its
  // mean pressure gives U = ((H + a) U(T_v H^2 / (H + a)^2) - a) / H, about a / H = 0.010 below the
  // series here, and the base sits at depth H - dx/2 + a of that column. The impermeable base needs
  // no such correction (the pure diffusion of this column matches the shifted series to 5e-4).
  const double a = 0.8144 * kDx, shifted_height = height + a;
  const double tv_targets[] = {0.1, 0.2, 0.5, 1.0};
  std::ostringstream measured;
  for (const double tv : tv_targets) {
    while (dynamics.time() * col.c_v / (height * height) < tv) dynamics.step(false);
    const double tv_now = dynamics.time() * col.c_v / (height * height);
    const double degree =
        (settlement(cm.model, height) - undrained.settlement) / (drained.settlement - undrained.settlement);
    const double base = mean_pressure(cm.model, 0.0, kDx) / col.p0;
    const double series = terzaghi_degree(tv_now), base_series = terzaghi_pressure(1.0 - 0.5 * kDx / height, tv_now);
    measured << "T_v " << tv_now << ": U " << degree << " (series " << series << "), base p/p0 " << base << " (series "
             << base_series << "); ";
    // The task's tolerances against the series: measured -0.018, -0.016, -0.011, -0.005 in U and
    // +0.008, +0.011, +0.011, +0.006 in p / p0 (the offset a, and the lag of the quasi-static run).
    EXPECT_NEAR(degree, series, 0.02) << "T_v " << tv_now;
    EXPECT_NEAR(base, base_series, 0.03) << "T_v " << tv_now;
    // Against the series of the shifted face, the degree of the mean pressure (which that series
    // describes exactly; the settlement's is 0.0045 lower at T_v = 0.1) and the base pressure: what
    // is left is the lag of the load ramp and of the damping (0.001 + 0.0013 in T_v, times
    // dU/dT_v = 1.78 at T_v = 0.1), measured -0.0037 and +0.0048 at T_v = 0.1, 0.0002 at T_v = 1.
    const double tv_shifted = tv_now * height * height / (shifted_height * shifted_height);
    const double pressure_degree = 1.0 - mean_pressure(cm.model, 0.0, height) / col.p0;
    const double degree_shifted = (shifted_height * terzaghi_degree(tv_shifted) - a) / height;
    const double base_shifted = terzaghi_pressure((height - 0.5 * kDx + a) / shifted_height, tv_shifted);
    measured << "mean-pressure U " << pressure_degree << " (shifted " << degree_shifted << "), base shifted "
             << base_shifted << "; ";
    EXPECT_NEAR(pressure_degree, degree_shifted, 0.006) << "T_v " << tv_now;
    EXPECT_NEAR(base, base_shifted, 0.008) << "T_v " << tv_now;
  }
  RecordProperty("terzaghi", measured.str());
}

}  // namespace
}  // namespace mppm::solver
