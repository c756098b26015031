// From a scene to a model: material.viscoplasticity (with its defaults and --set overrides)
// resolves through the registry, and a wrong model name in the scene is refused with the
// file, the key and the valid names.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "solver/plasticity/material_registry.hpp"

namespace mppm::plasticity {
namespace {

using ::testing::HasSubstr;

// The shear-band case (workflows/shear-band), reduced to what the parser needs.
const std::string kScene = R"(mppm: 1
name: shear-band
dimension: 2
thickness: 10 mm
geometry:
  file: specimen.geo
  spacing: 2.5 mm
  horizon_factor: 2.05
material:
  density: 2000
  solid_fraction: 0.65
  lambda: 13.9 MPa
  mu: 20.8 MPa
  mu_c: 41.6 MPa
  couple_moduli: [0, 0, 83.3 N]
  length_scale: 2 mm
  viscoplasticity: {friction_angle: 35 deg, dilatancy_angle: 15 deg, cohesion: 0.35 MPa,
                    hardening: -1 MPa, viscosity: 0.01 MPa*s}
effects: [micropolar, viscoplasticity]
boundary_conditions:
  - {boundary: top,    type: velocity, value: [0, -0.05 m/s]}
  - {boundary: bottom, type: velocity, value: [0, 0.05 m/s]}
time:
  end: 0.1 s
  step: 7 us
)";
const std::string kPath = "/cases/shear-band/scene.yaml";

TEST(PlasticityScene, SceneDefaultsResolveToTheDruckerPragerPerzynaModel) {
  const Scene scene = parse_scene(kScene, kPath);
  const auto model = make_viscoplastic_model(scene.material, scene.path);
  ASSERT_EQ(model->name(), "drucker-prager-perzyna");
  const DruckerPragerParameters& p = dynamic_cast<const DruckerPragerPerzynaModel&>(*model).constants().parameters;
  EXPECT_NEAR(p.friction_angle, 35.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_NEAR(p.dilatancy_angle, 15.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(p.cohesion, 0.35e6);
  EXPECT_DOUBLE_EQ(p.hardening, -1e6);
  EXPECT_DOUBLE_EQ(p.viscosity, 1e4);
  EXPECT_DOUBLE_EQ(p.length_scale, 2e-3);
  EXPECT_GE(p.residual_cohesion, 0.0);
  EXPECT_LE(p.residual_cohesion, p.cohesion);
  EXPECT_EQ(p.cone_match, ConeMatch::triaxial_compression);
}

TEST(PlasticityScene, OverridesReachTheModel) {
  const Scene scene = parse_scene(
      kScene, kPath,
      {"material.viscoplasticity.cone_match=plane-strain", "material.viscoplasticity.friction_angle=25deg"});
  const auto model = make_viscoplastic_model(scene.material, scene.path);
  const DruckerPragerPerzyna& c = dynamic_cast<const DruckerPragerPerzynaModel&>(*model).constants();
  EXPECT_EQ(c.parameters.cone_match, ConeMatch::plane_strain);
  EXPECT_NEAR(c.parameters.friction_angle, 25.0 * std::numbers::pi / 180.0, 1e-15);
}

TEST(PlasticityScene, UnknownModelNameInSceneIsRefusedWithValidNames) {
  const Scene scene = parse_scene(kScene, kPath, {"material.viscoplasticity.model=von-mises"});
  try {
    make_viscoplastic_model(scene.material, scene.path);
    FAIL() << "von-mises is not a registered model";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_THAT(msg, HasSubstr(kPath));
    EXPECT_THAT(msg, HasSubstr("material.viscoplasticity.model: unknown model 'von-mises'"));
    EXPECT_THAT(msg, HasSubstr("valid models: drucker-prager-perzyna"));
  }
}

}  // namespace
}  // namespace mppm::plasticity
