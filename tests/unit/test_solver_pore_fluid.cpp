// The saturated pore fluid (docs/theory.md section 12): the bond flux against Darcy's law (exact for a
// linear and a quadratic pressure on the lattice), conservation of the fluid, the flow update's
// dissipation, the coupling to the skeleton (p = M (zeta - n0 - b tr eps), forces minus the
// gradient of the total energy with the fluid's at a fixed fluid content), the dry run's bits with
// b = 0 and rho_f = 0, nothing allocated without the effect, and the undrained critical step.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/input_error.hpp"
#include "solver/bond_breakage.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/pore_fluid.hpp"
#include "solver/pressure_change_forces.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

constexpr double kDx = 1e-3;

// make_scene's material (porosity 0.2) with water in its pores.
Scene fluid_scene(int dimension, bool micropolar, double horizon_factor) {
  Scene s = make_scene(dimension, micropolar, kDx, horizon_factor);
  s.effects.pore_fluid = true;
  s.material.pore_fluid = testing::water(1e-12, 0.9);
  return s;
}

// Sets a pressure field p(x) on the body points (the flow reads p).
template <class F>
void set_pressure(Model& m, F&& pressure) {
  const int D = m.dimension();
  for (std::size_t i = 0; i < m.points.owned; ++i) m.points.pore_pressure[i] = pressure(&m.points.position[i * D]);
}

// A linear pressure p = g x: the fluid crossing the plane x = L/2 from the right half into the left
// half is the sum of the left half's rates V_i Phi_i (the pairs inside the half cancel), and Darcy's
// law says k' g A. The lattice is periodic along y (and z), so that every pair across the plane is
// there; along x it is cut more than a horizon away from the plane on both sides.
void check_linear_flux(int dimension, double horizon_factor) {
  const int nx = 16, ny = 8;
  Scene scene = fluid_scene(dimension, false, horizon_factor);
  const std::array<int, 3> n{nx, ny, dimension == 3 ? ny : 1};
  Model m = make_model(make_lattice(dimension, n, kDx, scene.thickness), scene,
                       {0.0, ny * kDx, dimension == 3 ? ny * kDx : 0.0});
  const double gradient = 3e6;  // Pa/m
  set_pressure(m, [&](const double* x) { return gradient * x[0]; });
  fluid_rates(m.points, m.bonds, *m.fluid);
  double into_left = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i)
    if (m.points.position[i * dimension] < 0.5 * nx * kDx) into_left += m.points.volume[i] * m.points.fluid_rate[i];
  const double area = ny * kDx * (dimension == 3 ? ny * kDx : scene.thickness);
  const double darcy = m.fluid->mobility * gradient * area;
  // The calibration makes this exact but for round-off: ~1e-15 per bond sum over a few hundred
  // points' sums of terms of either sign.
  EXPECT_NEAR(into_left, darcy, 1e-12 * darcy) << dimension << "-D, horizon factor " << horizon_factor;
}

TEST(SolverPoreFluid, LinearPressureGivesDarcysFluxExactly2D) { check_linear_flux(2, 3.05); }
TEST(SolverPoreFluid, LinearPressureGivesDarcysFluxExactly3D) { check_linear_flux(3, 2.05); }

// A quadratic pressure p = 1/2 c |x|^2 has lap p = d c: every point with a full family gets
// Phi = k' d c exactly (the odd terms of the family cancel by its symmetry).
void check_quadratic_rate(int dimension, double horizon_factor) {
  Scene scene = fluid_scene(dimension, false, horizon_factor);
  const int side = dimension == 2 ? 13 : 9;
  const std::array<int, 3> n{side, side, dimension == 3 ? side : 1};
  Model m = make_model(make_lattice(dimension, n, kDx, scene.thickness), scene);
  const double c = 4e9;  // Pa/m^2
  set_pressure(m, [&](const double* x) {
    double r2 = 0.0;
    for (int a = 0; a < dimension; ++a) r2 += x[a] * x[a];
    return 0.5 * c * r2;
  });
  fluid_rates(m.points, m.bonds, *m.fluid);
  const double expected = m.fluid->mobility * dimension * c;
  int interior = 0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    if (!testing::is_interior(m, i, n, kDx, scene.geometry.horizon())) continue;
    ++interior;
    // Round-off of sums of pressure differences ~ c L dx against their result c dx^2: 1e-15 L / dx.
    EXPECT_NEAR(m.points.fluid_rate[i], expected, 1e-11 * expected) << "point " << i;
  }
  EXPECT_GT(interior, 0);
}

