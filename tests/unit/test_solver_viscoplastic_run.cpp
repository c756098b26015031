// The viscoplasticity effect in mppm-solve: an effect that is on with an unreachable
// cohesion reproduces the run without it bit for bit; plastic runs are bitwise identical on 1
// and 2 threads; the critical step stays the elastic one; plastic fields are written only with
// the effect; a bad model name is bad input naming the key.
#include <gtest/gtest.h>
#include <omp.h>

#include <filesystem>
#include <random>

#include "common/input_error.hpp"
#include "common/snapshot_file.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/plasticity/material_registry.hpp"
#include "solver/snapshot_fields.hpp"
#include "solver/solve_run.hpp"
#include "tests/verification/solver_viscoplastic_cases.hpp"

namespace mppm::solver {
namespace {

namespace fs = std::filesystem;
using namespace testing;

SolveOptions options_for(const std::string& dir) {
  SolveOptions o;
  o.run_directory = dir;
  o.points_file = "compression.vtp";
  return o;
}

// Every file of two run directories that both have, compared byte for byte (run_info.json and
// log.txt hold wall times and effect names, so they are left out).
void expect_identical_runs(const std::string& a, const std::string& b, bool compare_energy) {
  EXPECT_EQ(read_text(a + "/" + run_layout::load), read_text(b + "/" + run_layout::load));
  if (compare_energy) {
    EXPECT_EQ(read_text(a + "/" + run_layout::energy), read_text(b + "/" + run_layout::energy));
  }
  int compared = 0;
  for (const auto& e : fs::directory_iterator(fs::path(a) / run_layout::snapshot_dir)) {
    const fs::path other = fs::path(b) / run_layout::snapshot_dir / e.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_EQ(read_text(e.path().string()), read_text(other.string())) << e.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 3);
}

// A short, violent version of the compression case (strain rate 100/s, layers at up to 1 m/s):
// plastic within a few hundred steps.
CompressionCase short_case() {
  CompressionCase c = compression_case(10, 10, 1e-4, 100.0, 1e3);
  c.scene.output.interval = 2.5e-5;
  return c;
}

// The kernel's per-point update is the material-point update of solver/plasticity with the
// kernel's own strain and wryness (2-D and 3-D, micropolar): same state bit for bit (the storage
// layouts agree: 3 x 3 eps_vp with zz in 2-D, row-major kap_vp), the stress the force pass uses
// is the returned one, and from a zero strain the trapezoid dissipation is 1/2 V sigma_1 : d eps_vp.
void check_kernel_update_matches_material_point(int dimension) {
  constexpr double dx = 1e-3;
  Scene scene = make_scene(dimension, true, dx, 2.05);
  scene.effects.viscoplasticity = true;
  ViscoplasticParameters vp;
  vp.friction_angle = 30.0 * kDeg;
  vp.dilatancy_angle = 10.0 * kDeg;
  vp.cohesion = 0.2e6;
  vp.hardening = -5e6;
  vp.residual_cohesion = 2e3;
  vp.viscosity = 10.0;
  scene.material.viscoplasticity = vp;
  const PointCloud cloud = make_lattice(dimension, {7, 7, 7}, dx, scene.thickness);
  Model m = build_model(cloud, model_options(scene));
  m.compute_internal_forces();  // zero strain: the start of the step
  // A random smooth field: compression plus shear in u, a linear micro-rotation field.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const int D = dimension, R = m.points.rotation_components;
  double grad_u[3][3], grad_w[3][3];
  for (auto& row : grad_u)
    for (double& v : row) v = 2e-3 * r(rng);
  grad_u[0][0] = 8e-3;  // in-plane pure shear: far outside the cone (compression alone is not)
  grad_u[1][1] = -8e-3;
  for (auto& row : grad_w)
    for (double& v : row) v = 2.0 * r(rng);  // [1/m]: kap ~ 2/m, l kap ~ 4e-3
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double* x = &m.points.position[i * D];
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) m.points.displacement[i * D + a] += grad_u[a][b] * x[b];
    for (int a = 0; a < R; ++a)
      for (int b = 0; b < D; ++b) m.points.rotation[i * R + a] += grad_w[a][b] * x[b];
  }
  const double dt = 1e-7;
  m.advance_internal_forces(dt, dt, true);
  const Snapshot s = make_snapshot(m, {"stress", "plastic_strain", "equivalent_plastic_strain"}, 1, dt);
  const auto& stress = s.find("stress")->data;
  const auto* model = m.viscoplastic_model.get();
  int plastic = 0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    Eigen::Matrix3d eps = Eigen::Matrix3d::Zero();
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) eps(a, b) = m.points.strain[i * D * D + a * D + b];
    const double* kap = &m.points.wryness[i * R * D];
    Eigen::Matrix3d expected_vp, sigma;
    double expected_ebar, dissipation;
    if (dimension == 2) {
      const auto u =
          model->update(eps, Eigen::Vector2d(kap[0], kap[1]), model->initial_state_2d(),
                        {m.constants.lambda, m.constants.mu, m.constants.mu_c, m.constants.bending_modulus}, dt);
      expected_vp = u.state.plastic_strain;
      expected_ebar = u.state.equivalent_plastic_strain;
      sigma = u.stress;
      dissipation = u.dissipation;
      plastic += u.plastic;
      EXPECT_EQ(m.points.plastic_wryness[i * 2], u.state.plastic_wryness[0]);
      EXPECT_EQ(m.points.plastic_wryness[i * 2 + 1], u.state.plastic_wryness[1]);
    } else {
      Eigen::Matrix3d k;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) k(a, b) = kap[a * 3 + b];
      const auto u = model->update(
          eps, k, model->initial_state_3d(),
          {m.constants.lambda, m.constants.mu, m.constants.mu_c, m.constants.a1, m.constants.a2, m.constants.a3}, dt);
      expected_vp = u.state.plastic_strain;
      expected_ebar = u.state.equivalent_plastic_strain;
      sigma = u.stress;
      dissipation = u.dissipation;
      plastic += u.plastic;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          EXPECT_EQ(m.points.plastic_wryness[i * 9 + a * 3 + b], u.state.plastic_wryness(a, b));
    }
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        ASSERT_EQ(m.points.plastic_strain[i * 9 + a * 3 + b], expected_vp(a, b)) << i << " " << a << b;
        // Round-off of two orderings of the same elastic law.
        ASSERT_NEAR(stress[i * 9 + a * 3 + b], sigma(a, b), 1e-9 * sigma.norm()) << i << " " << a << b;
      }
    EXPECT_EQ(m.points.equivalent_plastic_strain[i], expected_ebar);
    // sigma_0 = 0: the trapezoid gives half the right-point value.
    EXPECT_NEAR(m.points.plastic_dissipation[i], 0.5 * m.points.volume[i] * dissipation,
                1e-12 * m.points.volume[i] * std::abs(dissipation) + 1e-300);
  }
  // Most points flow (the check is not on an elastic state).
  EXPECT_GT(plastic, static_cast<int>(m.points.owned) / 2);
}

