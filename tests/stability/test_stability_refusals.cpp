// Stability cases refused up front, through the real executables (the exit code is the point):
// - the couple modulus entered 1000 x too large (a3 in kN instead of N, the seed examples'
//   units slip; or mu_c in GPa instead of MPa) with a fixed time step;
// - a bad time step (negative, zero, not a number, above the translational limit);
// - a broken points file (missing, not VTK, truncated, a negative or zero volume, a NaN
//   coordinate);
// - a geometry that yields no points (thinner than dx; a ring whose material falls between
//   the lattice points);
// - a negative volume from a broken geometry: point volumes are dx^2 t (2-D) or dx^3, set by
//   the preprocessor from the validated spacing and thickness, never from the geometry, so a
//   geometry cannot give a negative volume directly. What can is the orientation of its
//   boundary, if trusted: an outline traversed clockwise, a surface turned inside out (negative
//   signed area / volume), a self-overlapping outline (lobes of opposite sign). The first two
//   are oriented by the preprocessor (same points as the intact geometry, all volumes > 0), the
//   third is refused (exit 2 naming the file); a non-positive thickness (the one scene value in
//   the 2-D volume besides dx) is refused naming `thickness`; a points file that carries a
//   negative volume anyway is refused by mppm-solve (the broken-points-file case);
// - a scene whose boundary layers differ from those fixed in the points file (finding 7): a
//   loaded depth or a selection changed after preprocessing.
// Hazard: each of these either blows up after hours or produces a silent wrong answer.
// Expected: exit code 2 before the first step, a message naming the file (and the key, the
// mode and the parameter where it applies) and what was expected, and no output file: the run
// directory is not created (the time-step check happens before anything is written) and no
// points file appears.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "common/point_cloud.hpp"
#include "tests/stability/stability_support.hpp"

