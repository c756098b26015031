// Scene parsing: example scene, defaults, --set overrides, error locations, resolved round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "tests/unit/scene_text_edits.hpp"

using namespace mppm;

namespace {
// The crack-branching example scene (line numbers matter for the error tests).
const std::string kExample = R"(mppm: 1
name: crack-branching
dimension: 2
thickness: 1 mm
geometry:
  file: ../../geometry/branching_plate.geo
  unit: m
  spacing: 0.5 mm
  horizon_factor: 4.05
  precracks: [notch]
material:
  density: 2650
  solid_fraction: 0.95
  lambda: 14 GPa
  mu: 14 GPa
  mu_c: 4.667 GPa
  couple_moduli: [0, 0, 56 kN]
  length_scale: 2 mm
  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm}
effects: [micropolar, damage]
boundary_conditions:
  - {boundary: top,    type: traction, value: [0, 8 MPa],  ramp: 6.25 us}
  - {boundary: bottom, type: traction, value: [0, -8 MPa], ramp: 6.25 us}
time:
  end: 60 us
  step: 0.025 us
output:
  interval: 0.25 us
  load_interval: 0.025 us
  fields: [displacement, rotation, damage]
numerics:
  stabilization: 0.1
)";

const std::string kPath = "/cases/crack/scene.yaml";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return mppm::testing::scene_error_of(text, kPath, overrides);
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  return mppm::testing::replace_once(std::move(text), from, to);
}
}  // namespace

TEST(Scene, ReadsTheSceneExampleInSI) {
  const Scene s = parse_scene(kExample, kPath);
  EXPECT_EQ(s.name, "crack-branching");
  EXPECT_EQ(s.dimension, 2);
  EXPECT_DOUBLE_EQ(s.thickness, 1e-3);
  EXPECT_EQ(s.geometry.file, "/geometry/branching_plate.geo");  // relative to the scene file
  EXPECT_DOUBLE_EQ(s.geometry.spacing, 0.5e-3);
  EXPECT_DOUBLE_EQ(s.geometry.horizon(), 4.05 * 0.5e-3);
  ASSERT_EQ(s.geometry.precracks.size(), 1u);
  EXPECT_EQ(s.geometry.precracks[0].physical_group, "notch");
  EXPECT_DOUBLE_EQ(s.material.lambda, 14e9);
  EXPECT_DOUBLE_EQ(s.material.couple_moduli[2], 56e3);
  EXPECT_DOUBLE_EQ(s.material.partial_density(), 2650 * 0.95);
  EXPECT_DOUBLE_EQ(s.material.micro_inertia(), 0.5 * std::numbers::pi * 2650 * 0.95 * 4e-6);
  ASSERT_TRUE(s.material.damage.has_value());
  EXPECT_DOUBLE_EQ(s.material.damage->critical_energy_release_rate, 160.0);
  EXPECT_TRUE(s.effects.micropolar && s.effects.damage && !s.effects.viscoplasticity && !s.effects.gravity);
  ASSERT_EQ(s.boundary_conditions.size(), 2u);
  const auto& top = s.boundary_conditions[0];
  EXPECT_EQ(top.name, "top");
  EXPECT_EQ(top.type, BoundaryType::traction);
  EXPECT_DOUBLE_EQ(top.traction_depth, 0.5e-3);  // default: dx
  // Ramp: 0 at t = 0, half at t0/2, full value from t0 on.
  EXPECT_DOUBLE_EQ(top.value.component_at(0.0, 1), 0.0);
  EXPECT_DOUBLE_EQ(top.value.component_at(3.125e-6, 1), 4e6);
  EXPECT_DOUBLE_EQ(top.value.component_at(50e-6, 1), 8e6);
  EXPECT_DOUBLE_EQ(*s.time.step, 0.025e-6);
  EXPECT_DOUBLE_EQ(s.output.interval, 0.25e-6);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.where("material.lambda"), kPath + ":14: material.lambda");
}