TEST(SolverViscoplasticKernel, PointUpdateIsTheMaterialPointReturnIn2D) {
  check_kernel_update_matches_material_point(2);
}
TEST(SolverViscoplasticKernel, PointUpdateIsTheMaterialPointReturnIn3D) {
  check_kernel_update_matches_material_point(3);
}

TEST(SolverViscoplasticRun, UnreachableCohesionGivesTheElasticRunBitForBit) {
  CompressionCase on = short_case();
  on.scene.material.viscoplasticity->cohesion = 1e15;
  on.scene.material.viscoplasticity->residual_cohesion = 1e13;
  on.scene.output.fields = {"displacement", "rotation", "velocity", "stress", "couple_stress", "strain"};
  CompressionCase off = on;
  off.scene.effects.viscoplasticity = false;
  off.scene.material.viscoplasticity.reset();
  const std::string a = fresh_run_directory("unreachable_on"), b = fresh_run_directory("unreachable_off");
  const SolveResult ra = solve(on.scene, on.cloud, options_for(a));
  const SolveResult rb = solve(off.scene, off.cloud, options_for(b));
  EXPECT_EQ(ra.time_step, rb.time_step);
  EXPECT_EQ(ra.critical_time_step, rb.critical_time_step);
  // energy.csv too: the dissipation column is 0 in both.
  expect_identical_runs(a, b, true);
}

