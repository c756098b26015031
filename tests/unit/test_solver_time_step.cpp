// The critical time step (docs/theory.md section 9): the Lanczos (refined power-iteration) estimate is the
// real stability limit of the scheme, and a given step above it is refused with a message naming
// the mode and the parameter. workflows/shear-band/README.md as printed (a3 = 83.3 kN) must be refused at dt = 7 us;
// with the corrected a3 = 83.3 N it is accepted.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/point_stability.hpp"
#include "tests/unit/stage_process.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

// workflows/shear-band/README.md material on a small lattice of its spacing and horizon.
Scene shear_band_scene(double a3) {
  Scene s;
  s.path = "case1.yaml";
  s.dimension = 2;
  s.thickness = 0.01;
  s.geometry.spacing = 2.5e-3;
  s.geometry.horizon_factor = 2.05;
  s.material.density = 2000.0;
  s.material.solid_fraction = 0.65;
  s.material.lambda = 13.9e6;
  s.material.mu = 20.8e6;
  s.material.mu_c = 2 * 20.8e6;
  s.material.couple_moduli = {0.0, 0.0, a3};
  s.material.length_scale = 2e-3;
  s.effects.micropolar = true;
  s.time.end = 0.1;
  s.time.step = 7e-6;
  return s;
}

// The 3-D benchmark block's rock (workflows/benchmarks/scenes/block.yaml).
Scene rock_block() {
  Scene s = make_scene(3, true, 1e-3, 2.05);
  s.material.density = 2650.0;
  s.material.solid_fraction = 0.95;
  s.material.lambda = 14e9;
  s.material.mu = 14e9;
  s.material.mu_c = 4.667e9;
  s.material.couple_moduli = {11.2e3, 56e3, 16.8e3};
  s.material.length_scale = 2e-3;
  return s;
}

TEST(SolverTimeStep, CaseOneWithA3InNewtonIsAccepted) {
  const Scene s = shear_band_scene(83.3);
  Model m = make_model(make_lattice(2, {12, 12, 1}, 2.5e-3, 0.01), s);
  const CriticalTimeStep c = critical_time_step(m);
  EXPECT_GT(c.step, 7e-6);
  EXPECT_DOUBLE_EQ(choose_time_step(s, c), 7e-6);
}