TEST(Scene, OverridesApplyBeforeValidation) {
  const Scene s = parse_scene(kExample, kPath,
                              {"material.mu=20GPa", "effects=[micropolar]", "time.step=auto",
                               "boundary_conditions[1].value=[0, -4 MPa]", "geometry.spacing=1 mm"});
  EXPECT_DOUBLE_EQ(s.material.mu, 20e9);
  EXPECT_FALSE(s.effects.damage);
  EXPECT_FALSE(s.time.step.has_value());
  EXPECT_DOUBLE_EQ(s.boundary_conditions[1].value.component_at(1.0, 1), -4e6);
  EXPECT_DOUBLE_EQ(s.geometry.spacing, 1e-3);
  // The damage block is now the parameter set of an effect that is off: a warning names it.
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("material.damage"), std::string::npos) << s.warnings[0];
  // An override that creates a new block.
  const Scene v = parse_scene(kExample, kPath,
                              {"effects=[micropolar,viscoplasticity]",
                               "material.viscoplasticity={friction_angle: 25deg, dilatancy_angle: 15 deg, cohesion: "
                               "0.35 MPa, viscosity: 0.01 MPa*s}",
                               "material.viscoplasticity.friction_angle=30deg"});
  ASSERT_TRUE(v.material.viscoplasticity.has_value());
  EXPECT_NEAR(v.material.viscoplasticity->friction_angle, 30 * std::numbers::pi / 180, 1e-15);
}

TEST(Scene, ErrorsNameFileLineKeyAndExpectation) {
  // Unknown key, with a suggestion.
  auto e = error_of(replace(kExample, "  lambda: 14 GPa", "  lamda: 14 GPa"));
  EXPECT_NE(e.find(kPath + ":14: material.lamda: unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'lambda'"), std::string::npos) << e;
  // Wrong dimension names the key and both units.
  e = error_of(replace(kExample, "mu: 14 GPa", "mu: 14 mm"));
  EXPECT_NE(e.find(kPath + ":15: material.mu:"), std::string::npos) << e;
  EXPECT_NE(e.find("length"), std::string::npos) << e;
  EXPECT_NE(e.find("pressure"), std::string::npos) << e;
  // Missing required key names the parent's line.
  e = error_of(replace(kExample, "  spacing: 0.5 mm\n", ""));
  EXPECT_NE(e.find("geometry.spacing: missing required key"), std::string::npos) << e;
  // Physically impossible values.
  e = error_of(replace(kExample, "solid_fraction: 0.95", "solid_fraction: 1.5"));
  EXPECT_NE(e.find(":13: material.solid_fraction"), std::string::npos) << e;
  e = error_of(replace(kExample, "mu: 14 GPa", "mu: -1 GPa"));
  EXPECT_NE(e.find("material.mu"), std::string::npos) << e;
  // Unknown effect.
  e = error_of(replace(kExample, "[micropolar, damage]", "[micropolar, dammage]"));
  EXPECT_NE(e.find("effects[1]: unknown effect 'dammage'"), std::string::npos) << e;
  // An effect listed without its parameters.
  e = error_of(replace(kExample, "  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm}\n", ""));
  EXPECT_NE(e.find("material.damage: missing"), std::string::npos) << e;
  // Errors from --set name the override.
  e = error_of(kExample, {"material.mu=14 m"});
  EXPECT_NE(e.find("--set material.mu=14 m"), std::string::npos) << e;
  e = error_of(kExample, {"boundary_conditions[5].value=1"});
  EXPECT_NE(e.find("not an index"), std::string::npos) << e;
  // YAML syntax error reports the line.
  e = error_of("mppm: 1\ndimension: [2\n");
  EXPECT_NE(e.find(kPath + ":"), std::string::npos) << e;
  EXPECT_NE(e.find("not valid YAML"), std::string::npos) << e;
  // Empty scene.
  EXPECT_NE(error_of("").find("empty"), std::string::npos);
}

TEST(Scene, FreeComponentsHistoriesAndRotation) {
  const std::string text = replace(replace(kExample, "effects: [micropolar, damage]", "effects: [micropolar]"),
                                   "  - {boundary: top,    type: traction, value: [0, 8 MPa],  ramp: 6.25 us}\n",
                                   "  - {boundary: top, type: velocity, value: [free, -0.05 m/s], rotation_rate: 0,\n"
                                   "     history: [[0, 1], [0.09 s, 1], [0.09 s, 0]]}\n"
                                   "  - {name: left, box: [[-1 mm, 0], [0, 40 mm]], type: pressure, value: 0.1 MPa}\n");
  const Scene s = parse_scene(text, kPath);
  const auto& top = s.boundary_conditions[0];
  EXPECT_FALSE(top.constrained[0]);
  EXPECT_TRUE(top.constrained[1]);
  EXPECT_DOUBLE_EQ(top.value.component_at(0.05, 1), -0.05);
  EXPECT_DOUBLE_EQ(top.value.component_at(0.09, 1), 0.0);  // the jump applies from its time on
  ASSERT_TRUE(top.rotation.has_value());
  EXPECT_DOUBLE_EQ(top.rotation->component_at(0.05, 0), 0.0);
  const auto& left = s.boundary_conditions[1];
  EXPECT_EQ(left.name, "left");
  ASSERT_TRUE(left.selector.box.has_value());
  EXPECT_DOUBLE_EQ((*left.selector.box)[0][0], -1e-3);
}

