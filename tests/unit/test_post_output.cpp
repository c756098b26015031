// mppm-postprocess on a hand-made run directory: what ParaView/meshio read back is what the
// run wrote (checked against the snapshot files, read independently), the summary carries the
// run's counts, resolved blocks and metrics, and results do not depend on the thread count.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/snapshot_file.hpp"
#include "postprocess/crack_metrics.hpp"
#include "test_post_command.hpp"
#include "test_post_run_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mppm::post::testing;

std::string json_array(const std::vector<double>& values) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << values[i];
  out << "]";
  return out.str();
}

// expected.json: the snapshots as read by mppm::read_snapshot (not by the postprocessor).
void write_expected(const std::string& run, const std::vector<std::string>& snapshot_files, const std::string& path) {
  std::ofstream out(path);
  const mppm::Snapshot reference = mppm::read_snapshot(run + "/reference.snap");
  out << "{\"dimension\": " << reference.dimension << ", \"reference\": {";
  for (std::size_t f = 0; f < reference.fields.size(); ++f)
    out << (f ? ", " : "") << "\"" << reference.fields[f].name
        << "\": {\"components\": " << reference.fields[f].components
        << ", \"data\": " << json_array(reference.fields[f].data) << "}";
  out << "}, \"frames\": [";
  for (std::size_t k = 0; k < snapshot_files.size(); ++k) {
    const mppm::Snapshot s = mppm::read_snapshot(snapshot_files[k]);
    out << (k ? ", " : "") << "{\"time\": " << json_array({s.time}) << ", \"step\": " << s.step << ", \"fields\": {";
    for (std::size_t f = 0; f < s.fields.size(); ++f)
      out << (f ? ", " : "") << "\"" << s.fields[f].name << "\": {\"components\": " << s.fields[f].components
          << ", \"data\": " << json_array(s.fields[f].data) << "}";
    out << "}}";
  }
  out << "]}\n";
}

struct LoadColumns {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};

LoadColumns read_csv(const std::string& path) {
  LoadColumns table;
  std::istringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  std::istringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) table.header.push_back(cell);
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::vector<double> row;
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    table.rows.push_back(row);
  }
  return table;
}

std::size_t column(const LoadColumns& table, const std::string& name) {
  for (std::size_t c = 0; c < table.header.size(); ++c)
    if (table.header[c] == name) return c;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

TEST(PostOutput, MeshioReadsEveryFrameWithTheValuesTheRunWrote) {
  const std::string dir = scratch_directory("meshio");
  RunFixture fixture;
  const auto files = write_run_directory(dir + "/run", fixture);
  const auto result = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  write_expected(dir + "/run", files, dir + "/expected.json");
  const auto check = run_command({"/usr/bin/python3", std::string(MPPM_SOURCE_DIR) + "/tests/tools/check_post_vtu.py",
                                  dir + "/post/results.pvd", dir + "/expected.json"});
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("frames checked: 4"), std::string::npos) << check.output;
}

TEST(PostOutput, InPlaneStressOfA2DRunGetsItsInvariants) {
  // A 2-D solver may write only the in-plane stress block (4 components): the invariants are
  // then those of the in-plane state (sigma_zz = 0), recomputed independently by the checker.
  const std::string dir = scratch_directory("meshio_plane_stress");
  RunFixture fixture;
  fixture.stress_components = 4;
  fixture.snapshots = 2;
  const auto files = write_run_directory(dir + "/run", fixture);
  const auto result = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--no-plot"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("in-plane"), std::string::npos) << "says so: " << result.output;
  write_expected(dir + "/run", files, dir + "/expected.json");
  const auto check = run_command({"/usr/bin/python3", std::string(MPPM_SOURCE_DIR) + "/tests/tools/check_post_vtu.py",
                                  dir + "/post/results.pvd", dir + "/expected.json"});
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("frames checked: 2"), std::string::npos) << check.output;
}