TEST(SolverPoreFluid, QuadraticPressureGivesMobilityTimesLaplacian2D) { check_quadratic_rate(2, 3.05); }
TEST(SolverPoreFluid, QuadraticPressureGivesMobilityTimesLaplacian3D) { check_quadratic_rate(3, 2.05); }

// A random pressure on a block with impermeable faces: the flow moves fluid between points only,
// so sum V zeta stays as it was (to round-off) over many updates, and each update removes the stored
// energy dt D - M/2 sum V (dt Phi)^2 with the flow's dissipation rate
// D = 1/2 sum_i sum_j kappa0 (p_j - p_i)^2 V_i V_j / |xi| (the explicit update's own identity).
TEST(SolverPoreFluid, FlowConservesTheFluidAndDissipatesItsEnergy) {
  Scene scene = fluid_scene(2, false, 3.05);
  Model m = make_model(make_lattice(2, {12, 9, 1}, kDx, scene.thickness), scene);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    m.points.fluid_content_change[i] += 1e-4 * g(rng);
    m.points.pore_pressure[i] = m.fluid->biot_modulus * m.points.fluid_content_change[i];
  }
  const double volume0 = fluid_volume(m.points, *m.fluid);
  const double dt = 0.5 * fluid_step_limit(m.points, m.bonds, *m.fluid);
  const FluidConstants& fl = *m.fluid;
  for (int step = 0; step < 200; ++step) {
    // The dissipation rate from the pressures before the update.
    double rate = 0.0;
    for (std::size_t i = 0; i < m.points.owned; ++i)
      for (std::int64_t b = m.bonds.offset[i]; b < m.bonds.offset[i + 1]; ++b) {
        const auto j = static_cast<std::size_t>(m.bonds.neighbor[b]);
        double xi[2];
        bond_vector<2>(m.bonds, m.points.position.data(), i, b, xi);
        const double dp = m.points.pore_pressure[j] - m.points.pore_pressure[i];
        rate +=
            0.5 * fl.micro_conductivity * dp * dp * m.points.volume[i] * m.points.volume[j] / std::hypot(xi[0], xi[1]);
      }
    double stored = 0.0;
    for (std::size_t i = 0; i < m.points.owned; ++i)
      stored += m.points.volume[i] * m.points.pore_pressure[i] * m.points.pore_pressure[i] / fl.biot_modulus;
    const double removed = flow_update(m.points, m.bonds, fl, dt);
    double second_order = 0.0;
    for (std::size_t i = 0; i < m.points.owned; ++i) {
      const double dz = dt * m.points.fluid_rate[i];
      second_order += 0.5 * fl.biot_modulus * m.points.volume[i] * dz * dz;
    }
    // The update books the change of sum V p^2 / (2 M): round-off of the stored energy's size (measured
    // 3e-14 of it; dt x rate is 0.3 of it here, so a wrong formula is far outside).
    ASSERT_NEAR(removed, dt * rate - second_order, 1e-13 * stored) << "update " << step;
    ASSERT_GT(removed, 0.0);
  }
  // 200 updates of sums of ~100 terms of size V zeta: round-off ~1e-16 each, relative.
  EXPECT_NEAR(fluid_volume(m.points, *m.fluid), volume0, 1e-13 * volume0);
}