// An effect limited to a box (material.damage.region, material.viscoplasticity.region): read in
// scene units, written back by the resolved scene; a region without a box, or with another
// selector, is bad input naming the key.
TEST(Scene, EffectRegions) {
  const std::string damage = "  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm}\n";
  const std::string text = replace(kExample, damage,
                                   "  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm,\n"
                                   "           region: {box: [[40 mm, 20 mm], [100 mm, 60 mm]]}}\n");
  const Scene s = parse_scene(text, kPath);
  ASSERT_TRUE(s.material.damage->region.has_value());
  ASSERT_TRUE(s.material.damage->region->box.has_value());
  EXPECT_DOUBLE_EQ((*s.material.damage->region->box)[0][0], 40e-3);
  EXPECT_DOUBLE_EQ((*s.material.damage->region->box)[1][1], 60e-3);
  const Scene back = parse_scene(resolved_scene_yaml(s, {}), "/elsewhere/scene.resolved.yaml");
  ASSERT_TRUE(back.material.damage->region.has_value());
  EXPECT_EQ(*back.material.damage->region->box, *s.material.damage->region->box);
  std::string e = error_of(replace(
      kExample, damage, "  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm, region: {}}\n"));
  EXPECT_NE(e.find("material.damage.region: missing: box"), std::string::npos) << e;
  e = error_of(
      replace(kExample, damage,
              "  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm, region: {boundary: top}}\n"));
  EXPECT_NE(e.find("material.damage.region"), std::string::npos) << e;
  EXPECT_NE(e.find("boundary"), std::string::npos) << e;
  e = error_of(
      replace(kExample, damage,
              "  damage: {critical_energy_release_rate: 160 N/m, no_fail_depth: 2 mm, region: near the notch}\n"));
  EXPECT_NE(e.find("material.damage.region: expected {box:"), std::string::npos) << e;
}

// The spin is written as `rotation_rate` (the name of the boundary conditions' key and of the
// solver's field); the scene accepts that name for output.fields.
TEST(Scene, RotationRateIsAnOutputField) {
  const Scene s =
      parse_scene(replace(kExample, "fields: [displacement, rotation, damage]", "fields: [rotation_rate]"), kPath);
  ASSERT_EQ(s.output.fields.size(), 1u);
  EXPECT_EQ(s.output.fields[0], "rotation_rate");
  const std::string e =
      error_of(replace(kExample, "fields: [displacement, rotation, damage]", "fields: [angular_velocity]"));
  EXPECT_NE(e.find("output.fields"), std::string::npos) << e;
}

TEST(Scene, ResolvedSceneReadsBackToTheSameScene) {
  const std::string text =
      replace(kExample, "  - {boundary: top,    type: traction, value: [0, 8 MPa],  ramp: 6.25 us}\n",
              "  - {boundary: top, type: velocity, value: [free, -0.05 m/s], rotation_rate: 0.5,\n"
              "     history: [[0, 1], [0.09 s, 1], [0.09 s, 0]]}\n");
  // With the pore fluid next to damage (tests/unit/test_scene_pore_fluid.cpp checks the block alone).
  const Scene a = parse_scene(text, kPath,
                              {"effects=[micropolar, damage, pore_fluid]",
                               "material.pore_fluid={permeability: 3e-13 m^2, fluid_viscosity: 1.1 mPa*s, "
                               "biot_coefficient: 0.97, biot_modulus: 2.2 GPa, initial_pressure: 12.5 kPa}"});
  const std::string yaml = resolved_scene_yaml(a, {{"time_step_s", 2.5e-8}});
  const Scene b = parse_scene(yaml, "/elsewhere/scene.resolved.yaml");
  EXPECT_EQ(b.geometry.file, a.geometry.file);
  EXPECT_EQ(b.material.mu_c, a.material.mu_c);
  EXPECT_EQ(b.material.damage->no_fail_depth, a.material.damage->no_fail_depth);
  EXPECT_EQ(b.effects, a.effects);
  ASSERT_TRUE(a.material.pore_fluid.has_value() && b.material.pore_fluid.has_value());
  const auto& fa = *a.material.pore_fluid;
  const auto& fb = *b.material.pore_fluid;
  EXPECT_EQ(std::vector({fb.permeability, fb.fluid_viscosity, fb.fluid_density, fb.biot_coefficient, fb.biot_modulus,
                         fb.initial_pressure}),
            std::vector({fa.permeability, fa.fluid_viscosity, fa.fluid_density, fa.biot_coefficient, fa.biot_modulus,
                         fa.initial_pressure}));
  ASSERT_EQ(b.boundary_conditions.size(), a.boundary_conditions.size());
  for (std::size_t k = 0; k < a.boundary_conditions.size(); ++k) {
    EXPECT_EQ(b.boundary_conditions[k].value.times, a.boundary_conditions[k].value.times);
    EXPECT_EQ(b.boundary_conditions[k].value.values, a.boundary_conditions[k].value.values);
    EXPECT_EQ(b.boundary_conditions[k].constrained, a.boundary_conditions[k].constrained);
    EXPECT_EQ(b.boundary_conditions[k].rotation.has_value(), a.boundary_conditions[k].rotation.has_value());
    if (a.boundary_conditions[k].rotation) {
      EXPECT_EQ(b.boundary_conditions[k].rotation->values, a.boundary_conditions[k].rotation->values);
    }
  }
  EXPECT_EQ(b.time.step, a.time.step);
  EXPECT_EQ(b.output.fields, a.output.fields);
  EXPECT_NE(yaml.find("time_step_s"), std::string::npos);
}

