// The pore fluid's scene keys (docs/scene.md, material.pore_fluid): read in SI with their
// defaults, every bad value refused with its key and reason, the unsaturated retention curve read
// and checked, the hydrostatic start's keys, the block ignored with a warning while the effect is
// off, and the resolved scene read back unchanged.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "tests/unit/scene_text_edits.hpp"

using namespace mppm;

namespace {
// A saturated sand column (line numbers matter for the error tests).
const std::string kScene = R"(mppm: 1
name: consolidation
dimension: 2
thickness: 1 m
geometry:
  file: column.geo
  spacing: 0.1 m
  horizon_factor: 3.015
material:
  density: 2650 kg/m^3
  solid_fraction: 0.65
  lambda: 40 MPa
  mu: 30 MPa
  pore_fluid:
    permeability: 1e-12 m^2
    fluid_viscosity: 1 mPa*s
    fluid_density: 998 kg/m^3
    biot_coefficient: 0.9
    biot_modulus: 2 GPa
    initial_pressure: -10 kPa
effects: [pore_fluid]
boundary_conditions:
  - {boundary: top, type: traction, value: [0, -10 kPa]}
time:
  end: 1 s
)";

const std::string kPath = "/cases/consolidation/scene.yaml";
const std::string kBlock = "material.pore_fluid";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return mppm::testing::scene_error_of(text, kPath, overrides);
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  return mppm::testing::replace_once(std::move(text), from, to);
}

// The scene without the line of `key` in the pore_fluid block.
std::string without(const std::string& key) {
  const auto start = kScene.find("    " + key + ":");
  EXPECT_NE(start, std::string::npos) << key;
  return std::string(kScene).erase(start, kScene.find('\n', start) + 1 - start);
}
}  // namespace

TEST(ScenePoreFluid, ReadsTheBlockInSI) {
  const Scene s = parse_scene(kScene, kPath);
  EXPECT_TRUE(s.effects.pore_fluid);
  EXPECT_EQ(s.effects.names(), std::vector<std::string>{"pore_fluid"});
  ASSERT_TRUE(s.material.pore_fluid.has_value());
  const auto& f = *s.material.pore_fluid;
  EXPECT_DOUBLE_EQ(f.permeability, 1e-12);
  EXPECT_DOUBLE_EQ(f.fluid_viscosity, 1e-3);
  EXPECT_DOUBLE_EQ(f.fluid_density, 998.0);
  EXPECT_DOUBLE_EQ(f.biot_coefficient, 0.9);
  EXPECT_DOUBLE_EQ(f.biot_modulus, 2e9);
  EXPECT_DOUBLE_EQ(f.initial_pressure, -1e4);
  EXPECT_DOUBLE_EQ(f.mobility(), 1e-9);  // k' = k / mu_f
  EXPECT_DOUBLE_EQ(s.material.porosity(), 0.35);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.where("material.pore_fluid.biot_modulus"), kPath + ":19: material.pore_fluid.biot_modulus");
}

TEST(ScenePoreFluid, OptionalKeysHaveTheirDefaults) {
  std::string text = kScene;
  for (const char* key : {"fluid_density", "biot_coefficient", "initial_pressure"}) {
    const auto start = text.find(std::string("    ") + key + ":");
    ASSERT_NE(start, std::string::npos) << key;
    text.erase(start, text.find('\n', start) + 1 - start);
  }
  const Scene s = parse_scene(text, kPath);
  ASSERT_TRUE(s.material.pore_fluid.has_value());
  EXPECT_EQ(s.material.pore_fluid->fluid_density, 1000.0);  // water
  EXPECT_EQ(s.material.pore_fluid->biot_coefficient, 1.0);  // rigid grains
  EXPECT_EQ(s.material.pore_fluid->initial_pressure, 0.0);
}

