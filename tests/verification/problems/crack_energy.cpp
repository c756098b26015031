#include "tests/verification/problems/crack_energy.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "solver/boundary_conditions.hpp"
#include "solver/crack_area.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "tests/verification/problems/periodic_lattice.hpp"

namespace mppm::verification {

namespace {

constexpr int kBelow = 1, kAbove = 2;  // region / boundary id of the two layers
constexpr int kCheckEvery = 25;        // steps between separation checks (and energy evaluations)

}  // namespace

void set_crack_branching_material(Scene& s) {
  s.material.density = 2650.0;
  s.material.solid_fraction = 0.95;
  s.material.lambda = 14e9;
  s.material.mu = 14e9;
  s.material.mu_c = 14e9 / 3;
  s.material.length_scale = 2e-3;
  s.material.couple_moduli =
      s.dimension == 2 ? std::array<double, 3>{0.0, 0.0, 56e3} : std::array<double, 3>{0.2 * 56e3, 56e3, 0.3 * 56e3};
  s.effects.micropolar = true;
  s.effects.damage = true;
  s.material.damage = DamageParameters{160.0, 0.0, DamageCalibration::lattice, std::nullopt};
}

CrackEnergyResult drive_crack(const Scene& scene_in, const CrackStrip& strip) {
  if (!scene_in.effects.damage || !scene_in.material.damage)
    throw std::invalid_argument("drive_crack: the scene needs the damage effect and its parameters");
  if (strip.height % 2 != 0) throw std::invalid_argument("drive_crack: the height must be even");
  Scene scene = scene_in;
  const int D = scene.dimension;
  const double dx = scene.geometry.spacing;
  const int layers = static_cast<int>(std::ceil(scene.geometry.horizon_factor - 1e-9));
  const int rows = strip.height + 2 * layers;
  const int depth = D == 3 ? strip.depth : 1;
  PointCloud cloud = make_lattice(D, {strip.length, rows, depth}, dx, scene.thickness);
  std::int64_t below = 0, above = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const int row = static_cast<int>(std::floor(cloud.y[i] / dx));
    if (row < layers) {
      cloud.region[i] = cloud.boundary_id[i] = kBelow;
      ++below;
    } else if (row >= layers + strip.height) {
      cloud.region[i] = cloud.boundary_id[i] = kAbove;
      ++above;
    }
  }
  const double thickness = D == 2 ? scene.thickness : depth * dx;  // of the crack front
  const double face = strip.length * dx * thickness;
  cloud.boundaries = {BoundaryInfo{"below", "velocity", face, below, "", 0.0},
                      BoundaryInfo{"above", "velocity", face, above, "", 0.0}};

  // The pre-crack on the mid-plane from outside the left edge to the notch tip (3-D: a rectangle
  // of two triangles through the whole periodic thickness, so that its wrapped bonds are cut too).
  const double y_crack = (layers + strip.height / 2) * dx;
  const double x_tip = strip.notch * dx;
  if (D == 2) {
    cloud.precrack_vertices = {-dx, y_crack, 0.0, x_tip, y_crack, 0.0};
  } else {
    const double z0 = -2.0 * depth * dx, z1 = 3.0 * depth * dx;
    cloud.precrack_vertices = {-dx, y_crack, z0, x_tip, y_crack, z0, x_tip, y_crack, z1,
                               -dx, y_crack, z0, x_tip, y_crack, z1, -dx,   y_crack, z1};
  }

  // Both grips move away from the mid-plane (x and z held) until the opening gives W H =
  // overload x G_cr, then hold.
  const double g_cr = scene.material.damage->critical_energy_release_rate;
  const solver::CosseratConstants constants = solver::cosserat_constants(scene);
  const double h = strip.height * dx;
  const double strain = std::sqrt(2.0 * strip.overload * g_cr / ((constants.lambda + 2.0 * constants.mu) * h));
  const double grip_time = 0.5 * strain * h / strip.grip_speed;
  auto layer_condition = [&](const char* name, double sign) {
    BoundaryCondition bc;
    bc.name = name;
    bc.type = BoundaryType::velocity;
    std::vector<double> v(static_cast<std::size_t>(D), 0.0);
    bc.value.times = {0.0, grip_time, grip_time};
    bc.value.values = {v, v, v};
    bc.value.values[0][1] = bc.value.values[1][1] = sign * strip.grip_speed;
    bc.constrained.assign(static_cast<std::size_t>(D), true);
    return bc;
  };
  scene.boundary_conditions = {layer_condition("below", -1.0), layer_condition("above", 1.0)};
  scene.time.end = strip.end_time;