TEST(SolverTimeStep, CaseOneWithMisprintedA3InKilonewtonIsRefusedNamingTheRotationalMode) {
  const Scene s = shear_band_scene(83.3e3);
  Model m = make_model(make_lattice(2, {12, 12, 1}, 2.5e-3, 0.01), s);
  const CriticalTimeStep c = critical_time_step(m);
  EXPECT_LT(c.step, 7e-6);
  EXPECT_EQ(c.limiting_mode, "rotational");
  try {
    choose_time_step(s, c);
    FAIL() << "a step above the critical one was accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("time.step"), std::string::npos) << msg;
    EXPECT_NE(msg.find("rotational"), std::string::npos) << msg;
    EXPECT_NE(msg.find("couple_moduli"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a3"), std::string::npos) << msg;
  }
  // auto picks safety * critical
  Scene automatic = s;
  automatic.time.step.reset();
  EXPECT_DOUBLE_EQ(choose_time_step(automatic, c), automatic.time.safety * c.step);
}

// The block estimates that name the mode converge more coarsely than the step's (1e-2 over 3
// iterations, critical_time_step.cpp). No block step is below the coupled one (a Ritz value is
// below its block's omega^2, which is below the coupled one), and where one block limits by far
// (a3 = 83.3 kN: rotational, 14x below the translational step) its step is the coupled step
// within 1e-3 (the Ritz value within about 1e-3 of omega^2, half of that in the step, and the
// coupling between the blocks far smaller). With a3 = 83.3 N the blocks are 1.4x apart and the
// coupled step is 8 % below both.
TEST(SolverTimeStep, NamingBlockStepsAgreeWithTheCoupledStep) {
  for (const double a3 : {83.3, 83.3e3}) {
    const Scene s = shear_band_scene(a3);
    Model m = make_model(make_lattice(2, {16, 12, 1}, 2.5e-3, 0.01), s);
    CriticalTimeStep unnamed = coupled_critical_time_step(m);
    EXPECT_TRUE(unnamed.limiting_mode.empty());
    CriticalTimeStep c = unnamed;
    name_limiting_mode_on_whole_model(m, c);
    EXPECT_EQ(unnamed.step, c.step);
    const double limiting = c.limiting_mode == "rotational" ? c.rotational : c.translational;
    std::printf("a3 %g N: critical %.6e s, translational %.6e s, rotational %.6e s (%s, %s; %d + %d iterations)\n", a3,
                c.step, c.translational, c.rotational, c.limiting_mode.c_str(), c.driver.c_str(), c.iterations,
                c.naming_iterations);
    EXPECT_EQ(c.limiting_mode, "rotational");
    EXPECT_GE(c.translational, c.step * (1.0 - 1e-12));
    EXPECT_GE(c.rotational, c.step * (1.0 - 1e-12));
    if (a3 > 1e3) {
      EXPECT_NEAR(limiting, c.step, 1e-3 * c.step);
      // The bending modulus alone leaves nearly all of omega_max^2: its estimate stops once its Ritz
      // value passes half of the block's, after a few applications, where a converged one would take
      // at least 10 (naming_convergence). The two block estimates take at least 10 each.
      EXPECT_LT(c.naming_iterations, 30);
    }
  }
}

// The start-up estimates apply the kernel without the history effects (Model::linear_operator_kernel):
// with every bond acting and no plastic strain it is the model's own operator, bit for bit (the
// damage kernel skips no bond, the viscoplastic one subtracts a zero plastic strain, and both round
// alike: the fusions are written in the source). Once a bond is broken or a plastic strain is held,
// the model's own kernel answers (the elastic one would read the broken entry as a neighbour).
TEST(SolverTimeStep, ElasticResponseIsTheModelsOwnOperatorWhileNoHistoryIsHeld) {
  for (const int d : {2, 3}) {
    Scene s = make_scene(d, true, 1e-3, 3.05);
    s.effects.damage = true;
    s.material.damage = DamageParameters{100.0, 0.0, DamageCalibration::lattice, std::nullopt};
    s.effects.viscoplasticity = true;
    ViscoplasticParameters vp;
    vp.cohesion = 1e6;
    s.material.viscoplasticity = vp;
    Model m = make_model(make_lattice(d, {6, 5, d == 3 ? 4 : 1}, 1e-3, s.thickness), s);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> g(-1e-6, 1e-6);
    for (auto& u : m.points.displacement) u = g(rng);
    for (auto& w : m.points.rotation) w = 1e3 * g(rng);
    auto forces = [&](bool elastic) {
      if (elastic)
        m.linear_operator_kernel()(m.points, m.bonds, m.constants, nullptr);
      else
        m.compute_internal_forces();
      std::vector<double> both = m.points.force;
      both.insert(both.end(), m.points.moment.begin(), m.points.moment.end());
      return both;
    };
    const std::vector<double> own = forces(false);
    EXPECT_EQ(forces(true), own) << d << "-D";
    // A held plastic strain: the model's kernel (the elastic one would not subtract it).
    m.points.plastic_strain[0] = 1e-4;
    const std::vector<double> plastic = forces(false);
    EXPECT_NE(plastic, own) << d << "-D";
    EXPECT_EQ(forces(true), plastic) << d << "-D";
    m.points.plastic_strain[0] = 0.0;
    // A broken bond (both entries of its pair): the model's kernel skips it.
    const std::size_t i = 0;
    const auto b = static_cast<std::size_t>(m.bonds.offset[i]);
    const auto j = static_cast<std::size_t>(m.bonds.neighbor[b]);
    m.bonds.break_bond(static_cast<std::int64_t>(b));
    for (auto k = m.bonds.offset[j]; k < m.bonds.offset[j + 1]; ++k)
      if (m.bonds.neighbor[static_cast<std::size_t>(k)] == static_cast<std::int32_t>(i)) m.bonds.break_bond(k);
    const std::vector<double> broken = forces(false);
    EXPECT_NE(broken, own) << d << "-D";
    EXPECT_EQ(forces(true), broken) << d << "-D";
  }
}

// The mode named on the patch around the stiffest point (docs/theory.md section 9) is the one the
// whole model names: the same limiting mode and driver, and the limiting block's step within 1e-3
// (on these two, the whole model's naming estimate of that block is within 8e-5 of its converged
// one; the patch's estimates converge as tightly as the step's). The patch names it where the highest mode is one
// block's: the shear band's material with a3 in kN (rotational, the bending modulus) and a 3-D block (translational);
// the lattices are large enough for the patch (4 horizons around a corner, with its neighbours under a tenth of the
// model, so that it is tried). With a3 in N the highest mode mixes both blocks (the coupled step 8 % below both block
// steps): each block is then named on the patches around its own stiffest point, where they are under a tenth of the
// model (the larger lattice), else by the whole model.
TEST(SolverTimeStep, PatchNamesTheModeTheWholeModelNames) {
  struct Case {
    Scene scene;
    std::array<int, 3> n;
    bool on_patch, on_block_patches;
  };
  Scene block = make_scene(3, true, 1e-3, 2.05);
  for (const Case& k :
       {Case{shear_band_scene(83.3e3), {64, 56, 1}, true, false},
        Case{shear_band_scene(83.3), {64, 56, 1}, false, false},
        Case{shear_band_scene(83.3), {160, 140, 1}, false, false}, Case{block, {28, 27, 26}, true, false}}) {
    const double dx = k.scene.geometry.spacing;
    Model m = make_model(make_lattice(k.scene.dimension, k.n, dx, k.scene.thickness), k.scene);
    // The step on the whole model in both, so that the naming alone is compared.
    const CriticalTimeStep named = critical_time_step(m, StepEstimate::whole_model);
    CriticalTimeStep whole = coupled_critical_time_step(m);
    name_limiting_mode_on_whole_model(m, whole);
    std::printf(
        "%d-D: critical %.6e s; patch of %zu points (block patches %zu, %zu): %s (%s), translational %.6e s, "
        "rotational %.6e s, %d applications; whole model: %s, %.6e s, %.6e s, %d applications\n",
        k.scene.dimension, named.step, named.naming_patch_points, named.naming_block_patch_points[0],
        named.naming_block_patch_points[1], named.limiting_mode.c_str(), named.driver.c_str(), named.translational,
        named.rotational, named.naming_iterations, whole.limiting_mode.c_str(), whole.translational, whole.rotational,
        whole.naming_iterations);
    EXPECT_EQ(named.naming_patch_points > 0, k.on_patch);
    EXPECT_EQ(named.naming_block_patch_points[0] > 0, k.on_block_patches);
    EXPECT_EQ(named.naming_block_patch_points[1] > 0, k.on_block_patches);
    EXPECT_LT(named.naming_iterations, k.on_block_patches ? 4 * whole.naming_iterations : 1 << 30);
    EXPECT_LT(named.naming_patch_points, m.points.owned / 2);
    EXPECT_EQ(named.step, whole.step);
    EXPECT_EQ(named.limiting_mode, whole.limiting_mode);
    EXPECT_EQ(named.driver.substr(0, 40), whole.driver.substr(0, 40));  // a quoted fraction may differ
    const bool rotational = whole.limiting_mode == "rotational";
    EXPECT_NEAR(rotational ? named.rotational : named.translational,
                rotational ? whole.rotational : whole.translational, 1e-3 * whole.step);
    // No block step below the coupled one (a patch's block value is below the whole block's).
    EXPECT_GE(named.translational, named.step * (1.0 - 1e-12));
    EXPECT_GE(named.rotational, named.step * (1.0 - 1e-12));
  }
}

// Points made by mppm-preprocess from a scene of the repository (with `set`, one --set), into the
// test's scratch directory.
std::string preprocessed_points(const std::string& scene, const std::string& name, const std::string& set = "") {
  const std::filesystem::path dir = std::filesystem::path(MPPM_BINARY_DIR) / "test_scratch" / "mixed-mode";
  std::filesystem::create_directories(dir);
  const std::string points = (dir / (name + ".vtp")).string();
  std::vector<std::string> command{mppm::testing::binary("mppm-preprocess"), std::string(MPPM_SOURCE_DIR) + "/" + scene,
                                   "-o", points};
  if (!set.empty()) command.insert(command.end(), {"--set", set});
  const mppm::testing::StageOutcome pre = mppm::testing::run_stage_process(command);
  EXPECT_EQ(pre.code, 0) << pre.err;
  return points;
}

// Highest modes that mix both blocks, as mppm-preprocess makes their models: the 3-D benchmark block
// (workflows/benchmarks/scenes/block.yaml, 20^3 points, its bottom a layer of fixed velocity, its
// top loaded; the coupled step 0.5 % below the translational one) and the Kalthoff-Winkler plate
// (workflows/kalthoff-winkler/scene.yaml: notches, a small length scale; the coupled step 0.3 %
// below the rotational one). Each block is named on the patches around its own stiffest point, at
// a small part of the whole model's cost, with the whole model's limiting mode and driver. Each
// block step is checked against the whole model's converged estimate (the step's convergence): a
// block's omega^2 on its patches is the 4-horizon estimate (a lower bound) raised by the rise from
// 3 to 4 horizons, which is at most 1e-3 of it, so the block step is at most 5e-4 short of the
// converged one; and the raise covers the shortfall, so it is not longer, up to the converged
// estimate's own creep (1e-6). The whole model's naming estimate (its coarser convergence) is
// quoted beside it: on the plate it is 2.8e-3 long in the rotational step.
TEST(SolverTimeStep, MixedModeIsNamedOnEachBlocksPatchesAsTheWholeModelNamesIt) {
  struct Case {
    const char* name;
    Model model;
  };
  const Scene plate = load_scene(std::string(MPPM_SOURCE_DIR) + "/workflows/kalthoff-winkler/scene.yaml");
  Case cases[] = {
      {"3-D block", make_model(read_point_cloud(preprocessed_points("workflows/benchmarks/scenes/block.yaml", "block20",
                                                                    "geometry.file=block20.geo")),
                               rock_block())},
      {"Kalthoff-Winkler plate",
       build_model(read_point_cloud(preprocessed_points("workflows/kalthoff-winkler/scene.yaml", "kalthoff-winkler")),
                   model_options(plate))}};
  for (Case& k : cases) {
    Model& m = k.model;
    const CriticalTimeStep named = critical_time_step(m);
    CriticalTimeStep whole = named, converged = named;
    name_limiting_mode_on_whole_model(m, whole);
    name_limiting_mode_on_whole_model(m, converged, NamingConvergence::converged);
    std::printf(
        "%s: block patches of %zu and %zu points: %s, translational %.6e s, rotational %.6e s, %d applications; "
        "whole model converged: %.6e s, %.6e s, %d applications; whole model's naming: %s, %.6e s, %.6e s, %d "
        "applications (coupled %.6e s)\n",
        k.name, named.naming_block_patch_points[0], named.naming_block_patch_points[1], named.limiting_mode.c_str(),
        named.translational, named.rotational, named.naming_iterations, converged.translational, converged.rotational,
        converged.naming_iterations, whole.limiting_mode.c_str(), whole.translational, whole.rotational,
        whole.naming_iterations, named.step);
    EXPECT_GT(named.naming_block_patch_points[0], 0u) << k.name;
    EXPECT_GT(named.naming_block_patch_points[1], 0u) << k.name;
    EXPECT_EQ(named.naming_patch_points, 0u) << k.name;
    // The cost: applications times the points they apply to, under half the whole model's naming's.
    const std::size_t largest_patch = std::max(named.naming_block_patch_points[0], named.naming_block_patch_points[1]);
    EXPECT_LT(static_cast<double>(named.naming_iterations) * static_cast<double>(largest_patch),
              0.5 * whole.naming_iterations * static_cast<double>(m.points.owned))
        << k.name;
    EXPECT_EQ(named.limiting_mode, converged.limiting_mode) << k.name;
    EXPECT_EQ(named.limiting_mode, whole.limiting_mode) << k.name;
    EXPECT_EQ(named.driver.substr(0, 40), converged.driver.substr(0, 40)) << k.name;
    for (const auto& [on_patches, reference] :
         {std::pair{named.translational, converged.translational}, std::pair{named.rotational, converged.rotational}}) {
      EXPECT_LE(on_patches, reference * (1.0 + 1e-6)) << k.name;
      EXPECT_GE(on_patches, reference * (1.0 - 5e-4)) << k.name;
    }
    EXPECT_GT(named.translational, named.step) << k.name;  // mixed: both block steps above the coupled one
    EXPECT_GT(named.rotational, named.step) << k.name;
  }
}

// The patches' estimates run side by side on two threads (the step's patches of 4 and 3 horizons,
// the naming's two blocks, each on a model of its own) and one after the other on one thread: the
// same bits. A 3-D lattice block names its mode on the step's patch, the 3-D benchmark block held
// and loaded on each block's patches.
TEST(SolverTimeStep, PatchEstimatesGiveTheSameBitsOnOneAndTwoThreads) {
  const int saved = omp_get_max_threads();
  Model models[] = {make_model(make_lattice(3, {28, 27, 26}, 1e-3, 1.0), make_scene(3, true, 1e-3, 2.05)),
                    make_model(read_point_cloud(preprocessed_points("workflows/benchmarks/scenes/block.yaml",
                                                                    "block20-threads", "geometry.file=block20.geo")),
                               rock_block())};
  for (Model& m : models) {
    omp_set_num_threads(1);
    const CriticalTimeStep one = critical_time_step(m);
    omp_set_num_threads(2);
    const CriticalTimeStep two = critical_time_step(m);
    EXPECT_GT(one.step_patch_points, 0u) << one.whole_model_reason;
    EXPECT_GT(one.naming_patch_points + one.naming_block_patch_points[0], 0u);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one.step), std::bit_cast<std::uint64_t>(two.step));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one.translational), std::bit_cast<std::uint64_t>(two.translational));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one.rotational), std::bit_cast<std::uint64_t>(two.rotational));
    EXPECT_EQ(one.limiting_mode, two.limiting_mode);
    EXPECT_EQ(one.driver, two.driver);
    EXPECT_EQ(one.iterations, two.iterations);
    EXPECT_EQ(one.naming_iterations, two.naming_iterations);
    EXPECT_EQ(one.naming_patch_points, two.naming_patch_points);
    EXPECT_EQ(one.naming_block_patch_points, two.naming_block_patch_points);
  }
  omp_set_num_threads(saved);
}

