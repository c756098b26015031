// mppm-preprocess as users run it: bad input of every kind named in issue 2 ends with exit
// code 2 and one message that names the offending file and the problem, never a crash and
// never an output file; a good scene writes the points file and the report.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& arguments) {
  const std::string command = std::string(MPPM_BINARY_DIR) + "/bin/mppm-preprocess " + arguments + " 2>&1";
  CliRun result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;  // -1: killed by a signal
  return result;
}

std::string scene(const std::string& name) { return std::string(MPPM_SOURCE_DIR) + "/tests/data/scenes/" + name; }

std::string output_path(const std::string& name) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "test_output" / "preprocess_cli";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return (dir / name).string();
}

void expect_bad_input(const std::string& scene_file, const std::vector<std::string>& fragments,
                      const std::string& extra = "") {
  const std::string out = output_path(scene_file + ".vtp");
  const CliRun r = run(scene(scene_file) + " -o " + out + " " + extra);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const std::string& fragment : fragments)
    EXPECT_NE(r.output.find(fragment), std::string::npos) << "missing '" << fragment << "' in: " << r.output;
  EXPECT_FALSE(fs::exists(out)) << "output written despite bad input";
}

}  // namespace

TEST(PreprocessCommandLine, MissingSceneFile) {
  expect_bad_input("pre_no_such_scene.yaml", {"pre_no_such_scene.yaml"});
}

TEST(PreprocessCommandLine, MissingGeometryFile) {
  expect_bad_input("pre_bad_missing_geometry.yaml", {"does_not_exist.geo", "not found"});
}

TEST(PreprocessCommandLine, UnknownPhysicalGroup) {
  expect_bad_input("pre_bad_unknown_group.yaml",
                   {"pre_bad_unknown_group.yaml:14", "unknown physical group 'lid'", "branching_plate.geo", "'top'"});
}

TEST(PreprocessCommandLine, SpacingLargerThanTheBody) {
  expect_bad_input("pre_bad_dx_too_large.yaml", {"pre_bad_dx_too_large.yaml", "branching_plate.geo", "larger than the body"});
}

TEST(PreprocessCommandLine, OpenSurface) {
  expect_bad_input("pre_bad_open_surface.yaml", {"open_box.stl", "not closed"});
}

TEST(PreprocessCommandLine, SelfIntersectingSurface) {
  expect_bad_input("pre_bad_self_intersecting.yaml", {"self_intersecting.stl", "intersects itself"});
}

TEST(PreprocessCommandLine, WrongUnitDimension) {
  expect_bad_input("pre_bad_unit_dimension.yaml", {"pre_bad_unit_dimension.yaml:9", "geometry.spacing", "kg"});
}

TEST(PreprocessCommandLine, UnknownKey) {
  expect_bad_input("pre_bad_unknown_key.yaml", {"pre_bad_unknown_key.yaml:11", "colour"});
}

TEST(PreprocessCommandLine, BadOverrideAndMissingOutput) {
  expect_bad_input("pre_branching_plate.yaml", {"geometry.spacing"}, "--set geometry.spacing=2s");
  const CliRun r = run(scene("pre_branching_plate.yaml"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("-o"), std::string::npos) << r.output;
}

TEST(PreprocessCommandLine, GoodSceneWritesPointsAndReport) {
  const std::string out = output_path("plate.vtp");
  const CliRun r = run(scene("pre_branching_plate.yaml") + " -o " + out + " --threads 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_NE(r.output.find("body (region 0): 16000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bonds"), std::string::npos) << r.output;
  const CliRun quiet = run(scene("pre_branching_plate.yaml") + " -o " + out + " --quiet");
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_TRUE(quiet.output.empty()) << quiet.output;
}