// material.viscoplasticity.region: outside the box the points stay elastic (no plastic strain at
// all), inside they flow as without a region.
TEST(SolverViscoplasticRun, RegionLimitsFlowToItsBox) {
  CompressionCase c = short_case();
  const double x_cut = 0.5 * c.width;
  Selector left;
  left.box = std::array<std::array<double, 3>, 2>{{{-1.0, -1.0, -1.0}, {x_cut, 1.0, 1.0}}};
  c.scene.material.viscoplasticity->region = left;
  c.scene.output.fields = {"equivalent_plastic_strain"};
  const std::string dir = fresh_run_directory("region");
  solve(c.scene, c.cloud, options_for(dir));
  // The last snapshot (the names sort by step).
  std::string last;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / run_layout::snapshot_dir))
    last = std::max(last, e.path().string());
  const Snapshot s = read_snapshot(last);
  const SnapshotField* ebar = s.find("equivalent_plastic_strain");
  ASSERT_NE(ebar, nullptr);
  std::size_t flowing_inside = 0, inside = 0;
  for (std::size_t i = 0; i < c.cloud.x.size(); ++i) {
    if (c.cloud.x[i] > x_cut) {
      ASSERT_EQ(ebar->data[i], 0.0) << "point " << i << " outside the region flowed";
    } else {
      ++inside;
      if (ebar->data[i] > 0.0) ++flowing_inside;
    }
  }
  // The short case flows nearly everywhere without a region (PointUpdateIsTheMaterialPointReturn
  // checks more than half): inside the region it still does.
  EXPECT_GT(flowing_inside, inside / 2);
}

TEST(SolverViscoplasticRun, PlasticRunIsBitwiseIdenticalOnOneAndTwoThreads) {
  const ParallelThresholds saved_thresholds = parallel_thresholds();
  parallel_thresholds() = ParallelThresholds{1, 1, 1};  // every loop threaded, even on this lattice
  CompressionCase c = short_case();
  c.scene.material.viscoplasticity->hardening = -20e6;  // softening: the most sensitive case
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::string one = fresh_run_directory("threads1");
  solve(c.scene, c.cloud, options_for(one));
  omp_set_num_threads(2);
  const std::string two = fresh_run_directory("threads2");
  solve(c.scene, c.cloud, options_for(two));
  omp_set_num_threads(saved);
  parallel_thresholds() = saved_thresholds;
  expect_identical_runs(one, two, true);
  // The comparison is on a run that did flow.
  const auto energy = read_csv_rows(one + "/" + run_layout::energy);
  EXPECT_GT(energy.back()[5], 0.0);
}

TEST(SolverViscoplasticRun, CriticalStepIsTheElasticOne) {
  // The plastic parameters do not enter the step: plastic flow only lowers the tangent stiffness.
  CompressionCase soft = short_case();
  CompressionCase elastic = soft;
  elastic.scene.effects.viscoplasticity = false;
  elastic.scene.material.viscoplasticity.reset();
  soft.scene.material.viscoplasticity->cohesion = 1e3;  // yields at once
  soft.scene.material.viscoplasticity->residual_cohesion = 10.0;
  const SolveResult a = solve(soft.scene, soft.cloud, options_for(fresh_run_directory("step_soft")));
  const SolveResult b = solve(elastic.scene, elastic.cloud, options_for(fresh_run_directory("step_elastic")));
  EXPECT_EQ(a.critical_time_step, b.critical_time_step);
  EXPECT_EQ(a.time_step, b.time_step);
}

TEST(SolverViscoplasticRun, PlasticFieldsOnlyWithTheEffect) {
  CompressionCase c = short_case();
  const std::string dir = fresh_run_directory("fields");
  solve(c.scene, c.cloud, options_for(dir));
  const Snapshot s = read_snapshot(dir + "/" + run_layout::snapshot_dir + "/" + run_layout::snapshot_name(0));
  ASSERT_NE(s.find("plastic_strain"), nullptr);
  EXPECT_EQ(s.find("plastic_strain")->components, 9);
  ASSERT_NE(s.find("plastic_shear_strain"), nullptr);
  EXPECT_EQ(s.find("plastic_shear_strain")->components, 1);
  ASSERT_NE(s.find("equivalent_plastic_strain"), nullptr);
  CompressionCase off = c;
  off.scene.effects.viscoplasticity = false;
  off.scene.material.viscoplasticity.reset();
  const std::string dir_off = fresh_run_directory("fields_off");
  solve(off.scene, off.cloud, options_for(dir_off));
  const Snapshot t = read_snapshot(dir_off + "/" + run_layout::snapshot_dir + "/" + run_layout::snapshot_name(0));
  EXPECT_EQ(t.find("plastic_strain"), nullptr);
  EXPECT_EQ(t.find("plastic_shear_strain"), nullptr);
  const std::string log = read_text(dir_off + "/" + run_layout::log);
  EXPECT_NE(log.find("'plastic_strain' is not produced"), std::string::npos);
}

TEST(SolverViscoplasticRun, UnknownModelNameIsBadInputNamingTheKey) {
  CompressionCase c = short_case();
  c.scene.material.viscoplasticity->model = "cam-clay";
  try {
    solve(c.scene, c.cloud, options_for(fresh_run_directory("bad_model")));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("material.viscoplasticity.model"), std::string::npos) << m;
    EXPECT_NE(m.find("drucker-prager-perzyna"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace mppm::solver