// Where the highest mode spreads over the whole body (a periodic lattice: no surface, no corner, a
// plane wave on top), no patch holds it: a patch's own points held in by fixed neighbours lose
// more than 2e-3 of omega_max^2 at 4 and at 8 horizons, and the whole model names the mode.
TEST(SolverTimeStep, BodyWideModeIsNamedOnTheWholeModel) {
  const double dx = 1e-3;
  const Scene s = make_scene(2, true, dx, 2.05);
  const std::array<int, 3> n{170, 170, 1};  // 8 horizons with the neighbours: under a tenth, so tried
  Model m = make_model(make_lattice(2, n, dx, s.thickness), s, {n[0] * dx, n[1] * dx, 0.0});
  const CriticalTimeStep c = critical_time_step(m);
  CriticalTimeStep whole = coupled_critical_time_step(m);
  name_limiting_mode_on_whole_model(m, whole);
  EXPECT_EQ(c.naming_patch_points, 0u);
  EXPECT_EQ(c.limiting_mode, whole.limiting_mode);
  EXPECT_EQ(c.translational, whole.translational);
  EXPECT_EQ(c.naming_iterations, whole.naming_iterations);
}

// A patch's Ritz value is a lower bound of the whole model's omega_max^2. So a whole-model estimate
// below it (a Lanczos run that stopped short of the top, here one made 2 % short by hand) gives way
// to it: the critical step becomes the patch's, which is the converged step within 1e-6.
TEST(SolverTimeStep, PatchAboveTheWholeEstimateLowersTheStep) {
  Model m = make_model(make_lattice(3, {28, 27, 26}, 1e-3, 1.0), make_scene(3, true, 1e-3, 2.05));
  const CriticalTimeStep converged = coupled_critical_time_step(m);
  CriticalTimeStep short_of_the_top = converged;
  short_of_the_top.step *= 1.01;
  name_limiting_mode(m, short_of_the_top);
  EXPECT_GT(short_of_the_top.naming_patch_points, 0u);
  EXPECT_NEAR(short_of_the_top.step, converged.step, 1e-6 * converged.step);
  EXPECT_TRUE(short_of_the_top.step_from_patch);
  CriticalTimeStep as_converged = converged;
  name_limiting_mode(m, as_converged);
  EXPECT_EQ(as_converged.step, converged.step);
  EXPECT_FALSE(as_converged.step_from_patch);
  // The same where the patch holds the highest mode but does not name it (a mixed mode: the whole
  // model names it): the step is still the patch's. This patch holds the mode within 3.7e-4 of
  // omega_max^2 (measured), so its step is the converged one or up to 2e-4 longer, never shorter
  // (a lower bound of omega_max^2), and well below the 1 % too long one.
  Model mixed = make_model(make_lattice(2, {64, 56, 1}, 2.5e-3, 0.01), shear_band_scene(83.3));
  const CriticalTimeStep mixed_converged = coupled_critical_time_step(mixed);
  CriticalTimeStep mixed_short = mixed_converged;
  mixed_short.step *= 1.01;
  name_limiting_mode(mixed, mixed_short);
  EXPECT_EQ(mixed_short.naming_patch_points, 0u);
  EXPECT_TRUE(mixed_short.step_from_patch);
  EXPECT_GE(mixed_short.step, mixed_converged.step * (1.0 - 1e-8));
  EXPECT_LE(mixed_short.step, mixed_converged.step * (1.0 + 1e-3));
}

