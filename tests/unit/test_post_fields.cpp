// Units of the postprocessor with hand-calculated answers: stress invariants, load.csv
// reduction and peak load, the resolved-scene blocks as JSON.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "postprocess/derived_fields.hpp"
#include "postprocess/json_value.hpp"
#include "postprocess/load_curve.hpp"
#include "postprocess/yaml_to_json.hpp"

namespace {

using namespace mppm::post;

std::vector<double> tensor(double xx, double xy, double xz, double yx, double yy, double yz, double zx, double zy,
                           double zz) {
  return {xx, xy, xz, yx, yy, yz, zx, zy, zz};
}

TEST(PostDerivedFields, VonMisesAndMeanStressOfKnownStates) {
  // Uniaxial s: q = |s|, p = s/3. Pure shear t: q = sqrt(3) t, p = 0. Hydrostatic: q = 0.
  // A skew-symmetric part (Cosserat) does not count in q. Exact up to rounding: 1e-12 relative.
  std::vector<double> stress;
  for (const auto& t : {tensor(-8e6, 0, 0, 0, 0, 0, 0, 0, 0), tensor(0, 3e6, 0, 3e6, 0, 0, 0, 0, 0),
                        tensor(5e5, 0, 0, 0, 5e5, 0, 0, 0, 5e5), tensor(0, 3e6 + 7e5, 0, 3e6 - 7e5, 0, 0, 0, 0, 0)})
    stress.insert(stress.end(), t.begin(), t.end());
  const auto q = von_mises_stress(stress);
  const auto p = mean_stress(stress);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_NEAR(q[0], 8e6, 1e-12 * 8e6);
  EXPECT_NEAR(p[0], -8e6 / 3.0, 1e-12 * 8e6);
  EXPECT_NEAR(q[1], std::sqrt(3.0) * 3e6, 1e-12 * 3e6);
  EXPECT_EQ(p[1], 0.0);
  EXPECT_NEAR(q[2], 0.0, 1e-12 * 5e5);
  EXPECT_NEAR(p[2], 5e5, 1e-12 * 5e5);
  EXPECT_NEAR(q[3], q[1], 1e-12 * 3e6);
  EXPECT_THROW(von_mises_stress(std::vector<double>(8, 0.0)), std::invalid_argument);
}

TEST(PostDerivedFields, Magnitude) {
  const auto m = magnitude({3, 4, 0, 0, 0, 0, -1, 2, 2}, 3);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_DOUBLE_EQ(m[0], 5.0);
  EXPECT_DOUBLE_EQ(m[1], 0.0);
  EXPECT_DOUBLE_EQ(m[2], 3.0);
}

class PostLoadCurve : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("mppm_post_load_" + name + ".csv");
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
};

TEST_F(PostLoadCurve, AxisMainBoundaryAndPeak) {
  // left: pressure (force along x only); top: velocity moving down with a reaction that peaks
  // at row 2; bottom: velocity moving up. Main = first kinematic boundary that moves: top.
  const auto path = write("axis",
                          "time_s,left_ux_m,left_uy_m,left_Fx_N,left_Fy_N,top_ux_m,top_uy_m,top_Fx_N,top_Fy_N,"
                          "bottom_ux_m,bottom_uy_m,bottom_Fx_N,bottom_Fy_N\n"
                          "0,0,0,100,0,0,0,0,0,0,0,0,0\n"
                          "1e-3,1e-6,0,100,1,0,-5e-5,2,-800,0,5e-5,-2,810\n"
                          "2e-3,2e-6,0,100,1,0,-1e-4,3,-1200,0,1e-4,-3,1190\n"
                          "3e-3,3e-6,0,100,1,0,-1.5e-4,1,-900,0,1.5e-4,-1,905\n");
  const auto table = read_load_table(path);
  const auto curve = make_load_curve(table);
  ASSERT_EQ(curve.boundaries.size(), 3u);
  EXPECT_EQ(curve.boundaries[0].name, "left");
  EXPECT_EQ(curve.boundaries[0].axis, 0);
  EXPECT_EQ(curve.boundaries[1].axis, 1);
  EXPECT_EQ(curve.force[1][2], -1200.0);
  EXPECT_EQ(curve.displacement[1][3], -1.5e-4);
  const auto peak = find_peak_load(curve, {"top", "bottom"});
  EXPECT_EQ(peak.boundary, "top");
  EXPECT_EQ(*peak.peak_load_N, 1200.0);
  EXPECT_EQ(*peak.displacement_at_peak_m, 1e-4);
  EXPECT_EQ(*peak.time_at_peak_s, 2e-3);
  // Without kinematic boundaries (traction-loaded plate): the largest peak force wins.
  EXPECT_EQ(find_peak_load(curve, {}).boundary, "top");
  const std::string csv = load_curve_csv(curve);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "time_s,left_ux_m,left_Fx_N,top_uy_m,top_Fy_N,bottom_uy_m,bottom_Fy_N");
}

