// The unsaturated pore fluid in the solver (docs/theory.md section 12, "Unsaturated (retention)"):
// the force pass recovers p from the fluid content by the retention inverse and adds Bishop's pore
// stress -b S_r p 1 (against the dry skeleton's force tensors); with a retention curve and p >= 0
// throughout, a coupled run is the saturated run to the bit; and a coupled run under suction keeps its
// fluid to round-off and closes its energy balance to round-off, with the stored fluid energy booked as
// the work the fluid received.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/explicit_dynamics.hpp"
#include "solver/pore_fluid.hpp"
#include "solver/symmetric_tensor.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

constexpr double kDx = 1e-3;
const RetentionParameters kLoam{"van_genuchten", 1e4, 2.0, 0.1};

// make_scene's skeleton (porosity 0.2) with water in its pores, under the retention curve kLoam.
Scene unsaturated_scene(double initial_pressure) {
  Scene s = make_scene(2, true, kDx, 3.05);
  s.effects.pore_fluid = true;
  s.material.pore_fluid = testing::water(1e-12, 0.9, initial_pressure);
  s.material.pore_fluid->retention = kLoam;
  return s;
}

// Random displacements, rotations and fluid contents (around the start's) of a 10 x 8 block.
void disturb(Model& m, double content_amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& u : m.points.displacement) u = 1e-4 * kDx * g(rng);
  for (auto& w : m.points.rotation) w = 1e-4 * g(rng);
  for (auto& z : m.points.fluid_content_change) z += content_amplitude * g(rng);
}

// Each body point's force tensor A_i = sigma_i K_i^-1 - G_s (C:K_i^-1) eps_i differs from the dry
// skeleton's by -b S_r(p_i) p_i K_i^-1, with p_i the pressure whose content at the point's volumetric
// strain is the one held (the inverse to round-off: 1e-12 of the content's change).
TEST(SolverUnsaturated, ForcePassAddsBishopsPoreStress) {
  const Scene scene = unsaturated_scene(-1e3);
  Scene dry_scene = scene;
  dry_scene.effects.pore_fluid = false;
  dry_scene.material.pore_fluid.reset();
  Model m = make_model(make_lattice(2, {10, 8, 1}, kDx, scene.thickness), scene);
  Model dry = make_model(make_lattice(2, {10, 8, 1}, kDx, scene.thickness), dry_scene);
  disturb(m, 3e-3, 3);
  dry.points.displacement = m.points.displacement;
  dry.points.rotation = m.points.rotation;
  m.compute_internal_forces(false);
  dry.compute_internal_forces(false);
  const RetentionCurve curve = *retention_curve(*scene.material.pore_fluid);
  const FluidStorage storage{scene.material.porosity(), 0.9, 2e9};
  int saturated = 0, unsaturated = 0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double p = m.points.pore_pressure[i];
    const double* eps = &m.points.strain[i * 4];
    const double eps_v = eps[0] + eps[3];
    const double content = m.points.fluid_content_change[i];
    ASSERT_NEAR(fluid_content_change(curve, storage, p, eps_v), content, 1e-12 * std::abs(content)) << i;
    (p < 0.0 ? unsaturated : saturated)++;
    const Eigen::Matrix2d kinv = unpack_symmetric<2>(&m.points.shape_inverse[i * 3]);
    const double stress = 0.9 * saturation(curve, p) * p;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double with_fluid = m.points.force_tensor[i * 4 + a * 2 + b];
        const double without = dry.points.force_tensor[i * 4 + a * 2 + b];
        // The two tensors are rounded at 1e-16 of their size; their difference keeps that.
        const double rounding = 1e-14 * std::max(std::abs(with_fluid), std::abs(without));
        EXPECT_NEAR(with_fluid - without, -stress * kinv(a, b), rounding + 1e-12 * std::abs(stress * kinv(a, b))) << i;
      }
  }
  // Both branches of the inverse were taken (the content's spread crosses saturation).
  EXPECT_GT(unsaturated, 10);
  EXPECT_GT(saturated, 10);
}

// A free block with a bump of fluid; ExplicitDynamics with explicit flow substeps fixed at the start's
// limit (under suction the capacity only grows as the bump spreads and the skeleton swells).
struct BlockRun {
  std::vector<double> displacement, pressure;
  double worst_balance = 0.0, volume_change = 0.0, stored_fluid = 0.0, initial_total = 0.0;
  double flow_dissipation = 0.0, kinetic = 0.0;
};