// After a batch of flow updates the forces are corrected by the pressure change alone
// (solver/pressure_change_forces.hpp): the same forces, moments and force tensors as a whole force
// evaluation at the new fluid content, to round-off (1e-10 of the largest: sums of a few hundred
// terms in another order), near the faces and with a broken bond too. Unsaturated (a retention curve,
// under suction), the correction is that of Bishop's pore stress S_r(p) p, which is not linear in p.
void check_pressure_change_forces(int dimension, std::array<int, 3> n, double horizon_factor,
                                  bool unsaturated = false) {
  Scene scene = fluid_scene(dimension, true, horizon_factor);
  if (unsaturated) {
    scene.material.pore_fluid->retention = RetentionParameters{"van_genuchten", 1e4, 2.0, 0.1};
    scene.material.pore_fluid->initial_pressure = -5e3;
  }
  scene.effects.damage = true;
  scene.material.damage = DamageParameters{};
  Model m = make_model(make_lattice(dimension, n, kDx, scene.thickness), scene);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& u : m.points.displacement) u = 1e-4 * kDx * g(rng);
  for (auto& w : m.points.rotation) w = 1e-4 * g(rng);
  // (Under suction the capacity is ~1e-5 / Pa, not 1/M: a larger change of content moves p as much.)
  for (auto& z : m.points.fluid_content_change) z += (unsaturated ? 1e-3 : 1e-5) * g(rng);
  const std::size_t k = 7;  // a bond broken at point 7
  m.bonds.break_bond(mirror_bond(m.bonds, k, static_cast<std::size_t>(m.bonds.neighbor[m.bonds.offset[k]])));
  m.bonds.break_bond(m.bonds.offset[k]);
  m.compute_internal_forces(false);
  const std::vector<double> before = m.points.pore_pressure;
  flow_update(m.points, m.bonds, *m.fluid, 0.5 * fluid_step_limit(m.points, m.bonds, *m.fluid));
  add_pressure_change_forces(m.points, m.bonds, m.constants, before);
  const PointData corrected = m.points;
  m.compute_internal_forces(false);
  auto expect_close = [&](const std::vector<double>& a, const std::vector<double>& b, const char* what) {
    double scale = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      scale = std::max(scale, std::abs(b[i]));
      worst = std::max(worst, std::abs(a[i] - b[i]));
    }
    EXPECT_LT(worst, 1e-10 * scale) << dimension << "-D " << what;
  };
  expect_close(corrected.force, m.points.force, "force");
  expect_close(corrected.moment, m.points.moment, "moment");
  expect_close(corrected.force_tensor, m.points.force_tensor, "force tensor");
  // The check can fail: the pressure change moved the forces by far more than that.
  double moved = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i)
    moved = std::max(moved, std::abs(m.points.pore_pressure[i] - before[i]));
  for (double p : before) scale = std::max(scale, std::abs(p));
  EXPECT_GT(moved, 1e-3 * scale);
}

TEST(SolverPoreFluid, PressureChangeCorrectsTheForcesAsAnEvaluation2D) {
  check_pressure_change_forces(2, {10, 8, 1}, 3.05);
}
TEST(SolverPoreFluid, PressureChangeCorrectsTheForcesAsAnEvaluation3D) {
  check_pressure_change_forces(3, {6, 5, 5}, 2.05);
}
TEST(SolverPoreFluid, PressureChangeCorrectsTheForcesAsAnEvaluationUnsaturated) {
  check_pressure_change_forces(2, {10, 8, 1}, 3.05, true);
}

// A hydrostatic start (docs/theory.md section 12) is the fluid at rest: its potential p - rho_f g . x
// is the same at every point, so no point has a rate (to round-off of p), near the faces too.
TEST(SolverPoreFluid, HydrostaticStartHasNoFlow) {
  Scene scene = fluid_scene(2, false, 3.05);
  scene.effects.gravity = true;
  scene.gravity = {0.0, -9.81, 0.0};
  const double level = 0.02;  // above the 9 mm block: p > 0 everywhere
  scene.material.pore_fluid->free_surface = level;
  Model m = make_model(make_lattice(2, {12, 9, 1}, kDx, scene.thickness), scene);
  double largest_p = 0.0, conductance = 0.0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double y = m.points.position[2 * i + 1];
    EXPECT_NEAR(m.points.pore_pressure[i], 1000.0 * 9.81 * (level - y), 1e-9);
    largest_p = std::max(largest_p, m.points.pore_pressure[i]);
  }
  for (std::int64_t b = m.bonds.offset[0]; b < m.bonds.offset[1]; ++b) conductance += 1e-9 / kDx;  // V / |xi| <= this
  fluid_rates(m.points, m.bonds, *m.fluid);
  // Sums of ~30 potential differences, each the difference of two ~200 Pa values rounded at 1e-16.
  for (std::size_t i = 0; i < m.points.owned; ++i)
    EXPECT_LT(std::abs(m.points.fluid_rate[i]), 1e-13 * m.fluid->micro_conductivity * conductance * largest_p) << i;
  // A constant start of the same mean pressure is not at rest: the check can fail.
  Scene constant = scene;
  constant.material.pore_fluid->free_surface.reset();
  constant.material.pore_fluid->initial_pressure = largest_p;
  Model c = make_model(make_lattice(2, {12, 9, 1}, kDx, scene.thickness), constant);
  fluid_rates(c.points, c.bonds, *c.fluid);
  double moving = 0.0;
  for (double r : c.points.fluid_rate) moving = std::max(moving, std::abs(r));
  EXPECT_GT(moving, 1e-6 * m.fluid->micro_conductivity * conductance * largest_p);
}