// The step on patches (docs/theory.md section 9): where the highest mode lives at the stiffest
// points (surfaces, corners, layers), the step comes from the patches of 4 horizons around them,
// raised by their rise from 3 horizons. Its stated margin against the whole model's estimate:
// never longer (the raise covers the 4-horizon patch's shortfall, to the whole model's own Lanczos
// convergence, 1e-6 here), and at most 5e-4 shorter (the raise is at most 1e-3 of omega_max^2,
// the confinement limit, and omega_max^2 of a 4-horizon patch is at most the whole model's: by
// Cauchy interlacing, a principal submatrix). The plates with layers hold their highest mode in a
// layer's corner.
TEST(SolverTimeStep, StepOnPatchesIsTheWholeModelsWithinItsMargin) {
  struct Case {
    const char* name;
    Scene scene;
    std::array<int, 3> n;
    bool layers;
  };
  Scene plate = make_scene(2, true, 1e-3, 3.05);
  Scene classical = make_scene(2, false, 1e-3, 3.05);
  Scene block = make_scene(3, true, 1e-3, 2.05);
  for (const Case& k : {Case{"micro-polar plate with layers", plate, {90, 40, 1}, true},
                        Case{"non-polar plate with layers", classical, {90, 40, 1}, true},
                        Case{"3-D micro-polar block", block, {28, 27, 26}, false}}) {
    const double dx = k.scene.geometry.spacing;
    PointCloud cloud = make_lattice(k.scene.dimension, k.n, dx, k.scene.thickness);
    if (k.layers) testing::add_end_layers(cloud, k.n[0], 3, "displacement", "velocity");
    Model m = make_model(cloud, k.scene);
    const StiffestPoints stiffest = stiffest_points(m.points, m.bonds, m.constants);
    const CriticalTimeStep on_patches = estimate_critical_step(m, StepEstimate::patch, stiffest);
    const CriticalTimeStep whole = coupled_critical_time_step(m);
    std::printf("%s: patches %.9e s (%zu points, %d applications), whole model %.9e s (%d iterations): %+.2e\n", k.name,
                on_patches.step, on_patches.step_patch_points, on_patches.iterations, whole.step, whole.iterations,
                on_patches.step / whole.step - 1.0);
    EXPECT_GT(on_patches.step_patch_points, 0u) << k.name << ": " << on_patches.whole_model_reason;
    EXPECT_TRUE(on_patches.whole_model_reason.empty()) << k.name;
    EXPECT_LE(on_patches.step, whole.step * (1.0 + 1e-6)) << k.name;
    EXPECT_GE(on_patches.step, whole.step * (1.0 - 5e-4)) << k.name;
    if (k.layers) {
      EXPECT_GT(m.points.region[stiffest.any.index], 0) << k.name;
    }
  }
}

