// The pore fluid's boundary conditions (docs/scene.md, boundary_conditions): `pore_pressure` (a
// drained boundary) and `fluid_flux` (an inflow) read in SI with their labels and histories, only
// with the effect pore_fluid, the keys that do not fit them refused by name, one fluid condition
// per boundary, and the resolved scene read back unchanged.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "common/scene.hpp"

using namespace mppm;

namespace {
// A consolidation column: loaded and drained on top, fed on the left (line numbers matter).
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
  pore_fluid: {permeability: 1e-12 m^2, fluid_viscosity: 1 mPa*s, biot_modulus: 2 GPa}
effects: [pore_fluid]
boundary_conditions:
  - {boundary: top, type: traction, value: [0, -10 kPa]}
  - {boundary: top, type: pore_pressure, value: 0 Pa}
  - {boundary: left, type: fluid_flux, value: 1e-3 mm/s, ramp: 2 s}
  - {boundary: bottom, type: velocity, value: [0, 0]}
time:
  end: 10 s
)";

const std::string kPath = "/cases/consolidation/scene.yaml";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, kPath, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

const std::string kDrained = "  - {boundary: top, type: pore_pressure, value: 0 Pa}";
const std::string kFlux = "  - {boundary: left, type: fluid_flux, value: 1e-3 mm/s, ramp: 2 s}";
}  // namespace

TEST(SceneFluidBoundaries, ReadsDrainedAndFluxConditionsInSI) {
  const Scene s = parse_scene(kScene, kPath);
  ASSERT_EQ(s.boundary_conditions.size(), 4u);
  const BoundaryCondition& drained = s.boundary_conditions[1];
  EXPECT_EQ(drained.type, BoundaryType::pore_pressure);
  // A face may carry a load and a fluid condition: the fluid's label gets the type appended.
  EXPECT_EQ(s.boundary_conditions[0].name, "top");
  EXPECT_EQ(drained.name, "top_pore_pressure");
  EXPECT_EQ(drained.value.times, std::vector<double>{0.0});
  EXPECT_EQ(drained.value.values, std::vector<std::vector<double>>{{0.0}});
  EXPECT_EQ(drained.constrained, std::vector<bool>{true});
  const BoundaryCondition& flux = s.boundary_conditions[2];
  EXPECT_EQ(flux.type, BoundaryType::fluid_flux);
  EXPECT_EQ(flux.name, "left_fluid_flux");
  EXPECT_EQ(flux.value.times, (std::vector<double>{0.0, 2.0}));
  ASSERT_EQ(flux.value.values.size(), 2u);
  EXPECT_DOUBLE_EQ(flux.value.values[1][0], 1e-6);  // m/s, inflow per area
  EXPECT_DOUBLE_EQ(flux.traction_depth, 0.1);       // default: dx
  EXPECT_TRUE(s.warnings.empty());
  // Histories and depths as for the other conditions; a given name is kept.
  const Scene h = parse_scene(replace(replace(kScene, kDrained,
                                              "  - {name: drain, boundary: top, type: pore_pressure, history: "
                                              "[[0 s, 0 kPa], [1 s, 5 kPa]]}"),
                                      kFlux, "  - {boundary: left, type: fluid_flux, value: 2e-6, depth: 0.3 m}"),
                              kPath);
  EXPECT_EQ(h.boundary_conditions[1].name, "drain");
  EXPECT_EQ(h.boundary_conditions[1].value.values, (std::vector<std::vector<double>>{{0.0}, {5e3}}));
  EXPECT_DOUBLE_EQ(h.boundary_conditions[2].traction_depth, 0.3);
}

TEST(SceneFluidBoundaries, NeedTheEffectPoreFluid) {
  const std::string dry = replace(kScene, "effects: [pore_fluid]", "effects: []");
  EXPECT_EQ(error_of(dry),
            kPath + ":18: boundary_conditions[1].type: pore_pressure needs the effect pore_fluid (add it to effects)");
  EXPECT_EQ(error_of(replace(dry, kDrained + "\n", "")),
            kPath + ":18: boundary_conditions[1].type: fluid_flux needs the effect pore_fluid (add it to effects)");
  // The list of types names them.
  const auto e = error_of(replace(kScene, "type: pore_pressure", "type: porepressure"));
  EXPECT_NE(e.find("boundary_conditions[1].type: unknown type 'porepressure' (expected one of: velocity, "
                   "displacement, traction, pressure, pore_pressure, fluid_flux); did you mean 'pore_pressure'?"),
            std::string::npos)
      << e;
}