// A detached point (every bond broken, as damage leaves it) keeps its fluid through the flow updates,
// its pressure relaxes to that of its own fluid at no strain, and the update books nothing for it:
// it stores no energy (the energy rows leave it out).
TEST(SolverPoreFluid, DetachedPointKeepsItsFluid) {
  Scene scene = fluid_scene(2, false, 3.05);
  scene.effects.damage = true;
  scene.material.damage = DamageParameters{};
  Model m = make_model(make_lattice(2, {9, 9, 1}, kDx, scene.thickness), scene);
  const std::size_t k = 40;  // the middle point
  for (std::int64_t b = m.bonds.offset[k]; b < m.bonds.offset[k + 1]; ++b) {
    const auto j = static_cast<std::size_t>(m.bonds.neighbor[b]);
    m.bonds.break_bond(mirror_bond(m.bonds, k, j));
    m.bonds.break_bond(b);
  }
  m.points.detached[k] = 1;
  m.points.fluid_content_change[k] = 1e-4;
  m.points.pore_pressure[k] = 7e5;
  const double removed = flow_update(m.points, m.bonds, *m.fluid, 1e-9);
  EXPECT_EQ(m.points.fluid_content_change[k], 1e-4);
  EXPECT_DOUBLE_EQ(m.points.pore_pressure[k], m.fluid->biot_modulus * 1e-4);
  EXPECT_EQ(removed, 0.0);  // every other point is at rest with p = 0
}

// The pass-1 pressure of a uniform volumetric strain e (d e = tr eps) at the initial fluid
// content n0 + p0 / M: p = p0 - b M d e at every point with a full family (where eps is exact).
TEST(SolverPoreFluid, UndrainedPressureFollowsTheVolumetricStrain) {
  Scene scene = fluid_scene(2, true, 3.05);
  scene.material.pore_fluid->initial_pressure = 150e3;
  const std::array<int, 3> n{13, 13, 1};
  Model m = make_model(make_lattice(2, n, kDx, scene.thickness), scene);
  const double e = -2e-4;  // compression
  for (std::size_t i = 0; i < m.points.owned; ++i)
    for (int a = 0; a < 2; ++a) m.points.displacement[i * 2 + a] = e * m.points.position[i * 2 + a];
  m.compute_internal_forces(false);
  const double expected = 150e3 - 0.9 * 2e9 * 2.0 * e;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    if (testing::is_interior(m, i, n, kDx, scene.geometry.horizon())) {
      EXPECT_NEAR(m.points.pore_pressure[i], expected, 1e-9 * expected) << "point " << i;
    }
  }
}

// Forces and moments are minus the gradient of the total energy, the fluid's V p^2 / (2 M) with
// p = M (zeta - n0 - b tr eps) included, at a fixed fluid content (central differences, exact for
// a quadratic energy up to round-off; the tolerance as in test_solver_energy_gradient.cpp).
void check_fluid_gradient(int dimension, std::array<int, 3> n, double horizon_factor) {
  Scene scene = fluid_scene(dimension, true, horizon_factor);
  scene.material.pore_fluid->initial_pressure = 1e6;
  Model m = make_model(make_lattice(dimension, n, kDx, scene.thickness), scene);
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& u : m.points.displacement) u = 1e-4 * kDx * g(rng);
  for (auto& w : m.points.rotation) w = 1e-4 * g(rng);
  for (auto& z : m.points.fluid_content_change) z += 1e-5 * g(rng);
  auto energy = [&] {
    m.compute_internal_forces(true);
    return internal_energy(m).total();
  };
  energy();
  ASSERT_GT(internal_energy(m).fluid, 0.1 * internal_energy(m).total()) << "the fluid's energy must count";
  const std::vector<double> force = m.points.force;
  double scale = 0.0;
  for (std::size_t k = 0; k < force.size(); ++k)
    scale = std::max(scale, std::abs(force[k]) * m.points.volume[k / static_cast<std::size_t>(dimension)]);
  for (std::size_t k = 0; k < force.size(); ++k) {
    const double h = 1e-6 * kDx;
    const double saved = m.points.displacement[k];
    m.points.displacement[k] = saved + h;
    const double ep = energy();
    m.points.displacement[k] = saved - h;
    const double em = energy();
    m.points.displacement[k] = saved;
    const double fd = -(ep - em) / (2.0 * h);
    ASSERT_NEAR(force[k] * m.points.volume[k / static_cast<std::size_t>(dimension)], fd, 1e-7 * scale)
        << dimension << "-D, component " << k;
  }
}

TEST(SolverPoreFluid, ForcesAreMinusTheGradientOfTheEnergyWithTheFluid2D) { check_fluid_gradient(2, {7, 6, 1}, 3.05); }
TEST(SolverPoreFluid, ForcesAreMinusTheGradientOfTheEnergyWithTheFluid3D) { check_fluid_gradient(3, {5, 4, 4}, 2.05); }