// --set reaches the block's keys like any other, units and all.
TEST(ScenePoreFluid, OverridesReachTheBlock) {
  const Scene s =
      parse_scene(kScene, kPath, {"material.pore_fluid.permeability=1 um^2", "material.pore_fluid.biot_coefficient=1"});
  EXPECT_DOUBLE_EQ(s.material.pore_fluid->permeability, 1e-12);
  EXPECT_EQ(s.material.pore_fluid->biot_coefficient, 1.0);
  // A new block, with the effect switched on, on a scene that has neither.
  const auto block = kScene.find("  pore_fluid:\n");
  const std::string dry = replace(std::string(kScene).erase(block, kScene.find("effects:") - block),
                                  "effects: [pore_fluid]", "effects: none");
  ASSERT_EQ(dry.find("pore_fluid"), std::string::npos);
  const Scene wet = parse_scene(dry, kPath,
                                {"effects=[pore_fluid]",
                                 "material.pore_fluid={permeability: 2e-12 m^2, "
                                 "fluid_viscosity: 1 mPa*s, biot_modulus: 3 GPa}"});
  ASSERT_TRUE(wet.material.pore_fluid.has_value());
  EXPECT_DOUBLE_EQ(wet.material.pore_fluid->biot_modulus, 3e9);
  const auto e = error_of(kScene, {"material.pore_fluid.permeability=-1e-12 m^2"});
  EXPECT_EQ(e, kPath +
                   ": --set material.pore_fluid.permeability=-1e-12 m^2: material.pore_fluid.permeability: -1e-12 "
                   "must be > 0");
}

TEST(ScenePoreFluid, BadValuesNameTheKeyAndTheReason) {
  // (override, the message after "FILE: --set ...: ")
  const std::pair<const char*, const char*> bad[] = {
      {"permeability=0", "permeability: 0 must be > 0"},
      {"permeability=1e-12 m", "permeability: \"1e-12 m\" is a length (e.g. m, mm), expected an area (e.g. m^2, mm^2)"},
      {"fluid_viscosity=0", "fluid_viscosity: 0 must be > 0"},
      {"fluid_viscosity=1 mPa",
       "fluid_viscosity: \"1 mPa\" is a pressure or stress (e.g. Pa, MPa), expected a "
       "viscosity (e.g. Pa*s, MPa*s)"},
      {"fluid_density=-1 kg/m^3", "fluid_density: -1 must be >= 0"},
      {"biot_modulus=0 GPa", "biot_modulus: 0 must be > 0"},
      {"biot_modulus=-2 GPa", "biot_modulus: -2e+09 must be > 0"},
      {"initial_pressure=inf", "initial_pressure: \"inf\" is not a finite number"},
      {"initial_pressure=1e300 GPa", "initial_pressure: \"1e300 GPa\" is out of range"},
      {"initial_pressure=10 m", "initial_pressure: \"10 m\" is a length"},
  };
  for (const auto& [set, expected] : bad) {
    const auto e = error_of(kScene, {kBlock + "." + set});
    EXPECT_EQ(e.rfind(kPath + ": --set " + kBlock + "." + set + ": " + kBlock + "." + expected, 0), 0u)
        << set << ": " << e;
  }
}

// b in (n0, 1], n0 = 1 - solid_fraction = 0.35 here: the message gives the porosity.
TEST(ScenePoreFluid, BiotCoefficientLiesAbovePorosityAndAtMostOne) {
  for (const char* b : {"0.36", "1"}) {
    const Scene s = parse_scene(kScene, kPath, {kBlock + ".biot_coefficient=" + b});
    EXPECT_EQ(s.material.pore_fluid->biot_coefficient, std::stod(b)) << b;
  }
  const std::string expected =
      " is out of range (expected porosity < b <= 1, with the porosity n0 = 1 - material.solid_fraction = 0.35)";
  for (const char* b : {"0.35", "0", "1.01"}) {
    EXPECT_EQ(error_of(replace(kScene, "biot_coefficient: 0.9", std::string("biot_coefficient: ") + b)),
              kPath + ":18: material.pore_fluid.biot_coefficient: " + b + expected)
        << b;
  }
  // The porosity follows the solid fraction: 0.9 is out of range for n0 = 0.95.
  EXPECT_NE(error_of(kScene, {"material.solid_fraction=0.05"})
                .find("with the porosity n0 = 1 - "
                      "material.solid_fraction = 0.95)"),
            std::string::npos);
}