TEST_F(PostLoadCurve, IncompleteLastLineIsDroppedBadRowIsAnError) {
  const auto table = read_load_table(write("incomplete", "time_s,a_ux_m,a_Fx_N\n0,0,0\n1,2,3\n2,4"));
  EXPECT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.notes.size(), 1u);
  try {
    read_load_table(write("bad", "time_s,a_ux_m,a_Fx_N\n0,0,0\n1,two,3\n2,4,5\n"));
    FAIL() << "a bad row must be an error";
  } catch (const mppm::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_load_table(write("header", "t,a\n0,1\n")), mppm::InputError);
  EXPECT_THROW(read_load_table("/nonexistent/load.csv"), mppm::InputError);
}

// The pore fluid's boundaries have volume columns in load.csv (NAME_outflow_m3_per_s, NAME_outflow_m3,
// NAME_inflow_m3_per_s, NAME_inflow_m3; docs/stages.md): they are no load curves, and the load
// curves of the other boundaries are those of a table without them.
TEST_F(PostLoadCurve, FluidBoundaryColumnsAreNotLoadCurves) {
  const auto path = write("fluid",
                          "time_s,top_ux_m,top_uy_m,top_Fx_N,top_Fy_N,top_pore_pressure_outflow_m3_per_s,"
                          "top_pore_pressure_outflow_m3,left_fluid_flux_inflow_m3_per_s,left_fluid_flux_inflow_m3\n"
                          "0,0,0,0,0,0,0,0,0\n"
                          "1,0,-1e-5,0,-100,2e-9,2e-9,1e-9,1e-9\n"
                          "2,0,-2e-5,0,-100,1e-9,3e-9,1e-9,2e-9\n");
  const auto curve = make_load_curve(read_load_table(path));
  ASSERT_EQ(curve.boundaries.size(), 1u);
  EXPECT_EQ(curve.boundaries[0].name, "top");
  EXPECT_EQ(curve.boundaries[0].axis, 1);
  EXPECT_EQ(curve.force[0][1], -100.0);
  const std::string csv = load_curve_csv(curve);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "time_s,top_uy_m,top_Fy_N");
  EXPECT_EQ(find_peak_load(curve, {}).boundary, "top");
}

TEST(PostResolvedBlocks, QuantitiesBecomeSINumbersAnglesDegrees) {
  const YAML::Node node = YAML::Load(
      "{density: 2650, lambda: 14000000000, friction_angle: 35 deg, cohesion: 0.35 MPa, model: "
      "drucker-prager-perzyna,\n"
      " couple_moduli: [0, 0, 56000], name: '1', value: [free, -0.05], on: true}");
  const std::string json = yaml_to_json(node).dump();
  const YAML::Node back = YAML::Load(json);
  EXPECT_EQ(back["density"].as<int>(), 2650);
  EXPECT_DOUBLE_EQ(back["lambda"].as<double>(), 14e9);
  EXPECT_NEAR(back["friction_angle"].as<double>(), 35.0, 1e-12);
  EXPECT_NEAR(back["cohesion"].as<double>(), 3.5e5, 1e-6);
  EXPECT_EQ(back["model"].as<std::string>(), "drucker-prager-perzyna");
  EXPECT_EQ(back["value"][0].as<std::string>(), "free");
  EXPECT_NE(json.find("\"name\": \"1\""), std::string::npos) << "names stay strings: " << json;
  EXPECT_NE(json.find("\"on\": true"), std::string::npos) << json;
}

TEST(PostJson, NumbersRoundTripAndNonFiniteIsNull) {
  auto object = JsonValue::object();
  object.set("third", 1.0 / 3.0);
  object.set("nan", std::nan(""));
  object.set("none", std::optional<double>());
  object.set("text", "a \"quoted\"\nline");
  const std::string text = object.dump();
  const YAML::Node back = YAML::Load(text);
  EXPECT_EQ(back["third"].as<double>(), 1.0 / 3.0);
  EXPECT_TRUE(back["nan"].IsNull());
  EXPECT_TRUE(back["none"].IsNull());
  EXPECT_EQ(back["text"].as<std::string>(), "a \"quoted\"\nline");
}

}  // namespace
