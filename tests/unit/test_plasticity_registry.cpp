// Run-time selection of the viscoplastic model by name (material.viscoplasticity.model):
// the default resolves, an unknown name is refused with the list of valid ones, and bad
// parameters are reported with the file and key (exit code 2 at the stage level).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "common/input_error.hpp"
#include "solver/plasticity/material_registry.hpp"

namespace mppm::plasticity {
namespace {

using ::testing::HasSubstr;

Material case1_material() {
  Material m;
  m.density = 2000;
  m.lambda = 13.9e6;
  m.mu = 20.8e6;
  m.mu_c = 41.6e6;
  m.couple_moduli = {0.0, 0.0, 83.3};
  m.length_scale = 2e-3;
  ViscoplasticParameters vp;
  vp.friction_angle = 35.0 * std::numbers::pi / 180.0;
  vp.dilatancy_angle = 15.0 * std::numbers::pi / 180.0;
  vp.cohesion = 0.35e6;
  vp.hardening = -1e6;
  vp.viscosity = 0.01e6;
  vp.residual_cohesion = 0.0035e6;
  m.viscoplasticity = vp;
  return m;
}

std::string message_of(const Material& m) {
  try {
    make_viscoplastic_model(m, "shear.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PlasticityRegistry, DefaultModelResolvesAndMatchesFreeFunction) {
  const Material m = case1_material();
  EXPECT_EQ(m.viscoplasticity->model, "drucker-prager-perzyna");  // the scene's default
  const auto model = make_viscoplastic_model(m, "shear.yaml");
  ASSERT_NE(model, nullptr);
  EXPECT_EQ(model->name(), "drucker-prager-perzyna");
  const auto* dp = dynamic_cast<const DruckerPragerPerzynaModel*>(model.get());
  ASSERT_NE(dp, nullptr);
  EXPECT_EQ(dp->constants().parameters.length_scale, 2e-3);
  EXPECT_EQ(dp->constants().parameters.cone_match, ConeMatch::triaxial_compression);

  const CosseratElasticity<2> el{m.lambda, m.mu, m.mu_c, m.couple_moduli[2]};
  Eigen::Matrix3d eps = Eigen::Matrix3d::Zero();
  eps(0, 1) = eps(1, 0) = 0.03;
  eps(1, 1) = -0.005;
  const PlasticState<2> s0 = model->initial_state_2d();
  EXPECT_EQ(s0.cohesion, 0.35e6);
  const PointUpdate<2> a = model->update(eps, Eigen::Vector2d(1.0, 2.0), s0, el, 7e-6);
  const PointUpdate<2> b = drucker_prager_perzyna_update(
      eps, Eigen::Vector2d(1.0, 2.0), s0, el, make_drucker_prager_perzyna(drucker_prager_parameters(m)), 7e-6);
  EXPECT_TRUE(a.plastic);
  EXPECT_EQ(a.stress, b.stress);
  EXPECT_EQ(a.state.equivalent_plastic_strain, b.state.equivalent_plastic_strain);
}

TEST(PlasticityRegistry, PlaneStrainMatchIsSelectedByTheSceneKey) {
  Material m = case1_material();
  m.viscoplasticity->cone_match = ConeMatch::plane_strain;
  const auto model = make_viscoplastic_model(m, "shear.yaml");
  const auto& dp = dynamic_cast<const DruckerPragerPerzynaModel&>(*model);
  EXPECT_EQ(dp.constants().parameters.cone_match, ConeMatch::plane_strain);
  const ConeCoefficients expected =
      cone_coefficients(m.viscoplasticity->friction_angle, m.viscoplasticity->dilatancy_angle, ConeMatch::plane_strain);
  EXPECT_EQ(dp.constants().cone.friction_slope, expected.friction_slope);
}

TEST(PlasticityRegistry, UnknownModelListsValidNames) {
  Material m = case1_material();
  m.viscoplasticity->model = "drucker-prager";
  const std::string msg = message_of(m);
  EXPECT_THAT(msg, HasSubstr("shear.yaml"));
  EXPECT_THAT(msg, HasSubstr("material.viscoplasticity.model"));
  EXPECT_THAT(msg, HasSubstr("'drucker-prager'"));
  EXPECT_THAT(msg, HasSubstr("valid models: drucker-prager-perzyna"));
}

TEST(PlasticityRegistry, ListOfValidNamesFollowsTheTable) {
  MaterialRegistry registry;
  const MaterialRegistry::Factory none = [](const Material&) -> std::unique_ptr<ViscoplasticModel> { return nullptr; };
  registry.add("zeta-model", none);
  registry.add("alpha-model", none);
  EXPECT_THROW(registry.add("alpha-model", none), std::logic_error);
  EXPECT_TRUE(registry.contains("zeta-model"));
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"alpha-model", "zeta-model"}));
  Material m = case1_material();
  try {
    registry.create(m, "s.yaml");
    FAIL() << "drucker-prager-perzyna is not in this table";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("(valid models: alpha-model, zeta-model)"));
  }
}

TEST(PlasticityRegistry, BadParametersNameFileAndKey) {
  {
    Material m = case1_material();
    m.viscoplasticity->friction_angle = 2.0;  // rad, > 90 deg
    EXPECT_THAT(message_of(m),
                HasSubstr("shear.yaml: material.viscoplasticity.friction_angle: must be in [0, 90) deg"));
  }
  {
    Material m = case1_material();
    m.viscoplasticity->viscosity = -1.0;
    EXPECT_THAT(message_of(m), HasSubstr("material.viscoplasticity.viscosity: must be"));
  }
  {
    Material m = case1_material();
    m.viscoplasticity->residual_cohesion = 1e6;  // above c0
    EXPECT_THAT(message_of(m), HasSubstr("material.viscoplasticity.residual_cohesion: must be in [0, cohesion]"));
  }
  {
    Material m = case1_material();
    m.length_scale = -1.0;
    EXPECT_THAT(message_of(m), HasSubstr("material.length_scale: must be"));
  }
  {
    Material m = case1_material();
    m.viscoplasticity.reset();
    EXPECT_THAT(message_of(m), HasSubstr("shear.yaml: material.viscoplasticity: missing"));
  }
}

}  // namespace
}  // namespace mppm::plasticity
