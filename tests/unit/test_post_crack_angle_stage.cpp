// The crack angle through mppm-postprocess: the summary keys on the fixture run (a straight
// crack growing along +x from a damaged pre-crack, tests/unit/test_post_run_fixture.cpp), the
// --crack-tip / --crack-direction / --crack-angle-range / --crack-angle-time options, the
// snapshot the angle is measured on, and bad option values (exit code 2, a message naming the
// option, nothing written).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "test_post_command.hpp"
#include "test_post_run_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mppm::post::testing;

// The fixture: 40 x 30 mm, dx 1 mm, delta 3.015 mm; the pre-crack is the band |y - 15 mm| < dx
// for x < 8 mm (tip at x = 7.5 mm); snapshots at 0, 1, 2 and 3 us, where the crack's last
// column is x = 7.5, 14.5, 20.5 and 27.5 mm: 0, 7, 13 and 20 mm from the tip.
constexpr double kHorizon = 3.015e-3;

YAML::Node postprocess(const std::string& name, const std::vector<std::string>& extra) {
  const std::string dir = scratch_directory(name);
  write_run_directory(dir + "/run", RunFixture{});
  std::vector<std::string> argv{postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet", "--no-plot"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const auto r = run_command(argv);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return YAML::LoadFile(dir + "/post/summary.json");
}

TEST(PostCrackAngleStage, SummaryOfAStraightCrack) {
  const YAML::Node summary = postprocess("crack_angle_default", {});
  // The band is symmetric about y = 15 mm: the fit is exactly along +x.
  ASSERT_EQ(summary["crack_angle_deg"].size(), 1u);
  EXPECT_NEAR(summary["crack_angle_deg"][0].as<double>(), 0.0, 1e-9);
  ASSERT_EQ(summary["crack_angles"].size(), 1u);
  const YAML::Node crack = summary["crack_angles"][0];
  EXPECT_EQ(crack["tip_index"].as<int>(), 0);
  EXPECT_EQ(crack["crack_index"].as<int>(), 0);
  // The tip: the last pre-crack column (x = 7.5 mm), on the band's axis.
  EXPECT_NEAR(crack["tip_m"][0].as<double>(), 7.5e-3, 1e-9);
  EXPECT_NEAR(crack["tip_m"][1].as<double>(), 15e-3, 1e-9);
  EXPECT_NEAR(crack["precrack_direction"][0].as<double>(), 1.0, 1e-12);
  EXPECT_NEAR(crack["signed_angle_deg"].as<double>(), 0.0, 1e-9);
  EXPECT_NEAR(crack["fit_direction"][0].as<double>(), 1.0, 1e-12);
  EXPECT_NEAR(crack["fit_point_m"][1].as<double>(), 15e-3, 1e-9);
  EXPECT_GT(crack["points"].as<int>(), 10);
  EXPECT_DOUBLE_EQ(crack["range_from_m"].as<double>(), 2 * kHorizon);
  EXPECT_DOUBLE_EQ(crack["range_to_m"].as<double>(), 12 * kHorizon);
  // The crack never reaches 12 horizons (36 mm) from the tip: measured on the last snapshot.
  EXPECT_DOUBLE_EQ(crack["measured_at_s"].as<double>(), 3e-6);
  EXPECT_FALSE(crack["reached_outer_radius"].as<bool>());
}

TEST(PostCrackAngleStage, MeasuredWhereTheCrackCrossesTheRingOrAtAGivenTime) {
  // A ring of 2 to 10 mm: the crack is 13 mm from the tip at 2 us, the first snapshot past it.
  YAML::Node summary = postprocess("crack_angle_crossing", {"--crack-angle-range", "2mm,10mm"});
  ASSERT_EQ(summary["crack_angles"].size(), 1u);
  EXPECT_NEAR(summary["crack_angles"][0]["signed_angle_deg"].as<double>(), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(summary["crack_angles"][0]["measured_at_s"].as<double>(), 2e-6);
  EXPECT_TRUE(summary["crack_angles"][0]["reached_outer_radius"].as<bool>());
  // --crack-angle-time 1.5us: the snapshot at 1 us (the crack 7 mm from the tip, inside the ring).
  summary = postprocess("crack_angle_time", {"--crack-angle-range", "2mm,10mm", "--crack-angle-time", "1.5us"});
  ASSERT_EQ(summary["crack_angles"].size(), 1u);
  EXPECT_NEAR(summary["crack_angles"][0]["signed_angle_deg"].as<double>(), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(summary["crack_angles"][0]["measured_at_s"].as<double>(), 1e-6);
  EXPECT_FALSE(summary["crack_angles"][0]["reached_outer_radius"].as<bool>());
  // A time past the run: the last snapshot; exactly a snapshot's time: that snapshot.
  summary = postprocess("crack_angle_time_late", {"--crack-angle-time", "1 ms"});
  EXPECT_DOUBLE_EQ(summary["crack_angles"][0]["measured_at_s"].as<double>(), 3e-6);
  summary = postprocess("crack_angle_time_exact", {"--crack-angle-range", "2mm,10mm", "--crack-angle-time", "2us"});
  EXPECT_DOUBLE_EQ(summary["crack_angles"][0]["measured_at_s"].as<double>(), 2e-6);
}

TEST(PostCrackAngleStage, GivenTipsDirectionAndRange) {
  // Two tips, one direction for both (+y: the crack then runs at -90 degrees to it); the
  // second tip has no crack, which a note says.
  const YAML::Node summary =
      postprocess("crack_angle_given", {"--crack-tip", "8mm,15mm", "--crack-tip", "0.03,0.005", "--crack-direction",
                                        "90deg", "--crack-angle-range", "5mm,15mm"});
  ASSERT_EQ(summary["crack_angles"].size(), 1u);
  const YAML::Node crack = summary["crack_angles"][0];
  EXPECT_EQ(crack["tip_index"].as<int>(), 0);
  EXPECT_NEAR(crack["signed_angle_deg"].as<double>(), -90.0, 1e-9);
  EXPECT_NEAR(summary["crack_angle_deg"][0].as<double>(), 90.0, 1e-9);
  EXPECT_DOUBLE_EQ(crack["tip_m"][0].as<double>(), 8e-3);
  EXPECT_DOUBLE_EQ(crack["range_from_m"].as<double>(), 5e-3);
  EXPECT_DOUBLE_EQ(crack["range_to_m"].as<double>(), 15e-3);
  bool noted = false;
  for (const auto& note : summary["notes"])
    if (note.as<std::string>().find("crack angle: no crack leaves the tip at (30, 5) mm") != std::string::npos)
      noted = true;
  EXPECT_TRUE(noted) << summary["notes"];
}

// Exit code 2, the message contains `expected`, and no post directory is made.
void expect_refused(const std::string& name, const std::vector<std::string>& extra, const std::string& expected,
                    RunFixture fixture = RunFixture{}) {
  const std::string dir = scratch_directory(name);
  write_run_directory(dir + "/run", fixture);
  std::vector<std::string> argv{postprocess_executable(), dir + "/run", "-o", dir + "/post", "--no-plot"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const auto r = run_command(argv);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/post")) << "nothing is written for bad options";
}

TEST(PostCrackAngleStage, BadOptionValues) {
  expect_refused("crack_angle_bad_tip", {"--crack-tip", "8mm", "--crack-direction", "0deg"},
                 "mppm-postprocess: error: --crack-tip '8mm': 1 coordinates (expected X,Y or X,Y,Z");
  expect_refused("crack_angle_bad_direction", {"--crack-tip", "8mm,15mm", "--crack-direction", "45"},
                 "--crack-direction '45': \"45\" is not an angle with a unit");
  expect_refused("crack_angle_bad_range", {"--crack-angle-range", "20mm,5mm"},
                 "--crack-angle-range '20mm,5mm': FROM must be at least 0 and below TO");
  expect_refused(
      "crack_angle_time_unit", {"--crack-angle-time", "40mm"},
      "mppm-postprocess: error: --crack-angle-time '40mm': \"40mm\" is a length (e.g. m, mm), expected a time");
  expect_refused("crack_angle_time_text", {"--crack-angle-time", "later"},
                 "--crack-angle-time 'later': \"later\" is not a number");
  expect_refused("crack_angle_no_direction", {"--crack-tip", "8mm,15mm"}, "--crack-tip needs --crack-direction");
  // Plain numbers are metres: 8,15 is far outside the 40 x 30 mm body.
  expect_refused("crack_angle_outside", {"--crack-tip", "8,15", "--crack-direction", "0deg"},
                 "--crack-tip (8000, 15000, 0) mm lies outside the body (x 0.5 to 39.5 mm, y 0.5 to 29.5 mm);");
  expect_refused("crack_angle_out_of_plane", {"--crack-tip", "8mm,15mm,1mm", "--crack-direction", "0deg"},
                 "the run is 2-D (z = 0 mm): give the tip and the direction in the x-y plane");
  RunFixture no_damage;
  no_damage.damage = false;
  expect_refused("crack_angle_no_damage", {"--crack-tip", "8mm,15mm", "--crack-direction", "0deg"},
                 "need a run with a damage field", no_damage);
}

}  // namespace
