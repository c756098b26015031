// POST_DIR/view.py, the ParaView state mppm-postprocess writes: it names the case's main field,
// and a real pvbatch (headless under xvfb-run, as in test_post_pvbatch.cpp) runs it from a moved
// post directory, shows the body points only and saves a non-blank picture of the requested
// size. Like the other ParaView tests, this FAILS (never skips) without ParaView: the workflows'
// make targets install the Debian packages paraview, xvfb and xauth.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>

#include "paraview_available.hpp"
#include "postprocess/external_tools.hpp"
#include "test_post_command.hpp"
#include "test_post_run_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mppm::post::testing;

// Width and height from the PNG header (signature, then the IHDR chunk: big-endian at 16 and 20).
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& path) {
  const std::string bytes = read_text(path);
  if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0 || bytes.compare(12, 4, "IHDR") != 0) return {0, 0};
  const auto word = [&bytes](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
    return value;
  };
  return {word(16), word(20)};
}

// `program` headless under xvfb-run, with ParaView's Python modules found, as test_post_pvbatch.cpp
// runs pvbatch.
std::vector<std::string> under_xvfb(const std::vector<std::string>& program) {
  std::vector<std::string> command{"env"};
  for (const auto& variable : mppm::post::paraview_python_environment()) command.push_back(variable);
  // -n: start the free-display search away from xvfb-run's default 99 (concurrent runs race).
  command.insert(command.end(), {"xvfb-run", "-a", "-n", std::to_string(800 + ::getpid() % 90), "-s",
                                 "-screen 0 1280x1024x24 -nolisten tcp -noreset"});
  command.insert(command.end(), program.begin(), program.end());
  return command;
}

// Runs it once more when Xvfb was not ready for the connection (see test_post_pvbatch.cpp).
CommandResult run_with_display(const std::vector<std::string>& command) {
  auto result = run_command(command);
  if (result.exit_code != 0 && result.output.find("bad X server connection") != std::string::npos)
    result = run_command(command);
  return result;
}

std::string postprocess(const std::string& dir, const RunFixture& fixture, std::vector<std::string> extra = {}) {
  write_run_directory(dir + "/run", fixture);
  std::vector<std::string> command{postprocess_executable(), dir + "/run", "-o", dir + "/post", "--quiet", "--no-plot"};
  command.insert(command.end(), extra.begin(), extra.end());
  const auto post = run_command(command);
  EXPECT_EQ(post.exit_code, 0) << post.output;
  return read_text(dir + "/post/view.py");
}

TEST(PostViewState, NamesTheMainFieldAndTheWarpScale) {
  const std::string dir = scratch_directory("view_state_fields");
  RunFixture fixture;
  const std::string damage = postprocess(dir + "/damage", fixture);
  EXPECT_NE(damage.find("FIELD = \"damage\""), std::string::npos);
  EXPECT_NE(damage.find("WARP_SCALE = 1 "), std::string::npos);
  fixture.damage = false;
  EXPECT_NE(postprocess(dir + "/plastic", fixture).find("FIELD = \"plastic_shear_strain\""), std::string::npos);
  fixture.plasticity = false;
  const std::string elastic = postprocess(dir + "/elastic", fixture, {"--warp-scale", "10"});
  EXPECT_NE(elastic.find("FIELD = \"displacement\""), std::string::npos);
  EXPECT_NE(elastic.find("TITLE = \"displacement magnitude [m]\""), std::string::npos);
  EXPECT_NE(elastic.find("WARP_SCALE = 10 "), std::string::npos);
}

TEST(PostViewState, PvbatchOpensAMovedPostDirectoryAndSavesAPicture) {
  ASSERT_TRUE(paraview_installed());
  const std::string dir = scratch_directory("view_state");
  const RunFixture fixture;
  postprocess(dir, fixture);
  // view.py must find results.pvd next to itself, not where it was written or the working directory.
  fs::create_directories(dir + "/moved");
  fs::rename(dir + "/post", dir + "/moved/post");
  std::vector<std::string> command;
  ASSERT_NO_THROW(command = under_xvfb({"pvbatch", dir + "/moved/post/view.py", "--screenshot", dir + "/view.png",
                                        "--resolution", "900x600"}));
  const auto render = run_with_display(command);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  // The last time (the fixture's snapshots are at 0, 1, 2 and 3 us), and the body only: the
  // fixture's layer rows (region > 0) are hidden, and no body point is detached (damage < 1).
  const std::string shown = "t = 3e-06 s, " + std::to_string(fixture.nx * fixture.ny) + " of " +
                            std::to_string(fixture_points(fixture)) + " points shown, coloured by 'damage'";
  EXPECT_NE(render.output.find(shown), std::string::npos) << render.output;
  ASSERT_TRUE(fs::exists(dir + "/view.png")) << render.output;
  EXPECT_EQ(png_size(dir + "/view.png"), std::make_pair(900u, 600u));
  // Not blank: a colour-mapped body has hundreds of colours, a blank view a handful (64 as in
  // test_post_pvbatch.cpp).
  const auto colours =
      run_command({"/usr/bin/python3", std::string(MPPM_SOURCE_DIR) + "/tests/tools/check_post_png_colours.py", "64",
                   dir + "/view.png"});
  EXPECT_EQ(colours.exit_code, 0) << colours.output;
}

}  // namespace