namespace mppm::stability {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// True when the stage left nothing under `path` (not created, or an empty directory).
bool nothing_written(const std::string& path) { return !fs::exists(path) || fs::is_empty(path); }

// "... above the critical step 1.234e-08 s ..." -> 1.234e-08
double critical_step_in(const std::string& message) {
  const std::string key = "critical step ";
  const auto at = message.find(key);
  return at == std::string::npos ? std::nan("") : std::strtod(message.c_str() + at + key.size(), nullptr);
}

class StabilityRefusals : public ::testing::Test {
 protected:
  // Points of the block scenes, made once by the preprocessor executable.
  static void SetUpTestSuite() {
    // Named per process: ctest runs the tests of this fixture as parallel processes.
    points_ = fresh_directory("refusals-points-" + std::to_string(::getpid())) + ".vtp";
    const CommandResult r =
        run_program(program("mppm-preprocess"), {scene_path("couple_modulus_slip.yaml"), "-o", points_, "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() { fs::remove(points_); }
  static CommandResult solve(const std::string& scene, const std::string& run, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{scene_path(scene), "--points", points_, "-o", run, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_program(program("mppm-solve"), args);
  }
  // mu_c = 4667 GPa instead of 4.667 GPa (a3 as intended). mu_c stiffens both blocks: the
  // shear waves ((mu + mu_c) / rho) and the rotation (4 mu_c / I); on this lattice the
  // translational block ends up the limiting one.
  static CommandResult solve_with_mu_c_slip(const std::string& run) {
    return solve("couple_modulus_slip.yaml", run,
                 {"--set", "material.couple_moduli=[0, 0, 56 kN]", "--set", "material.mu_c=4667 GPa"});
  }
  static std::string points_;
};
std::string StabilityRefusals::points_;

TEST_F(StabilityRefusals, CoupleModulusInKilonewtonIsRefusedNamingTheRotationalModeAndA3) {
  const std::string run = fresh_directory("slip-a3");
  const CommandResult r = solve("couple_modulus_slip.yaml", run);
  std::printf("a3 = 56e3 kN: exit %d\n%s", r.exit_code, r.output.c_str());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "couple_modulus_slip.yaml")) << r.output;
  EXPECT_TRUE(contains(r.output, "time.step")) << r.output;
  EXPECT_TRUE(contains(r.output, "rotational")) << r.output;
  EXPECT_TRUE(contains(r.output, "material.couple_moduli")) << r.output;
  EXPECT_TRUE(contains(r.output, "a3")) << r.output;
  EXPECT_TRUE(nothing_written(run)) << run;

  // The same scene with the intended 56 kN runs: the refusal is the slip's doing.
  const std::string good = fresh_directory("slip-a3-corrected");
  const CommandResult ok = solve("couple_modulus_slip.yaml", good, {"--set", "material.couple_moduli=[0, 0, 56 kN]"});
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_EQ(read_run(good).status, "completed");
  const RunReport corrected = read_run(good);

  const double given = 0.1e-6;  // couple_modulus_slip.yaml
  const double slip_critical = critical_step_in(r.output);
  record_margin({"02-couple-modulus-a3-1000x", "couple modulus a3 entered in kN (1000 x), fixed step 0.1 us",
                 "refused before the first step: exit 2 naming the rotational mode and material.couple_moduli (a3)",
                 "exit " + std::to_string(r.exit_code) + "; critical step with the slip " + sci(slip_critical) +
                     " s, with the intended a3 " + sci(corrected.critical_time_step) + " s (that run exits " +
                     std::to_string(ok.exit_code) + ")",
                 "given step / slipped critical step " + sci(given / slip_critical) +
                     " (refused); intended critical / given " + sci(corrected.critical_time_step / given) +
                     " (accepted)",
                 r.exit_code == 2 && ok.exit_code == 0 && nothing_written(run)});
}

TEST_F(StabilityRefusals, CoupleModulusMuCInGigapascalIsRefusedBeforeTheFirstStep) {
  const std::string run = fresh_directory("slip-mu-c");
  const CommandResult r = solve_with_mu_c_slip(run);
  std::printf("mu_c = 4667 GPa: exit %d\n%s", r.exit_code, r.output.c_str());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "couple_modulus_slip.yaml")) << r.output;
  EXPECT_TRUE(contains(r.output, "time.step")) << r.output;
  EXPECT_TRUE(nothing_written(run)) << run;
  const double slip_critical = critical_step_in(r.output);
  const bool names_mu_c = contains(r.output, "material.mu_c");
  record_margin({"02-couple-modulus-mu-c-1000x",
                 "couple modulus mu_c entered in GPa for MPa-scale (1000 x), fixed step 0.1 us",
                 "refused before the first step: exit 2 naming material.mu_c",
                 "exit " + std::to_string(r.exit_code) + "; critical step with the slip " + sci(slip_critical) +
                     " s; message " + (names_mu_c ? "names material.mu_c" : "credits lambda and mu, not mu_c"),
                 "given step / slipped critical step " + sci(0.1e-6 / slip_critical) + " (refused)",
                 r.exit_code == 2 && nothing_written(run) && names_mu_c});
}

// The refusal must also tell the user which parameter to fix. The limiting block is the
// translational one (mu_c stiffens the shear waves, (mu + mu_c) / rho), and the solver credits it
// to mu_c because the same estimate without mu_c leaves less than half of omega_max^2
// (solver/critical_time_step.cpp); before that fix it named lambda and mu, which did not change.
TEST_F(StabilityRefusals, CoupleModulusMuCRefusalNamesMuC) {
  const CommandResult r = solve_with_mu_c_slip(fresh_directory("slip-mu-c-message"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "material.mu_c")) << r.output;
  EXPECT_TRUE(contains(r.output, "translational")) << r.output;
  // It names mu_c as the driver, not lambda and mu.
  EXPECT_FALSE(contains(r.output, "driven by material.lambda")) << r.output;
}

TEST_F(StabilityRefusals, BadTimeStepIsRefusedWithTheKeyAndNothingWritten) {
  struct Bad {
    std::vector<std::string> set;
    std::vector<std::string> expected_in_message;
  };
  // elastic_block.yaml shares the points of couple_modulus_slip.yaml (same geometry, spacing,
  // horizon and boundary conditions).
  const std::vector<Bad> cases{
      {{"time.step=-1 us"}, {"time.step"}},
      {{"time.step=0"}, {"time.step"}},
      {{"time.step=fast"}, {"time.step"}},
      {{"time.step=1 m"}, {"time.step"}},  // wrong dimension: a length
      // Above the translational limit (l = 2 mm: translational limits this block).
      {{"time.step=1 us"}, {"time.step", "translational", "material.lambda"}},
  };
  int k = 0;
  std::string codes;
  bool all_refused = true;
  for (const Bad& b : cases) {
    const std::string run = fresh_directory("bad-step-" + std::to_string(k++));
    std::vector<std::string> extra;
    for (const auto& s : b.set) {
      extra.push_back("--set");
      extra.push_back(s);
    }
    const CommandResult r = solve("elastic_block.yaml", run, extra);
    std::printf("--set %s: exit %d\n%s", b.set.front().c_str(), r.exit_code, r.output.c_str());
    EXPECT_EQ(r.exit_code, 2) << b.set.front();
    for (const auto& part : b.expected_in_message) EXPECT_TRUE(contains(r.output, part)) << r.output;
    // The message names where the bad value came from: the scene file or the --set option.
    EXPECT_TRUE(contains(r.output, "elastic_block.yaml") || contains(r.output, "--set")) << r.output;
    EXPECT_TRUE(nothing_written(run)) << run;
    codes += (codes.empty() ? "" : ", ") + b.set.front().substr(10) + " -> " + std::to_string(r.exit_code);
    all_refused = all_refused && r.exit_code == 2 && nothing_written(run);
  }
  record_margin({"08-bad-time-step", "bad time.step: negative, zero, not a number, a length, above the critical step",
                 "exit 2 naming time.step (and the limiting mode and parameter when too large), nothing written",
                 "exit codes: " + codes, "contract check (no numeric margin)", all_refused});
}

TEST_F(StabilityRefusals, BrokenPointsFileIsRefusedNamingTheFile) {
  const std::string dir = fresh_directory("broken-points");
  fs::create_directories(dir);
  // A valid cloud to break: the preprocessor's own points.
  const PointCloud good = read_point_cloud(points_);
  struct Broken {
    std::string name;
    std::string expected;  // part of the message besides the file name
  };
  std::vector<Broken> cases;
  {  // missing
    cases.push_back({dir + "/missing.vtp", ""});
  }
  {  // not VTK at all
    std::ofstream(dir + "/garbage.vtp") << "this is not a VTK file\n";
    cases.push_back({dir + "/garbage.vtp", ""});
  }
  {  // truncated: the first half of a valid file
    const std::string text = read_text(points_);
    std::ofstream(dir + "/truncated.vtp", std::ios::binary) << text.substr(0, text.size() / 2);
    cases.push_back({dir + "/truncated.vtp", ""});
  }
  {  // a negative volume (a broken geometry or a hand-edited file)
    PointCloud c = good;
    c.volume[c.size() / 2] = -c.volume[c.size() / 2];
    write_point_cloud(c, dir + "/negative_volume.vtp");
    cases.push_back({dir + "/negative_volume.vtp", "volume"});
  }
  {  // a zero volume
    PointCloud c = good;
    c.volume[3] = 0.0;
    write_point_cloud(c, dir + "/zero_volume.vtp");
    cases.push_back({dir + "/zero_volume.vtp", "volume"});
  }
  {  // a NaN coordinate
    PointCloud c = good;
    c.y[7] = std::numeric_limits<double>::quiet_NaN();
    write_point_cloud(c, dir + "/nan_coordinate.vtp");
    cases.push_back({dir + "/nan_coordinate.vtp", "non-finite"});
  }
  int k = 0;
  std::string codes;
  bool all_refused = true;
  for (const Broken& b : cases) {
    const std::string run = fresh_directory("broken-points-run-" + std::to_string(k++));
    const CommandResult r = run_program(program("mppm-solve"),
                                        {scene_path("elastic_block.yaml"), "--points", b.name, "-o", run, "--quiet"});
    std::printf("%s: exit %d\n%s", fs::path(b.name).filename().c_str(), r.exit_code, r.output.c_str());
    EXPECT_EQ(r.exit_code, 2) << b.name;
    EXPECT_TRUE(contains(r.output, b.name)) << r.output;
    if (!b.expected.empty()) {
      EXPECT_TRUE(contains(r.output, b.expected)) << r.output;
    }
    EXPECT_TRUE(nothing_written(run)) << run;
    codes += (codes.empty() ? "" : ", ") + fs::path(b.name).stem().string() + " -> " + std::to_string(r.exit_code);
    all_refused = all_refused && r.exit_code == 2 && contains(r.output, b.name) && nothing_written(run);
  }
  record_margin({"09-broken-points-file",
                 "broken points file: missing, not VTK, truncated, negative / zero volume, NaN coordinate",
                 "exit 2 naming the file and the problem, nothing written", "exit codes: " + codes,
                 "contract check (no numeric margin)", all_refused});
}

// The loaded points and the layers are fixed by mppm-preprocess; before the points file stored
// what they were made from, `--set boundary_conditions[0].depth=3mm` at solve time ran silently
// with the one row loaded at preprocessing (results identical to 1 and 5 mm).
TEST_F(StabilityRefusals, BoundaryChangedAfterPreprocessingIsRefused) {
  const std::string scene = scene_path("fragmentation_block.yaml");
  const std::string points = fresh_directory("boundary-origin-points") + ".vtp";
  const CommandResult made = run_program(program("mppm-preprocess"), {scene, "-o", points, "--quiet"});
  ASSERT_EQ(made.exit_code, 0) << made.output;
  auto solve_with = [&](const std::string& name, std::vector<std::string> sets) {
    const std::string run = fresh_directory(name);
    std::vector<std::string> args{scene, "--points", points, "-o", run, "--quiet", "--set", "time.end=0.5us"};
    args.insert(args.end(), sets.begin(), sets.end());
    CommandResult r = run_program(program("mppm-solve"), args);
    return std::pair{r, nothing_written(run)};
  };
  // The scene as preprocessed (its loaded depth is the default, dx = 1 mm) runs; so does the
  // same depth written out, and a change that does not touch the layers (the traction value).
  for (const std::vector<std::string>& same : {std::vector<std::string>{},
                                               {"--set", "boundary_conditions[0].depth=1 mm"},
                                               {"--set", "boundary_conditions[0].value=[0.5 GPa, 0]"}}) {
    const auto [r, empty] = solve_with("boundary-origin-same", same);
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  const auto [deeper, deeper_empty] =
      solve_with("boundary-origin-depth", {"--set", "boundary_conditions[0].depth=3 mm"});
  EXPECT_EQ(deeper.exit_code, 2) << deeper.output;
  for (const char* part :
       {"fragmentation_block.yaml", "boundary_conditions[0].depth", "0.003", "0.001", "rerun mppm-preprocess"})
    EXPECT_TRUE(contains(deeper.output, part)) << part << " missing in: " << deeper.output;
  EXPECT_TRUE(deeper_empty);
  const auto [moved, moved_empty] =
      solve_with("boundary-origin-selection", {"--set",
                                               "boundary_conditions[0]={box: [[0, 0], [1 mm, 20 mm]], "
                                               "type: traction, value: [1 GPa, 0]}"});
  EXPECT_EQ(moved.exit_code, 2) << moved.output;
  for (const char* part : {"boundary_conditions[0]", "selects box", "'left'", "rerun mppm-preprocess"})
    EXPECT_TRUE(contains(moved.output, part)) << part << " missing in: " << moved.output;
  EXPECT_TRUE(moved_empty);
  const bool pass = deeper.exit_code == 2 && moved.exit_code == 2 && deeper_empty && moved_empty &&
                    contains(deeper.output, "boundary_conditions[0].depth") && contains(moved.output, "selects box");
  record_margin(
      {"09c-boundary-changed-after-preprocessing",
       "a boundary's depth or selection changed after preprocessing (the layers are fixed in the points file)",
       "exit 2 naming the key and both values, nothing written; unchanged layers run",
       "depth 1 mm -> 3 mm: exit " + std::to_string(deeper.exit_code) + "; selection 'left' -> a box: exit " +
           std::to_string(moved.exit_code),
       "contract check (no numeric margin)", pass});
}

TEST_F(StabilityRefusals, GeometryWithoutPointsIsRefusedNamingTheGeometry) {
  const std::pair<const char*, const char*> cases[] = {{"no_points.yaml", "sliver.geo"},
                                                       {"no_points_ring.yaml", "thin_ring.geo"}};
  std::string codes;
  bool all_refused = true;
  for (const auto& [scene, geometry] : cases) {
    const std::string out = fresh_directory(std::string("no-points-") + geometry) + ".vtp";
    fs::remove(out);  // (fresh_directory empties the directory of that name, not this file)
    const CommandResult r = run_program(program("mppm-preprocess"), {scene_path(scene), "-o", out, "--quiet"});
    std::printf("%s: exit %d\n%s", scene, r.exit_code, r.output.c_str());
    EXPECT_EQ(r.exit_code, 2) << scene;
    EXPECT_TRUE(contains(r.output, scene)) << r.output;
    EXPECT_TRUE(contains(r.output, geometry)) << r.output;
    EXPECT_FALSE(fs::exists(out)) << out;
    codes += (codes.empty() ? "" : ", ") + std::string(geometry) + " -> " + std::to_string(r.exit_code);
    all_refused = all_refused && r.exit_code == 2 && contains(r.output, geometry) && !fs::exists(out);
  }
  record_margin({"10-geometry-without-points", "geometry yielding no points: 0.2 mm strip, ring between lattice points",
                 "mppm-preprocess exit 2 naming the scene and the geometry, no points file", "exit codes: " + codes,
                 "contract check (no numeric margin)", all_refused});
}

TEST_F(StabilityRefusals, NegativeVolumeFromABrokenGeometryIsImpossibleOrRefused) {
  std::string measured;
  bool all = true;
  auto note = [&](const std::string& what, bool ok) {
    measured += (measured.empty() ? "" : "; ") + what;
    all = all && ok;
  };
  // 1. The outline traversed clockwise: the same points as block.geo, every volume dx^2 t.
  {
    const std::string turned = fresh_directory("negative-volume-clockwise") + ".vtp";
    const std::string intact = fresh_directory("negative-volume-intact") + ".vtp";
    const CommandResult a = run_program(program("mppm-preprocess"),
                                        {scene_path("negative_volume_clockwise.yaml"), "-o", turned, "--quiet"});
    const CommandResult b = run_program(
        program("mppm-preprocess"),
        {scene_path("negative_volume_clockwise.yaml"), "-o", intact, "--quiet", "--set", "geometry.file=block.geo"});
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const PointCloud pa = read_point_cloud(turned), pb = read_point_cloud(intact);
    const double dv = 1e-3 * 1e-3 * 1e-3;  // dx^2 t
    bool same = pa.size() == pb.size() && pa.size() == 400;
    for (std::size_t i = 0; same && i < pa.size(); ++i)
      same = pa.x[i] == pb.x[i] && pa.y[i] == pb.y[i] && pa.volume[i] == pb.volume[i] &&
             std::abs(pa.volume[i] - dv) <= 1e-12 * dv;
    EXPECT_TRUE(same);
    note("clockwise outline: exit " + std::to_string(a.exit_code) + ", " + std::to_string(pa.size()) +
             " points, identical to the intact block, volumes dx^2 t",
         a.exit_code == 0 && same);
    fs::remove(turned);
    fs::remove(intact);
  }
  // 2. A closed surface turned inside out (every triangle of closed_cube.stl reversed): the same
  //    points as the intact cube, every volume dx^3.
  {
    const std::string dir = fresh_directory("negative-volume-inside-out");
    fs::create_directories(dir);
    const std::string cube = std::string(MPPM_SOURCE_DIR) + "/tests/data/geometry/closed_cube.stl";
    std::istringstream in(read_text(cube));
    std::ofstream out(dir + "/inside_out_cube.stl");
    std::string line;
    std::vector<std::string> loop;
    while (std::getline(in, line)) {
      if (line.find("vertex") != std::string::npos) {
        loop.push_back(line);
        if (loop.size() == 3) {
          out << loop[0] << "\n" << loop[2] << "\n" << loop[1] << "\n";  // reversed winding
          loop.clear();
        }
        continue;
      }
      out << line << "\n";
    }
    out.close();
    auto scene_for = [&](const std::string& geometry) {
      const std::string path = dir + "/" + fs::path(geometry).stem().string() + ".yaml";
      std::ofstream(path) << "mppm: 1\nname: inside-out\ndimension: 3\ngeometry:\n  file: " << geometry
                          << "\n  unit: mm\n  spacing: 1 mm\n  horizon_factor: 2.05\nmaterial: {density: 2650, "
                             "lambda: 14 GPa, mu: 14 GPa}\neffects: []\ntime: {end: 1 us, step: auto}\n";
      return path;
    };
    const CommandResult a = run_program(
        program("mppm-preprocess"), {scene_for(dir + "/inside_out_cube.stl"), "-o", dir + "/turned.vtp", "--quiet"});
    const CommandResult b =
        run_program(program("mppm-preprocess"), {scene_for(cube), "-o", dir + "/intact.vtp", "--quiet"});
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const PointCloud pa = read_point_cloud(dir + "/turned.vtp"), pb = read_point_cloud(dir + "/intact.vtp");
    bool same = pa.size() == pb.size() && pa.size() == 1000;
    for (std::size_t i = 0; same && i < pa.size(); ++i)
      same = pa.x[i] == pb.x[i] && pa.y[i] == pb.y[i] && pa.z[i] == pb.z[i] && pa.volume[i] == pb.volume[i] &&
             std::abs(pa.volume[i] - 1e-9) <= 1e-21;
    EXPECT_TRUE(same);
    note("inside-out STL cube: exit " + std::to_string(a.exit_code) + ", " + std::to_string(pa.size()) +
             " points, identical to the intact cube, volumes dx^3",
         a.exit_code == 0 && same);
  }
  // 3. A self-overlapping outline (bow tie): refused naming the file.
  {
    const std::string out = fresh_directory("negative-volume-bowtie") + ".vtp";
    fs::remove(out);
    const CommandResult r =
        run_program(program("mppm-preprocess"), {scene_path("negative_volume_bowtie.yaml"), "-o", out, "--quiet"});
    std::printf("bow tie: exit %d\n%s", r.exit_code, r.output.c_str());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.output, "bowtie.geo")) << r.output;
    EXPECT_FALSE(fs::exists(out));
    note("bow-tie outline: exit " + std::to_string(r.exit_code), r.exit_code == 2 && !fs::exists(out));
  }
  // 4. A thickness that would make dx^2 t negative or zero: refused naming the key, by both stages.
  for (const char* t : {"-1 mm", "0"}) {
    const std::string out = fresh_directory("negative-volume-thickness") + ".vtp";
    fs::remove(out);
    const std::string set = std::string("thickness=") + t;
    const CommandResult pre =
        run_program(program("mppm-preprocess"), {scene_path("elastic_block.yaml"), "-o", out, "--quiet", "--set", set});
    const std::string run = fresh_directory("negative-volume-thickness-run");
    const CommandResult solve = run_program(program("mppm-solve"), {scene_path("elastic_block.yaml"), "--points",
                                                                    points_, "-o", run, "--quiet", "--set", set});
    std::printf("--set %s: preprocess exit %d, solve exit %d\n%s%s", set.c_str(), pre.exit_code, solve.exit_code,
                pre.output.c_str(), solve.output.c_str());
    EXPECT_EQ(pre.exit_code, 2);
    EXPECT_EQ(solve.exit_code, 2);
    EXPECT_TRUE(contains(pre.output, "thickness")) << pre.output;
    EXPECT_TRUE(contains(solve.output, "thickness")) << solve.output;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(nothing_written(run));
    note("thickness " + std::string(t) + ": exit " + std::to_string(pre.exit_code) + " / " +
             std::to_string(solve.exit_code),
         pre.exit_code == 2 && solve.exit_code == 2 && !fs::exists(out) && nothing_written(run));
  }
  record_margin(
      {"09b-negative-volume-geometry",
       "a geometry that would give negative volumes: clockwise outline, inside-out surface, "
       "self-overlapping outline, non-positive thickness",
       "no negative volume ever reaches a points file: oriented (same points) or refused with exit 2 naming the "
       "file or key",
       measured, "contract check (no numeric margin)", all});
}

}  // namespace
}  // namespace mppm::stability