TEST(ScenePoreFluid, MissingAndUnknownKeysAreNamed) {
  for (const char* key : {"permeability", "fluid_viscosity", "biot_modulus"}) {
    const auto e = error_of(without(key));
    EXPECT_EQ(e.rfind(kPath + ":15: " + kBlock + "." + key + ": missing required key (", 0), 0u) << key << ": " << e;
  }
  auto e = error_of(replace(kScene, "    permeability:", "    permeabilty:"));
  EXPECT_EQ(e, kPath +
                   ":15: material.pore_fluid.permeabilty: unknown key (expected one of: permeability, "
                   "fluid_viscosity, fluid_density, biot_coefficient, biot_modulus, initial_pressure, free_surface, "
                   "retention); did "
                   "you mean "
                   "'permeability'?");
  e = error_of(kScene, {"material.pore_fluid=water"});
  EXPECT_NE(e.find("material.pore_fluid: expected a map of keys (permeability, "), std::string::npos) << e;
  // The effect without its block.
  e = error_of(kScene, {"material.pore_fluid=null"});
  EXPECT_NE(e.find(": material.pore_fluid: missing: the effect 'pore_fluid' needs {permeability, fluid_viscosity, "
                   "biot_modulus}"),
            std::string::npos)
      << e;
  // The effects list names the new effect among the valid ones.
  e = error_of(replace(kScene, "effects: [pore_fluid]", "effects: [porefluid]"));
  EXPECT_NE(e.find("effects[0]: unknown effect 'porefluid' (expected one of: micropolar, viscoplasticity, damage, "
                   "gravity, pore_fluid); did you mean 'pore_fluid'?"),
            std::string::npos)
      << e;
}

// The unsaturated model's retention curve is read (model, p_e > 0, n > 1, 0 <= S_res < 1, unknown keys
// refused), written back and read back bit for bit (the solver, not the reader, refuses to run it
// while its coupling is not built: test_solver_fluid_boundaries.cpp).
TEST(ScenePoreFluid, RetentionIsReadCheckedAndReadBack) {
  const auto with = [](const std::string& block) {
    return replace(kScene, "    initial_pressure: -10 kPa\n",
                   "    initial_pressure: -10 kPa\n    retention: " + block + "\n");
  };
  const Scene s = parse_scene(
      with("{model: van_genuchten, air_entry_pressure: 10 kPa, n: 1.56, residual_saturation: 0.078}"), kPath);
  ASSERT_TRUE(s.material.pore_fluid->retention.has_value());
  const RetentionParameters& r = *s.material.pore_fluid->retention;
  EXPECT_EQ(r.model, "van_genuchten");
  EXPECT_EQ(r.air_entry_pressure, 1e4);
  EXPECT_EQ(r.n, 1.56);
  EXPECT_EQ(r.residual_saturation, 0.078);
  const Scene back = parse_scene(resolved_scene_yaml(s), "/elsewhere/scene.resolved.yaml");
  ASSERT_TRUE(back.material.pore_fluid->retention.has_value());
  const RetentionParameters& b = *back.material.pore_fluid->retention;
  EXPECT_EQ(b.model, r.model);
  EXPECT_EQ(b.air_entry_pressure, r.air_entry_pressure);
  EXPECT_EQ(b.n, r.n);
  EXPECT_EQ(b.residual_saturation, r.residual_saturation);
  // The residual saturation is 0 unless given; a saturated scene has no retention.
  EXPECT_EQ(parse_scene(with("{model: van_genuchten, air_entry_pressure: 2 kPa, n: 3}"), kPath)
                .material.pore_fluid->retention->residual_saturation,
            0.0);
  EXPECT_FALSE(parse_scene(kScene, kPath).material.pore_fluid->retention.has_value());
  EXPECT_EQ(resolved_scene_yaml(parse_scene(kScene, kPath)).find("retention"), std::string::npos);

  EXPECT_EQ(error_of(with("{model: brooks_corey, air_entry_pressure: 10 kPa, n: 2}")),
            kPath + ":21: material.pore_fluid.retention.model: unknown model 'brooks_corey' (expected van_genuchten)");
  EXPECT_EQ(error_of(with("{model: van_genuchten, air_entry_pressure: 0 kPa, n: 2}")),
            kPath + ":21: material.pore_fluid.retention.air_entry_pressure: 0 must be > 0");
  EXPECT_EQ(error_of(with("{model: van_genuchten, air_entry_pressure: 10 kPa, n: 1}")),
            kPath + ":21: material.pore_fluid.retention.n: 1 must be > 1 (m = 1 - 1/n > 0)");
  EXPECT_EQ(error_of(with("{model: van_genuchten, air_entry_pressure: 10 kPa, n: 2, residual_saturation: 1}")),
            kPath +
                ":21: material.pore_fluid.retention.residual_saturation: 1 is out of range (expected 0 <= "
                "residual_saturation < 1)");
  auto e = error_of(with("{model: van_genuchten, air_entry_pressure: 10 kPa, n: 2, m: 0.5}"));
  EXPECT_NE(e.find("material.pore_fluid.retention.m: unknown key (expected one of: model, air_entry_pressure, n, "
                   "residual_saturation)"),
            std::string::npos)
      << e;
  e = error_of(with("{model: van_genuchten, n: 2}"));
  EXPECT_NE(e.find("material.pore_fluid.retention.air_entry_pressure: missing required key"), std::string::npos) << e;
  e = error_of(with("{air_entry_pressure: 10 kPa, n: 2}"));
  EXPECT_NE(e.find("material.pore_fluid.retention.model: missing required key"), std::string::npos) << e;
}