TEST(PostOutput, SummaryCarriesRunCountsResolvedBlocksAndMetrics) {
  const std::string dir = scratch_directory("summary");
  RunFixture fixture;
  write_run_directory(dir + "/run", fixture);
  const auto result = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const YAML::Node summary = YAML::LoadFile(dir + "/post/summary.json");  // JSON is YAML
  EXPECT_EQ(summary["status"].as<std::string>(), "completed");
  EXPECT_EQ(summary["points"].as<long>(), fixture_points(fixture));
  EXPECT_EQ(summary["bonds"].as<long>(), 28 * fixture_points(fixture));
  EXPECT_EQ(summary["steps"].as<long>(), 40 * (fixture.snapshots - 1));
  EXPECT_EQ(summary["threads"].as<int>(), 2);
  EXPECT_DOUBLE_EQ(summary["wall_seconds"].as<double>(), 1.5);
  ASSERT_EQ(summary["effects"].size(), 3u);
  EXPECT_EQ(summary["effects"][0].as<std::string>(), "micropolar");
  // Resolved blocks: SI numbers, angles in degrees ("35 deg" in the resolved scene).
  EXPECT_DOUBLE_EQ(summary["material"]["lambda"].as<double>(), 14e9);
  EXPECT_DOUBLE_EQ(summary["material"]["couple_moduli"][2].as<double>(), 56000.0);
  EXPECT_NEAR(summary["material"]["viscoplasticity"]["friction_angle"].as<double>(), 35.0, 1e-12);
  EXPECT_NEAR(summary["material"]["viscoplasticity"]["dilatancy_angle"].as<double>(), 15.0, 1e-12);
  EXPECT_EQ(summary["material"]["viscoplasticity"]["model"].as<std::string>(), "drucker-prager-perzyna");
  ASSERT_EQ(summary["boundary_conditions"].size(), 2u);
  EXPECT_EQ(summary["boundary_conditions"][1]["name"].as<std::string>(), "top");
  EXPECT_EQ(summary["boundary_conditions"][1]["value"][0].as<std::string>(), "free");
  EXPECT_DOUBLE_EQ(summary["boundary_conditions"][1]["value"][1].as<double>(), -0.05);

  // Peak load of the main boundary (the first moving kinematic one: bottom), from load.csv.
  const LoadColumns load = read_csv(dir + "/run/load.csv");
  const std::size_t fy = column(load, "bottom_Fy_N"), uy = column(load, "bottom_uy_m");
  std::size_t peak_row = 0;
  for (std::size_t r = 0; r < load.rows.size(); ++r)
    if (std::fabs(load.rows[r][fy]) > std::fabs(load.rows[peak_row][fy])) peak_row = r;
  EXPECT_EQ(summary["main_boundary"].as<std::string>(), "bottom");
  EXPECT_EQ(summary["main_axis"].as<std::string>(), "y");
  EXPECT_DOUBLE_EQ(summary["peak_load_N"].as<double>(), std::fabs(load.rows[peak_row][fy]));
  EXPECT_DOUBLE_EQ(summary["displacement_at_peak_m"].as<double>(), std::fabs(load.rows[peak_row][uy]));

  // The fixture's band runs along (0.8, 0.6): atan(0.6/0.8) = 36.87 deg to the x axis, with a
  // Gaussian profile of sigma = 3 dx, FWHM = 2 sqrt(2 ln 2) 3 dx = 7.06 mm. Tolerances: a small
  // interior (40 x 18 points) and a 1 mm lattice: 1 degree, and one spacing on the width.
  ASSERT_EQ(summary["shear_band_count"].as<int>(), 1);
  EXPECT_NEAR(summary["shear_band_angle_deg"].as<double>(), std::atan2(0.6, 0.8) * 180.0 / std::numbers::pi, 1.0);
  EXPECT_NEAR(summary["shear_band_width_m"].as<double>(), 2.0 * std::sqrt(2.0 * std::log(2.0)) * 3e-3, 1e-3);
  EXPECT_DOUBLE_EQ(summary["shear_band_time_s"].as<double>(), 3e-6);
  // The per-band details: the same angle and width, the line's direction (positive slope here)
  // and a centre on the generated band's centre line (through the fixture's band centre).
  ASSERT_EQ(summary["shear_bands"].size(), 1u);
  const YAML::Node band = summary["shear_bands"][0];
  EXPECT_DOUBLE_EQ(band["angle_deg"].as<double>(), summary["shear_band_angle_deg"].as<double>());
  EXPECT_DOUBLE_EQ(band["width_m"].as<double>(), summary["shear_band_width_m"].as<double>());
  EXPECT_NEAR(band["direction_deg"].as<double>(), band["angle_deg"].as<double>(), 1e-12);
  ASSERT_EQ(band["centre_m"].size(), 2u);
  EXPECT_GT(band["points"].as<long>(), 0);

  // The fixture's crack runs from the pre-crack (8 mm) 6.7 mm per snapshot: it starts in the
  // second snapshot, never branches and neither stops for 5 us nor reaches a boundary.
  EXPECT_DOUBLE_EQ(summary["crack_start_time_s"].as<double>(), 1e-6);
  EXPECT_TRUE(summary["crack_branch_time_s"].IsNull());
  EXPECT_TRUE(summary["crack_end_time_s"].IsNull());
  // 20/3 mm per us, quantized by dx at both ends of a 1 us window: +-2 dx / (6.67 mm) = 30%.
  EXPECT_NEAR(summary["crack_tip_speed_max_m_per_s"].as<double>(), 20.0 / 3.0 * 1e3, 0.3 * 20.0 / 3.0 * 1e3);
  EXPECT_NEAR(summary["crack_length_m"].as<double>(), 20e-3, 2e-3);
  // The crack path's threshold is in the summary, so that scripts need not repeat it.
  EXPECT_DOUBLE_EQ(summary["crack_damage_threshold"].as<double>(), mppm::post::CrackSettings{}.damage_threshold);
}