// The naming's first patch is the step's (4 horizons around the stiffest point of all): kept from
// the step's estimate, it is neither cut nor estimated again, and names the same mode with the
// same bits, in fewer applications (the step's coupled estimate is not repeated).
TEST(SolverTimeStep, NamingOnTheStepsKeptPatchIsTheSameBits) {
  Scene plate = make_scene(2, true, 1e-3, 3.05);
  Scene block = make_scene(3, true, 1e-3, 2.05);
  for (const auto& [name, scene, n, layers] :
       {std::tuple{"micro-polar plate with layers", plate, std::array<int, 3>{90, 40, 1}, true},
        std::tuple{"3-D micro-polar block", block, std::array<int, 3>{28, 27, 26}, false}}) {
    PointCloud cloud = make_lattice(scene.dimension, n, scene.geometry.spacing, scene.thickness);
    if (layers) testing::add_end_layers(cloud, n[0], 3, "displacement", "velocity");
    Model m = make_model(cloud, scene);
    const StiffestPoints stiffest = stiffest_points(m.points, m.bonds, m.constants);
    const PatchCentre centre = patch_centre(m, stiffest.any);
    std::optional<StepPatch> kept;
    CriticalTimeStep reused = estimate_critical_step(m, StepEstimate::patch, stiffest, &kept);
    ASSERT_TRUE(kept.has_value()) << name;
    CriticalTimeStep cut = reused;
    name_limiting_mode(m, reused, centre, &kept);
    name_limiting_mode(m, cut, centre);
    EXPECT_GT(reused.naming_patch_points, 0u) << name;
    EXPECT_EQ(reused.step, cut.step) << name;
    EXPECT_EQ(reused.translational, cut.translational) << name;
    EXPECT_EQ(reused.rotational, cut.rotational) << name;
    EXPECT_EQ(reused.limiting_mode, cut.limiting_mode) << name;
    EXPECT_EQ(reused.driver, cut.driver) << name;
    EXPECT_EQ(reused.naming_patch_points, cut.naming_patch_points) << name;
    EXPECT_LT(reused.naming_iterations, cut.naming_iterations) << name;
  }
}