  omp_set_num_threads(strip.threads);
  solver::Model model = make_model(cloud, scene, {0.0, 0.0, D == 3 ? depth * dx : 0.0});
  const solver::BoundaryConditions conditions(scene, cloud, model.points, "crack-strip");
  const double critical = solver::critical_time_step(model).step;
  const double dt = strip.safety * model.damage_critical_step(critical);
  model.set_breakage_time_step(dt);
  solver::ExplicitDynamics dynamics(model, conditions, dt);
  dynamics.initialize();

  CrackEnergyResult r;
  r.points = model.points.owned;
  r.bonds = model.bonds.bond_count();
  r.time_step = dt;
  r.critical_g = g_cr;
  r.crack_area = (strip.length - strip.notch) * dx * thickness;
  r.available_energy = strip.overload * g_cr * r.crack_area;

  // Pairs (i < j) across the mid-plane whose crossing point lies right of the notch tip.
  const solver::PointData& p = model.points;
  const solver::BondFamilies& f = model.bonds;
  auto crossing = [&](std::size_t i, std::int64_t b) {
    double xi[3];
    solver::bond_vector(f, p, i, b, xi);
    const double yi = p.position[i * D + 1], dy = xi[1];
    const double yj = yi + dy;
    if (!((yi < y_crack) != (yj < y_crack))) return false;
    const double x = p.position[i * D] + (y_crack - yi) / dy * xi[0];
    return x > x_tip;
  };
  auto count_crossing = [&](bool intact_only) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < p.owned; ++i)
      for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
        if (f.neighbor_of(b) > i && crossing(i, b) && (!intact_only || f.acting(b))) ++count;
    return count;
  };
  r.crossing_bonds = count_crossing(false);
  // 3-D: the crack area of the broken bonds (solver/crack_area.hpp), the pre-crack's at the start.
  auto broken_bond_area = [&] {
    double area = 0.0;
    for (std::size_t i = 0; i < p.owned; ++i) area += solver::point_crack_area(p, f, model.precrack_cuts, i);
    return area;
  };
  const double precrack_area = D == 3 ? broken_bond_area() : 0.0;

  const auto start = std::chrono::steady_clock::now();
  const auto max_steps = static_cast<std::int64_t>(std::ceil(strip.end_time / dt));
  std::int64_t k = 0;
  while (k < max_steps) {
    ++k;
    const bool check = k % kCheckEvery == 0 || k == max_steps;
    dynamics.step(check);
    if (!dynamics.finite()) break;
    if (check && count_crossing(true) == 0) {
      r.separated = true;
      r.separation_time = dynamics.time();
      break;
    }
  }
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.steps = k;
  r.bond_updates = static_cast<std::int64_t>(r.bonds) * k;
  const solver::EnergyState& e = dynamics.energy();
  r.fracture_dissipation = e.fracture_dissipation;
  r.external_work = e.external_work;
  r.balance_error = dynamics.balance_error();
  r.measured_g = r.fracture_dissipation / r.crack_area;
  r.crossing_bonds_broken = r.crossing_bonds - count_crossing(true);
  for (std::size_t i = 0; i < p.owned; ++i)
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const std::size_t j = f.neighbor_of(b);
      const double work = solver::bond_work(f, i, b);
      if (f.acting(b))
        r.largest_bond_work_ratio = std::max(r.largest_bond_work_ratio, work / model.constants.critical_bond_work);
      if (j <= i || f.acting(b)) continue;
      r.broken_bond_work += p.volume[i] * p.volume[j] * work;
      if (crossing(i, b)) r.crossing_bond_work += p.volume[i] * p.volume[j] * work;
    }
  r.other_bonds_broken = model.broken_bonds - r.crossing_bonds_broken;
  if (D == 3) r.broken_bond_area = broken_bond_area() - precrack_area;
  return r;
}

}  // namespace mppm::verification
