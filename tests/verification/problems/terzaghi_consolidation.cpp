#include "tests/verification/problems/terzaghi_consolidation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/pore_fluid.hpp"
#include "tests/verification/problems/fluid_column.hpp"

namespace mppm::verification {

namespace {

constexpr int kLayerRows = 3;  // rows of the layers: the lattice rows within the horizon

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The settlement: minus the mean vertical displacement of the loaded top row.
double settlement(const solver::Model& m, const TerzaghiColumn& col) {
  double uy = 0.0, n = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    if (m.points.region[i] == 0 && m.points.position[2 * i + 1] > col.height - col.dx) {
      uy += m.points.displacement[2 * i + 1];
      n += 1.0;
    }
  return -uy / n;
}

// Mean pressure of the body rows with y in [lo, hi).
double mean_pressure(const solver::Model& m, double lo, double hi) {
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
solver::ExplicitDynamics quasi_static(ColumnModel& cm, double wave_speed, double height, double safety) {
  const double dt = safety * solver::critical_time_step(cm.model).step;
  solver::ExplicitDynamics dynamics(cm.model, cm.conditions, dt);
  dynamics.set_damping(2.0 * std::numbers::pi * wave_speed / (2.0 * height));
  const solver::Model& m = cm.model;
  dynamics.set_flow_schedule(
      solver::flow_schedule(solver::fluid_step_limit(m.points, m.bonds, *m.fluid, &m.drains), dt));
  return dynamics;
}

TerzaghiStaticState static_state(const TerzaghiColumn& col, bool drained, double safety, double& seconds) {
  Scene s = col.scene;
  if (drained)
    s.material.pore_fluid->biot_coefficient = 0.0;  // the reader refuses b = 0; the model takes it
  else
    s.material.pore_fluid->permeability = 1e-40;  // no update within the run
  History& load = s.boundary_conditions[1].value;
  load = History{{0.0}, {load.values.back()}};
  ColumnModel cm(s, col.cloud, col.width());
  const double wave_speed = drained ? col.c_u * std::sqrt(col.e_oed / (col.e_oed + col.biot_modulus)) : col.c_u;
  const auto start = std::chrono::steady_clock::now();
  solver::ExplicitDynamics dynamics = quasi_static(cm, wave_speed, col.height, safety);
  dynamics.initialize();
  // 40 transits: the critically damped first mode decays by exp(-40 pi / 2) ~ 1e-27.
  const auto steps = static_cast<std::int64_t>(40.0 * col.height / wave_speed / dynamics.time_step());
  for (std::int64_t k = 0; k < steps; ++k) dynamics.step(false);
  seconds += seconds_since(start);
  return {settlement(cm.model, col), mean_pressure(cm.model, 0.0, 0.5 * col.height), steps};
}

}  // namespace

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

TerzaghiColumn terzaghi_column(int rows, double dx, double horizon_factor) {
  TerzaghiColumn col;
  col.dx = dx;
  col.height = rows * dx;
  Scene& s = col.scene;
  s = saturated_scene(dx, horizon_factor, 1e-12, col.biot_modulus);
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
  load.traction_depth = dx;
  const BoundaryCondition drain = condition("top_pore_pressure", BoundaryType::pore_pressure, {0.0}, "top");
  s.boundary_conditions = {base, load, drain};
  col.cloud = column_cloud(col.columns, rows, kLayerRows, dx, s.thickness, ColumnTags{3, 2, 0});
  PointCloud& c = col.cloud;
  c.horizon = horizon_factor * dx;
  const double area = col.width() * s.thickness;
  c.boundaries = {boundary_info(base, area, count_tagged(c, 1, 0), c.horizon),
                  boundary_info(load, area, count_tagged(c, 0, 2), dx),
                  boundary_info(drain, area, count_tagged(c, 3, 0), c.horizon)};
  return col;
}

TerzaghiRun consolidate(const TerzaghiColumn& col, const std::vector<double>& tv_targets, double safety) {
  TerzaghiRun run;
  run.undrained = static_state(col, false, safety, run.solve_seconds);
  run.drained = static_state(col, true, safety, run.solve_seconds);

  ColumnModel cm(col.scene, col.cloud, col.width());
  const auto start = std::chrono::steady_clock::now();
  solver::ExplicitDynamics dynamics = quasi_static(cm, col.c_u, col.height, safety);
  // The flow updates every other step. At this interval a kick with the forces of before the flow
  // pumped energy into the top rows' fastest modes until the run blew up near T_v = 0.13; the
  // forces refreshed after the flow keep it stable (docs/theory.md section 12). A fluid step limit
  // below two mechanical steps keeps its own schedule.
  solver::FlowSchedule schedule = dynamics.flow_schedule();
  run.natural_flow_interval = schedule.interval;
  schedule.interval = std::min<std::int64_t>(schedule.interval, 2);
  run.flow_interval = schedule.interval;
  dynamics.set_flow_schedule(schedule);
  dynamics.initialize();

  const double per_second = col.c_v / (col.height * col.height);  // T_v per second
  for (const double tv : tv_targets) {
    while (dynamics.time() * per_second < tv) dynamics.step(false);
    TerzaghiSample s;
    s.tv = dynamics.time() * per_second;
    s.degree =
        (settlement(cm.model, col) - run.undrained.settlement) / (run.drained.settlement - run.undrained.settlement);
    s.base_pressure = mean_pressure(cm.model, 0.0, col.dx) / col.p0;
    s.pressure_degree = 1.0 - mean_pressure(cm.model, 0.0, col.height) / col.p0;
    s.degree_series = terzaghi_degree(s.tv);
    s.base_series = terzaghi_pressure(1.0 - 0.5 * col.dx / col.height, s.tv);
    run.samples.push_back(s);
  }
  run.solve_seconds += seconds_since(start);
  run.points = cm.model.points.owned;
  run.bonds = cm.model.bonds.bond_count();
  run.steps = run.undrained.steps + run.drained.steps + dynamics.steps();
  run.time_step = dynamics.time_step();
  return run;
}

double TerzaghiRun::base_pressure_error() const {
  double e = 0.0;
  for (const TerzaghiSample& s : samples) e = std::max(e, std::abs(s.base_pressure - s.base_series));
  return e;
}

}  // namespace mppm::verification