// The step falls back to the whole model's estimate, and says why, where no patch can give it.
TEST(SolverTimeStep, StepFallsBackToTheWholeModelAndSaysWhy) {
  const double dx = 1e-3;
  const Scene s = make_scene(2, true, dx, 2.05);
  auto on_patches = [](Model& m) {
    return estimate_critical_step(m, StepEstimate::patch, stiffest_points(m.points, m.bonds, m.constants));
  };
  auto expect_whole = [](const CriticalTimeStep& c, Model& m, const std::string& reason) {
    EXPECT_EQ(c.step_patch_points, 0u) << reason;
    EXPECT_NE(c.whole_model_reason.find(reason), std::string::npos) << c.whole_model_reason;
    EXPECT_EQ(c.step, coupled_critical_time_step(m).step) << reason;  // the same bits
  };
  // A periodic lattice: its top mode is a plane wave over the whole body, which a patch held in
  // by fixed neighbours cuts short (the rise from 3 to 4 horizons is far above 1e-3).
  const std::array<int, 3> n{170, 170, 1};
  Model periodic = make_model(make_lattice(2, n, dx, s.thickness), s, {n[0] * dx, n[1] * dx, 0.0});
  expect_whole(on_patches(periodic), periodic, "reaches beyond its patch");
  // The shear-band material on a lattice without layers: its highest modes mix translation and
  // micro-rotation and decay slowly from the corner, rising by 1.8e-3 (a3 = 83.3 N) and 1.4e-3
  // (a3 = 83.3 kN) from 3 to 4 horizons (measured).
  for (const double a3 : {83.3, 83.3e3}) {
    Model slow_decay = make_model(make_lattice(2, {64, 56, 1}, 2.5e-3, 0.01), shear_band_scene(a3));
    expect_whole(on_patches(slow_decay), slow_decay, "reaches beyond its patch");
  }
  // A body so small that the patch would hold more than a tenth of it.
  Model small = make_model(make_lattice(2, {20, 18, 1}, dx, s.thickness), s);
  expect_whole(on_patches(small), small, "more than a tenth");
  // Asked for.
  Model asked = make_model(make_lattice(2, {64, 56, 1}, dx, s.thickness), s);
  const StiffestPoints stiffest = stiffest_points(asked.points, asked.bonds, asked.constants);
  expect_whole(estimate_critical_step(asked, StepEstimate::whole_model, stiffest), asked,
               "numerics.step_estimate: whole_model");
  EXPECT_GT(estimate_critical_step(asked, StepEstimate::patch, stiffest).step_patch_points, 0u);
  // A model that holds history (here a broken bond): its operator is not the start-up's.
  Scene damaged_scene = s;
  damaged_scene.effects.damage = true;
  damaged_scene.material.damage = DamageParameters{100.0, 0.0, DamageCalibration::lattice, std::nullopt};
  Model damaged = make_model(make_lattice(2, {64, 56, 1}, dx, s.thickness), damaged_scene);
  damaged.bonds.break_bond(0);
  const CriticalTimeStep c = on_patches(damaged);
  EXPECT_EQ(c.step_patch_points, 0u);
  EXPECT_NE(c.whole_model_reason.find("holds history"), std::string::npos) << c.whole_model_reason;
}