TEST(PostOutput, LoadCurveHasOneDisplacementAndForcePerLoadedBoundary) {
  const std::string dir = scratch_directory("load_curve");
  write_run_directory(dir + "/run", RunFixture{});
  const auto result = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const LoadColumns load = read_csv(dir + "/run/load.csv");
  const LoadColumns curve = read_csv(dir + "/post/load_curve.csv");
  ASSERT_EQ(curve.header, (std::vector<std::string>{"time_s", "bottom_uy_m", "bottom_Fy_N", "top_uy_m", "top_Fy_N"}));
  ASSERT_EQ(curve.rows.size(), load.rows.size());
  for (std::size_t r = 0; r < load.rows.size(); ++r)
    for (const auto& name : curve.header)
      EXPECT_EQ(curve.rows[r][column(curve, name)], load.rows[r][column(load, name)]);
  // load_curve.png: a PNG image of some substance (matplotlib figure with two panels).
  const std::string png = read_text(dir + "/post/load_curve.png");
  ASSERT_GT(png.size(), 10000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(PostOutput, SameOutputForAnyThreadCount) {
  const std::string dir = scratch_directory("threads");
  write_run_directory(dir + "/run", RunFixture{});
  for (const char* threads : {"1", "2"}) {
    const auto r = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post" + threads, "--quiet",
                                "--no-plot", "--threads", threads});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  std::size_t compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir + "/post1")) {
    if (!entry.is_regular_file()) continue;
    const auto relative = fs::relative(entry.path(), dir + "/post1");
    EXPECT_EQ(read_text(entry.path().string()), read_text((fs::path(dir + "/post2") / relative).string()))
        << relative << " differs between 1 and 2 threads";
    ++compared;
  }
  EXPECT_EQ(compared, 4u + 1u + 1u + 1u + 1u);  // 4 frames, results.pvd, load_curve.csv, summary.json, view.py
}

TEST(PostOutput, NumericalFailureRunIsPostprocessedUpToItsLastSnapshot) {
  const std::string dir = scratch_directory("numerical_failure");
  RunFixture fixture;
  fixture.snapshots = 3;
  fixture.status = "numerical_failure";
  fixture.message = "non-finite displacement at point 12 (step 81)";
  write_run_directory(dir + "/run", fixture);
  const auto result = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--no-plot"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("numerical_failure"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("last good snapshot"), std::string::npos) << result.output;
  const YAML::Node summary = YAML::LoadFile(dir + "/post/summary.json");
  EXPECT_EQ(summary["status"].as<std::string>(), "numerical_failure");
  EXPECT_EQ(summary["message"].as<std::string>(), fixture.message);
  EXPECT_EQ(summary["snapshots"].as<int>(), 3);
  EXPECT_TRUE(fs::exists(dir + "/post/results/results_000080.vtu"));
}

}  // namespace