// 60 steps of a free vibration from a random displacement: the positions after them, bit for bit.
std::vector<double> vibrate(Model& m, double dt) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& u : m.points.displacement) u = 1e-5 * kDx * g(rng);
  for (auto& w : m.points.rotation) w = 1e-5 * g(rng);
  const BoundaryConditions none(m.points);
  ExplicitDynamics dynamics(m, none, dt);
  dynamics.initialize();
  for (int k = 0; k < 60; ++k) dynamics.step(k % 10 == 0);
  std::vector<double> state = m.points.displacement;
  state.insert(state.end(), m.points.rotation.begin(), m.points.rotation.end());
  return state;
}

// With b = 0 and rho_f = 0 the fluid exerts nothing on the skeleton and adds no mass: the mechanics
// are the dry run's, to the bit (the scene reader refuses b = 0; the model takes it).
TEST(SolverPoreFluid, ZeroBiotCoefficientAndFluidDensityGiveTheDryBits) {
  const Scene dry_scene = make_scene(2, true, kDx, 3.05);
  Scene wet_scene = fluid_scene(2, true, 3.05);
  wet_scene.material.pore_fluid->biot_coefficient = 0.0;
  wet_scene.material.pore_fluid->fluid_density = 0.0;
  const PointCloud cloud = make_lattice(2, {10, 8, 1}, kDx, dry_scene.thickness);
  Model dry = make_model(cloud, dry_scene);
  Model wet = make_model(cloud, wet_scene);
  const double dt = 0.5 * critical_time_step(dry).step;
  EXPECT_EQ(critical_time_step(wet).step, 2.0 * dt);
  EXPECT_EQ(vibrate(dry, dt), vibrate(wet, dt));
}

// Without the effect nothing of the fluid is allocated.
TEST(SolverPoreFluid, NothingOfTheFluidWithoutTheEffect) {
  Scene scene = fluid_scene(2, true, 3.05);
  scene.effects.pore_fluid = false;
  Model m = make_model(make_lattice(2, {8, 8, 1}, kDx, scene.thickness), scene);
  EXPECT_FALSE(m.fluid);
  EXPECT_TRUE(m.points.pore_pressure.empty());
  EXPECT_TRUE(m.points.fluid_content_change.empty());
  EXPECT_TRUE(m.points.fluid_rate.empty());
  EXPECT_EQ(m.constants.density, scene.material.partial_density());
}

// Held in the pores, the fluid stiffens the skeleton: its response at a fixed fluid content is the
// dry skeleton's with lambda + b^2 M (exactly so without the stabilization, which depends on lambda),
// over the mixture density. The critical steps of the two agree to the Lanczos tolerance.
TEST(SolverPoreFluid, CriticalStepIsTheUndrainedOne) {
  Scene wet_scene = fluid_scene(2, false, 3.05);
  wet_scene.numerics.stabilization = 0.0;
  wet_scene.material.pore_fluid->initial_pressure = 3e5;  // must not enter the operator
  Scene dry_scene = wet_scene;
  dry_scene.effects.pore_fluid = false;
  const double b = wet_scene.material.pore_fluid->biot_coefficient,
               modulus = wet_scene.material.pore_fluid->biot_modulus;
  dry_scene.material.lambda += b * b * modulus;
  dry_scene.material.density +=
      wet_scene.material.porosity() * wet_scene.material.pore_fluid->fluid_density / wet_scene.material.solid_fraction;
  const PointCloud cloud = make_lattice(2, {10, 9, 1}, kDx, wet_scene.thickness);
  Model wet = make_model(cloud, wet_scene);
  Model dry = make_model(cloud, dry_scene);
  const std::vector<double> fluid_content = wet.points.fluid_content_change;
  const CriticalTimeStep w = critical_time_step(wet), d = critical_time_step(dry);
  EXPECT_NEAR(w.step, d.step, 1e-6 * d.step);
  EXPECT_NE(w.driver.find("biot_modulus"), std::string::npos) << w.driver;
  // A given step above it is refused, naming the Biot modulus that drives it.
  wet_scene.time.step = 1.01 * w.step;
  try {
    choose_time_step(wet_scene, w);
    ADD_FAILURE() << "a step above the undrained critical step was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material.pore_fluid.biot_modulus"), std::string::npos) << e.what();
  }
  // And the estimate left the fluid as it was.
  EXPECT_EQ(wet.points.fluid_content_change, fluid_content);
}

}  // namespace
}  // namespace mppm::solver