// Runs a free body with random velocities at `factor` times the estimated critical step and
// returns the growth of the total energy.
// `on_patches`: a 90 x 40 plate of 1 mm spacing whose step comes from the patches (checked)
// instead of the 10 x 9 shear-band specimen.
double energy_growth(bool micropolar, double factor, bool on_patches = false) {
  Scene s = on_patches ? make_scene(2, micropolar, 1e-3, 3.05) : shear_band_scene(83.3);
  s.effects.micropolar = micropolar;
  Model m = on_patches ? make_model(make_lattice(2, {90, 40, 1}, 1e-3, s.thickness), s)
                       : make_model(make_lattice(2, {10, 9, 1}, 2.5e-3, 0.01), s);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  for (auto& v : m.points.velocity) v = 0.01 * g(rng);
  for (auto& w : m.points.spin) w = 1.0 * g(rng);
  const CriticalTimeStep c = critical_time_step(m);
  EXPECT_EQ(c.step_patch_points > 0, on_patches) << c.whole_model_reason;
  BoundaryConditions none(m.points);
  ExplicitDynamics dynamics(m, none, factor * c.step);
  dynamics.initialize();
  const double e0 = dynamics.energy().total();
  double growth = 1.0;
  for (int block = 0; block < 30 && growth < 1e6; ++block) {
    for (int k = 0; k < 49; ++k) dynamics.step(false);
    dynamics.step(true);
    growth = dynamics.energy().total() / e0;
  }
  return growth;
}