// A hydrostatic start needs gravity and the free surface's level, and the level goes with it only.
TEST(ScenePoreFluid, HydrostaticNeedsGravityAndItsLevel) {
  auto e = error_of(replace(kScene, "initial_pressure: -10 kPa", "initial_pressure: hydrostatic"));
  EXPECT_EQ(e, kPath +
                   ":20: material.pore_fluid.initial_pressure: hydrostatic needs the effect 'gravity' (the fluid's "
                   "weight sets the pressure)");
  const std::string wet = replace(kScene, "effects: [pore_fluid]", "effects: [pore_fluid, gravity]");
  e = error_of(replace(wet, "initial_pressure: -10 kPa", "initial_pressure: hydrostatic"));
  EXPECT_NE(e.find("material.pore_fluid.free_surface: missing required key"), std::string::npos) << e;
  e = error_of(replace(wet, "initial_pressure: -10 kPa", "initial_pressure: -10 kPa\n    free_surface: 1 m"));
  EXPECT_NE(e.find("material.pore_fluid.free_surface: goes with initial_pressure: hydrostatic"), std::string::npos)
      << e;
  const Scene s = parse_scene(
      replace(wet, "initial_pressure: -10 kPa", "initial_pressure: hydrostatic\n    free_surface: 80 cm"), kPath);
  ASSERT_TRUE(s.material.pore_fluid->free_surface.has_value());
  EXPECT_DOUBLE_EQ(*s.material.pore_fluid->free_surface, 0.8);
  // The resolved scene writes it back.
  const Scene back = parse_scene(resolved_scene_yaml(s), "/elsewhere/scene.resolved.yaml");
  EXPECT_EQ(back.material.pore_fluid->free_surface, s.material.pore_fluid->free_surface);
}

TEST(ScenePoreFluid, BlockIsIgnoredWithAWarningWhileTheEffectIsOff) {
  const std::string dry = replace(kScene, "effects: [pore_fluid]", "effects: []");
  const Scene s = parse_scene(dry, kPath);
  EXPECT_FALSE(s.effects.pore_fluid);
  EXPECT_FALSE(s.material.pore_fluid.has_value());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0],
            kPath + ":15: material.pore_fluid: ignored because the effect 'pore_fluid' is not listed in effects");
  // Ignored means not read: a bad value in it does not stop the run.
  EXPECT_NO_THROW(parse_scene(dry, kPath, {"material.pore_fluid.permeability=-1"}));
  EXPECT_EQ(resolved_scene_yaml(s).find("pore_fluid"), std::string::npos);
}

// The resolved scene (SI numbers, defaults written out) reads back to the same parameters, bit
// for bit, and lists k' and n0 under `derived`.
TEST(ScenePoreFluid, ResolvedSceneReadsBackToTheSameFluid) {
  const Scene a = parse_scene(kScene, kPath, {"material.pore_fluid.fluid_viscosity=1.1 mPa*s"});
  const std::string yaml = resolved_scene_yaml(a);
  const Scene b = parse_scene(yaml, "/elsewhere/scene.resolved.yaml");
  EXPECT_EQ(b.effects, a.effects);
  ASSERT_TRUE(b.material.pore_fluid.has_value());
  const auto& fa = *a.material.pore_fluid;
  const auto& fb = *b.material.pore_fluid;
  EXPECT_EQ(fb.permeability, fa.permeability);
  EXPECT_EQ(fb.fluid_viscosity, fa.fluid_viscosity);
  EXPECT_EQ(fb.fluid_density, fa.fluid_density);
  EXPECT_EQ(fb.biot_coefficient, fa.biot_coefficient);
  EXPECT_EQ(fb.biot_modulus, fa.biot_modulus);
  EXPECT_EQ(fb.initial_pressure, fa.initial_pressure);
  EXPECT_EQ(b.material.solid_fraction, a.material.solid_fraction);
  EXPECT_TRUE(b.warnings.empty());
  EXPECT_NE(yaml.find("permeability: 1e-12\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("initial_pressure: -10000\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("porosity: 0.35\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("fluid_mobility_m2_per_Pa_s: "), std::string::npos) << yaml;
  EXPECT_EQ(resolved_scene_yaml(b), yaml);  // a fixed point of write + read
}
