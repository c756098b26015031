// A real ParaView reads what mppm-postprocess writes: pvbatch (headless under xvfb-run) opens
// results.pvd, warps by displacement, colours by damage and renders a non-blank PNG; and
// --figures renders contour images. These tests FAIL (never skip) without ParaView: the
// workflows' make targets install the Debian packages paraview, xvfb and xauth.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "paraview_available.hpp"
#include "postprocess/external_tools.hpp"
#include "test_post_command.hpp"
#include "test_post_run_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mppm::post::testing;

// A contour image with a colour map has hundreds of distinct colours; a blank render has a
// handful (background, antialiased text). 64 separates the two with a wide margin.
constexpr const char* kMinimumColours = "64";

TEST(PostParaView, PvbatchRendersTheSeriesWarpedAndColouredByDamage) {
  ASSERT_TRUE(paraview_installed());
  const std::string dir = scratch_directory("pvbatch");
  write_run_directory(dir + "/run", RunFixture{});
  const auto post = run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet", "--no-plot"});
  ASSERT_EQ(post.exit_code, 0) << post.output;
  std::vector<std::string> environment;
  ASSERT_NO_THROW(environment = mppm::post::paraview_python_environment());
  std::vector<std::string> command{"env"};
  command.insert(command.end(), environment.begin(), environment.end());
  // -n: start the free-display search away from xvfb-run's default 99 (concurrent runs race).
  command.insert(command.end(), {"xvfb-run", "-a", "-n", std::to_string(900 + ::getpid() % 90), "-s",
                                 "-screen 0 1280x1024x24 -nolisten tcp -noreset", "pvbatch",
                                 std::string(MPPM_SOURCE_DIR) + "/tests/tools/check_post_render_pvbatch.py",
                                 dir + "/post/results.pvd", dir + "/render.png"});
  auto render = run_command(command);
  // Xvfb under load is sometimes not ready when pvbatch connects ("bad X server connection");
  // mppm-postprocess retries once for the same reason.
  if (render.exit_code != 0 && render.output.find("bad X server connection") != std::string::npos)
    render = run_command(command);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  ASSERT_TRUE(fs::exists(dir + "/render.png")) << render.output;
  const auto colours =
      run_command({"/usr/bin/python3", std::string(MPPM_SOURCE_DIR) + "/tests/tools/check_post_png_colours.py",
                   kMinimumColours, dir + "/render.png"});
  EXPECT_EQ(colours.exit_code, 0) << colours.output;
}

TEST(PostParaView, FiguresOptionWritesContourImagesOfChosenFieldsAndTimes) {
  ASSERT_TRUE(paraview_installed());
  const std::string dir = scratch_directory("figures");
  write_run_directory(dir + "/run", RunFixture{});
  const auto post =
      run_command({postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet", "--no-plot", "--figures",
                   "--fields", "damage,rotation", "--times", "1 us,3us", "--warp-scale", "10"});
  ASSERT_EQ(post.exit_code, 0) << post.output;
  std::vector<std::string> images;
  for (const char* field : {"damage", "rotation"})
    for (const char* step : {"000040", "000120"}) {
      const std::string png = dir + "/post/figures/" + field + "_" + step + ".png";
      EXPECT_TRUE(fs::exists(png)) << png;
      images.push_back(png);
    }
  // Exactly those four, and no temporary left behind.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir + "/post/figures")) {
    ++files;
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  }
  EXPECT_EQ(files, 4u);
  std::vector<std::string> command{
      "/usr/bin/python3", std::string(MPPM_SOURCE_DIR) + "/tests/tools/check_post_png_colours.py", kMinimumColours};
  command.insert(command.end(), images.begin(), images.end());
  const auto colours = run_command(command);
  EXPECT_EQ(colours.exit_code, 0) << colours.output;
}

}  // namespace