TEST(SolverTimeStep, EstimateIsTheStabilityLimitOfTheScheme) {
  for (bool micropolar : {true, false}) {
    // Just below the estimate the energy stays bounded (central differences conserve a nearby
    // energy; factor 2 covers its oscillation near the limit); just above, the highest mode
    // grows by orders of magnitude within a few hundred steps.
    EXPECT_LT(energy_growth(micropolar, 0.97), 2.0) << "micropolar=" << micropolar;
    EXPECT_GT(energy_growth(micropolar, 1.05), 1e6) << "micropolar=" << micropolar;
  }
}

// The same where the step comes from the patches.
TEST(SolverTimeStep, StepOnPatchesIsTheStabilityLimitOfTheScheme) {
  for (bool micropolar : {true, false}) {
    EXPECT_LT(energy_growth(micropolar, 0.97, true), 2.0) << "micropolar=" << micropolar;
    EXPECT_GT(energy_growth(micropolar, 1.05, true), 1e6) << "micropolar=" << micropolar;
  }
}

}  // namespace
}  // namespace mppm::solver

#include "solver/energy_guard.hpp"

namespace mppm::solver {
namespace {

// The running energy check stops growth the external work does not explain, and only that.
TEST(SolverEnergyGuard, StopsUnexplainedGrowthOnly) {
  EnergyGuard guard(0.05, 50);
  EnergyState e;
  e.kinetic = 1.0;
  e.external_work = 1.0;
  EXPECT_FALSE(guard.check(60, e, 0.0));  // fully explained by the work
  e.kinetic = 0.5;                        // energy lost (dissipation): not a failure
  EXPECT_FALSE(guard.check(61, e, 0.0));
  e.kinetic = 1.04;  // 4 % unexplained: within the tolerance
  EXPECT_FALSE(guard.check(62, e, 0.0));
  e.kinetic = 1.2;  // 20 %: stop, and say why
  const auto reason = guard.check(63, e, 0.0);
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->find("energy_check_tolerance"), std::string::npos) << *reason;
  // Before the start step nothing is checked.
  EnergyGuard early(0.05, 50);
  EXPECT_FALSE(early.check(10, e, 0.0));
  // Round-off once the energy has decayed to nothing is relative to the largest energy seen.
  EnergyGuard decayed(0.05, 0);
  EnergyState big;
  big.kinetic = 1.0;
  big.external_work = 1.0;
  EXPECT_FALSE(decayed.check(1, big, 0.0));
  EnergyState tiny;
  tiny.kinetic = 1e-20;
  tiny.external_work = -1e-3;  // damped away: all but round-off is gone
  EXPECT_FALSE(decayed.check(2, tiny, 0.0));
}

// A mode beyond the step (omega dt > 2) keeps the balance closed with a negative kinetic energy of
// the scheme; the check stops it, and a non-finite energy, which compares false with everything.
TEST(SolverEnergyGuard, StopsAnUnstableModeTheBalanceHides) {
  EnergyGuard guard(0.05, 0);
  EnergyState e;
  e.kinetic = 100.0;
  e.external_work = 100.0;
  EXPECT_FALSE(guard.check(1, e, 0.0));
  // The rotations of a few points blow up: -454 J of rotational kinetic energy, booked against
  // elastic energy, with the balance still closed to round-off (measured in a run that blew up).
  e.rotational_kinetic = -454.0;
  e.elastic = 454.0;
  const auto reason = guard.check(2, e, 0.0);
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->find("unstable"), std::string::npos) << *reason;
  EXPECT_NE(reason->find("rotational"), std::string::npos) << *reason;
  // Round-off of a stable scheme: 1e-3 of the scale negative, far inside the tolerance.
  EnergyGuard roundoff(0.05, 0);
  EnergyState r;
  r.kinetic = -0.1;
  r.elastic = 100.1;
  r.external_work = 100.0;
  EXPECT_FALSE(roundoff.check(1, r, 0.0));
  // Overflowed energies.
  EnergyGuard overflow(0.05, 0);
  EnergyState n;
  n.kinetic = std::numeric_limits<double>::quiet_NaN();
  const auto nan_reason = overflow.check(1, n, 0.0);
  ASSERT_TRUE(nan_reason);
  EXPECT_NE(nan_reason->find("no longer finite"), std::string::npos) << *nan_reason;
}

}  // namespace
}  // namespace mppm::solver