// The named choices are enums in the Scene, read and written by the same name table.
TEST(Scene, NamedChoicesAreReadAsEnumsAndWrittenBackByName) {
  const Scene lattice = parse_scene(kExample, kPath);
  EXPECT_EQ(lattice.material.damage->calibration, DamageCalibration::lattice);  // the default
  for (const auto& [value, name] : kDamageCalibrationNames) {
    const Scene s = parse_scene(kExample, kPath, {std::string("material.damage.calibration=") + name});
    EXPECT_EQ(s.material.damage->calibration, value) << name;
    EXPECT_NE(resolved_scene_yaml(s).find(std::string("calibration: ") + name), std::string::npos) << name;
    EXPECT_EQ(parse_scene(resolved_scene_yaml(s), kPath).material.damage->calibration, value) << name;
  }
  const std::string vp =
      "material.viscoplasticity={friction_angle: 25deg, dilatancy_angle: 15 deg, "
      "cohesion: 0.35 MPa, viscosity: 0.01 MPa*s}";
  const Scene outer = parse_scene(kExample, kPath, {"effects=[micropolar,viscoplasticity]", vp});
  EXPECT_EQ(outer.material.viscoplasticity->cone_match, ConeMatch::triaxial_compression);  // the default
  for (const auto& [value, name] : kConeMatchNames) {
    const Scene s = parse_scene(
        kExample, kPath,
        {"effects=[micropolar,viscoplasticity]", vp, std::string("material.viscoplasticity.cone_match=") + name});
    EXPECT_EQ(s.material.viscoplasticity->cone_match, value) << name;
    EXPECT_STREQ(to_string(value), name);
    EXPECT_NE(resolved_scene_yaml(s).find(std::string("cone_match: ") + name), std::string::npos) << name;
  }
  EXPECT_EQ(error_of(kExample, {"material.damage.calibration=latice"}),
            kPath +
                ": --set material.damage.calibration=latice: material.damage.calibration: unknown calibration "
                "'latice' (expected lattice, continuum or dissipation)");
  EXPECT_EQ(error_of(replace(kExample, "no_fail_depth: 2 mm}", "no_fail_depth: 2 mm, calibration: bulk}")),
            kPath +
                ":19: material.damage.calibration: unknown calibration 'bulk' (expected lattice, continuum or "
                "dissipation)");
  const auto e =
      error_of(kExample, {"effects=[micropolar,viscoplasticity]", vp, "material.viscoplasticity.cone_match=triaxial"});
  EXPECT_NE(e.find(": material.viscoplasticity.cone_match: unknown match 'triaxial' (expected triaxial-compression "
                   "or plane-strain)"),
            std::string::npos)
      << e;
}