BlockRun run_block(const Scene& scene, double content_amplitude, double dt, int steps) {
  Model m = make_model(make_lattice(2, {16, 12, 1}, kDx, scene.thickness), scene);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double dx = m.points.position[2 * i] - 8 * kDx, dy = m.points.position[2 * i + 1] - 6 * kDx;
    m.points.fluid_content_change[i] += content_amplitude * std::exp(-(dx * dx + dy * dy) / (4 * kDx * kDx));
  }
  const BoundaryConditions none(m.points);
  ExplicitDynamics dynamics(m, none, dt);
  dynamics.set_flow_schedule(
      flow_schedule(fluid_step_limit(m.points, m.bonds, *m.fluid), dt, FlowIntegration::explicit_substeps));
  dynamics.initialize();
  const double volume0 = dynamics.energy().fluid_volume;
  BlockRun r;
  for (int k = 0; k < steps; ++k) {
    dynamics.step(true);
    r.worst_balance = std::max(r.worst_balance, std::abs(dynamics.balance_error()));
  }
  r.displacement = m.points.displacement;
  r.pressure = m.points.pore_pressure;
  r.volume_change = (dynamics.energy().fluid_volume - volume0) / volume0;
  r.stored_fluid = dynamics.energy().fluid_stored;
  r.initial_total = dynamics.initial_total_energy();
  r.flow_dissipation = dynamics.energy().flow_dissipation;
  r.kinetic = dynamics.energy().kinetic;
  return r;
}

// With p >= 0 everywhere S_r = 1, k_r = 1 and the inverse is the saturated formula: the retention
// curve must then change nothing of the motion or the pressures, to the bit.
TEST(SolverUnsaturated, SaturatedThroughoutIsTheSaturatedRun) {
  Scene scene = unsaturated_scene(2e5);
  scene.material.pore_fluid->permeability = 1e-9;
  const BlockRun with_curve = run_block(scene, 1e-5, 2e-8, 200);
  scene.material.pore_fluid->retention.reset();
  const BlockRun saturated = run_block(scene, 1e-5, 2e-8, 200);
  for (double p : with_curve.pressure) ASSERT_GE(p, 0.0);
  EXPECT_EQ(with_curve.displacement, saturated.displacement);
  EXPECT_EQ(with_curve.pressure, saturated.pressure);
  // The stored fluid energy of the curve's run counts from the start; the saturated one's is
  // V p^2 / (2M) with the start's included. Their changes agree to the trapezoid rule's error on
  // the undrained updates, which is exact for p linear in the strain: round-off.
  EXPECT_LT(with_curve.worst_balance, 1e-12);
}

// Under suction a bump of fluid spreads and the skeleton swells: no fluid crosses a face (round-off),
// and the energy balance closes with the stored fluid energy booked as the work the fluid received.
// The trapezoid rule on each step's strain change (~1e-9) errs at its cube, far below round-off, so the
// balance closes to round-off (measured 7e-15 and 1e-14); booking the pore stress as b p instead of
// Bishop's b S_r p (S_r ~ 0.9 here) would leave ~10 % of the fluid's work, the size of the energies.
TEST(SolverUnsaturated, CoupledRunUnderSuctionKeepsItsBooks) {
  Scene scene = unsaturated_scene(-5e3);
  scene.material.pore_fluid->permeability = 1e-9;
  const BlockRun coarse = run_block(scene, 2e-3, 2e-8, 300), fine = run_block(scene, 2e-3, 1e-8, 600);
  std::printf(
      "unsaturated bump: balance %.3e (2e-8 s) %.3e (1e-8 s), flow dissipation %.3e J, stored fluid %.3e J, "
      "kinetic %.3e J\n",
      coarse.worst_balance, fine.worst_balance, coarse.flow_dissipation, coarse.stored_fluid, coarse.kinetic);
  EXPECT_LT(std::abs(coarse.volume_change), 1e-13);
  EXPECT_LT(std::abs(fine.volume_change), 1e-13);
  EXPECT_GT(coarse.flow_dissipation, 0.01 * coarse.initial_total) << "the flow must count";
  EXPECT_GT(coarse.kinetic, 0.1 * coarse.flow_dissipation) << "the skeleton must move";
  EXPECT_GT(std::abs(coarse.stored_fluid), coarse.flow_dissipation) << "the fluid's work must count";
  EXPECT_LT(coarse.worst_balance, 1e-12);
  EXPECT_LT(fine.worst_balance, 1e-12);
}

}  // namespace
}  // namespace mppm::solver