TEST(SceneFluidBoundaries, KeysThatDoNotFitAreRefusedByName) {
  const std::pair<std::string, std::string> bad[] = {
      {"  - {boundary: top, type: pore_pressure, value: 0 Pa, depth: 0.2 m}",
       "boundary_conditions[1].depth: only traction, pressure and fluid_flux conditions have a loaded depth (the "
       "layer of a pore_pressure condition is as deep as the horizon)"},
      {"  - {boundary: top, type: pore_pressure, value: 0 Pa, rotation: 0.01}",
       "boundary_conditions[1].rotation: micro-rotation can be prescribed only on velocity or displacement "
       "conditions (not on a pore_pressure condition)"},
      {"  - {boundary: top, type: pore_pressure, value: 0 Pa, rotation_rate: 1}",
       "boundary_conditions[1].rotation_rate: micro-rotation can be prescribed only on velocity or displacement "
       "conditions (not on a pore_pressure condition)"},
      {"  - {boundary: top, type: pore_pressure, value: free}",
       "boundary_conditions[1].value: only velocity and displacement components can be free"},
      {"  - {boundary: top, type: pore_pressure, value: [0 Pa, 0 Pa]}",
       "boundary_conditions[1].value: expected one value, a pressure or stress (e.g. Pa, MPa), for a pore_pressure "
       "condition"},
      {"  - {boundary: top, type: pore_pressure, value: 1 m/s}",
       "boundary_conditions[1].value: \"1 m/s\" is a velocity"},
      {"  - {boundary: top, type: pore_pressure, history: [[0, 0], [1, free]]}",
       "boundary_conditions[1].history[1][1]: only velocity and displacement components can be free"},
  };
  for (const auto& [line, expected] : bad) {
    const auto e = error_of(replace(kScene, kDrained, line));
    EXPECT_EQ(e.rfind(kPath + ":18: " + expected, 0), 0u) << line << "\n" << e;
  }
  const auto e = error_of(replace(kScene, kFlux, "  - {boundary: left, type: fluid_flux, value: 1 kPa}"));
  EXPECT_EQ(e.rfind(kPath + ":19: boundary_conditions[2].value: \"1 kPa\" is a pressure or stress", 0), 0u) << e;
}

// A boundary is drained or fed, once: a second fluid condition with the same selection is refused.
TEST(SceneFluidBoundaries, OneFluidConditionPerBoundary) {
  const auto both = error_of(replace(kScene, kFlux, "  - {boundary: top, type: fluid_flux, value: 1e-6 m/s}"));
  EXPECT_EQ(both, kPath +
                      ":19: boundary_conditions[2]: a second fluid condition (fluid_flux) on 'top', which "
                      "boundary_conditions[1] ('top_pore_pressure') already gives a pore_pressure (a boundary is "
                      "drained or takes an inflow, once)");
  const auto twice =
      error_of(replace(kScene, kFlux, "  - {name: again, boundary: top, type: pore_pressure, value: 1 kPa}"));
  EXPECT_NE(twice.find("boundary_conditions[2]: a second fluid condition (pore_pressure) on 'top'"), std::string::npos)
      << twice;
}

TEST(SceneFluidBoundaries, ResolvedSceneReadsBackToTheSameConditions) {
  const Scene a = parse_scene(kScene, kPath);
  const std::string yaml = resolved_scene_yaml(a);
  const Scene b = parse_scene(yaml, "/elsewhere/scene.resolved.yaml");
  ASSERT_EQ(b.boundary_conditions.size(), a.boundary_conditions.size());
  for (std::size_t k = 0; k < a.boundary_conditions.size(); ++k) {
    const BoundaryCondition &x = a.boundary_conditions[k], &y = b.boundary_conditions[k];
    EXPECT_EQ(y.name, x.name) << k;
    EXPECT_EQ(y.type, x.type) << k;
    EXPECT_EQ(y.value.times, x.value.times) << k;
    EXPECT_EQ(y.value.values, x.value.values) << k;
    EXPECT_EQ(y.constrained, x.constrained) << k;
    EXPECT_EQ(y.traction_depth, x.traction_depth) << k;
    EXPECT_EQ(y.selector.fingerprint(), x.selector.fingerprint()) << k;
  }
  // A drained layer has no loaded depth to write; a flux has.
  EXPECT_NE(yaml.find("type: pore_pressure\n    value: 0\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("type: fluid_flux\n    history:\n"), std::string::npos) << yaml;
  EXPECT_EQ(resolved_scene_yaml(b), yaml);  // a fixed point of write + read
}