// The thresholds of numerics: today's values by default, written to the resolved scene, read back,
// and a bad value names its key.
TEST(Scene, NumericsThresholdsDefaultEchoAndValidate) {
  const Scene s = parse_scene(kExample, kPath);
  EXPECT_EQ(s.numerics.energy_check_start_step, 50);
  EXPECT_EQ(s.numerics.detach_energy_rise, 0.5);
  EXPECT_EQ(s.numerics.overload_factor, 1.5);
  EXPECT_EQ(s.numerics.damaged_frequency_ratio, 3.5);
  const std::string yaml = resolved_scene_yaml(s);
  for (const char* line : {"energy_check_start_step: 50", "detach_energy_rise: 0.5", "overload_factor: 1.5",
                           "damaged_frequency_ratio: 3.5", "flow_integration: auto", "step_estimate: patch"}) {
    EXPECT_NE(yaml.find(line), std::string::npos) << line << "\n" << yaml;
  }
  const Scene t = parse_scene(kExample, kPath,
                              {"numerics.energy_check_start_step=200", "numerics.detach_energy_rise=0.25",
                               "numerics.overload_factor=3", "numerics.damaged_frequency_ratio=2",
                               "numerics.flow_integration=explicit", "numerics.step_estimate=whole_model"});
  const Scene back = parse_scene(resolved_scene_yaml(t), kPath);
  EXPECT_EQ(back.numerics.energy_check_start_step, 200);
  EXPECT_EQ(back.numerics.detach_energy_rise, 0.25);
  EXPECT_EQ(back.numerics.overload_factor, 3.0);
  EXPECT_EQ(back.numerics.damaged_frequency_ratio, 2.0);
  EXPECT_EQ(back.numerics.flow_integration, FlowIntegration::explicit_substeps);
  EXPECT_EQ(s.numerics.step_estimate, StepEstimate::patch);
  EXPECT_EQ(back.numerics.step_estimate, StepEstimate::whole_model);
  const std::pair<const char*, const char*> bad[] = {
      {"numerics.energy_check_start_step=-1", "numerics.energy_check_start_step: must be >= 0"},
      {"numerics.energy_check_start_step=2.5", "numerics.energy_check_start_step: \"2.5\" is not an integer"},
      {"numerics.detach_energy_rise=-0.1", "numerics.detach_energy_rise: -0.1 must be >= 0"},
      {"numerics.detach_energy_rise=inf", "numerics.detach_energy_rise: \"inf\" is not a finite number"},
      {"numerics.overload_factor=0", "numerics.overload_factor: 0 must be > 0"},
      {"numerics.damaged_frequency_ratio=0.5", "numerics.damaged_frequency_ratio: 0.5 must be >= 1"},
      {"numerics.damaged_frequency_ratio=1 mm", "numerics.damaged_frequency_ratio: \"1 mm\" is a length"},
      {"numerics.flow_integration=implicit", "numerics.flow_integration: unknown flow integration 'implicit'"},
      {"numerics.step_estimate=local", "numerics.step_estimate: unknown critical step estimate 'local'"}};
  for (const auto& [set, expected] : bad) {
    const auto e = error_of(kExample, {set});
    EXPECT_NE(e.find(expected), std::string::npos) << set << ": " << e;
  }
}

// crack_area (the crack surface of the broken bonds, docs/theory.md section 7) is a field of 3-D
// damage runs, written by default there; a 2-D scene that asks for it gets a warning, since 2-D
// runs measure the crack length instead.
TEST(Scene, CrackAreaIsAFieldOf3dDamageRuns) {
  const std::string block = R"(mppm: 1
dimension: 3
geometry: {file: block.step, unit: mm, spacing: 1 mm, horizon_factor: 3.015}
material: {density: 2650 kg/m3, lambda: 10 GPa, mu: 5 GPa, damage: {critical_energy_release_rate: 100 J/m^2}}
effects: [damage]
boundary_conditions:
  - {name: clamp, entities: [12], type: displacement, value: [0, 0, 0]}
time: {end: 10 us, step: 0.1 us}
)";
  const auto has_crack_area = [](const Scene& s) {
    return std::find(s.output.fields.begin(), s.output.fields.end(), "crack_area") != s.output.fields.end();
  };
  EXPECT_TRUE(has_crack_area(parse_scene(block, kPath)));
  EXPECT_FALSE(has_crack_area(parse_scene(replace(block, "effects: [damage]", "effects: []"), kPath)));
  EXPECT_FALSE(has_crack_area(parse_scene(kExample, kPath)));
  const Scene asked = parse_scene(
      replace(kExample, "fields: [displacement, rotation, damage]", "fields: [displacement, crack_area]"), kPath);
  EXPECT_FALSE(has_crack_area(asked));
  ASSERT_FALSE(asked.warnings.empty());
  EXPECT_NE(asked.warnings.back().find("'crack_area' is written in 3-D runs only"), std::string::npos)
      << asked.warnings.back();
}
