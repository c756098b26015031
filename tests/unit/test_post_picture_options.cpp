// Bad picture options of mppm-postprocess (--clip, --movie): exit code 2, a message naming the
// option and what was expected, and nothing written, before any ParaView is needed.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "post_notched_run_3d.hpp"
#include "test_post_command.hpp"
#include "test_post_run_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mppm::post::testing;

CommandResult postprocess(const std::string& run, const std::string& post, const std::vector<std::string>& extra) {
  std::vector<std::string> command{postprocess_executable(), run, "-o", post, "--no-plot"};
  command.insert(command.end(), extra.begin(), extra.end());
  return run_command(command);
}

void expect_refused(const CommandResult& result, const std::string& post, const std::string& words) {
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find(words), std::string::npos) << "expected '" << words << "' in: " << result.output;
  EXPECT_FALSE(fs::exists(post)) << "refused before anything is written";
}

TEST(PostPictureOptions, ClipTextThatIsNotAnAxisAndALengthIsRefused) {
  const std::string dir = scratch_directory("clip_text");
  write_run_directory(dir + "/run", RunFixture{});
  const std::string post = dir + "/post";
  for (const char* text : {"w=5mm", "x", "x=", "x=abc", "xy=5mm", "=5mm", ""})
    expect_refused(postprocess(dir + "/run", post, {"--figures", "--clip", text}), post, "--clip");
  // A length of the wrong dimension: the unit parser names it.
  const auto seconds = postprocess(dir + "/run", post, {"--figures", "--clip", "x=5 s"});
  expect_refused(seconds, post, "--clip 'x=5 s'");
  expect_refused(seconds, post, "length");
  expect_refused(postprocess(dir + "/run", post, {"--figures", "--clip", "w=5mm"}), post, "'w' is not x, y or z");
}

TEST(PostPictureOptions, ClipNeedsPicturesAndA3dRun) {
  const std::string dir = scratch_directory("clip_2d");
  write_run_directory(dir + "/run", RunFixture{});
  const std::string post = dir + "/post";
  expect_refused(postprocess(dir + "/run", post, {"--clip", "x=5mm"}), post, "add --figures or --movie");
  expect_refused(postprocess(dir + "/run", post, {"--figures", "--clip", "x=5mm"}), post, "this run is 2-D");
}

TEST(PostPictureOptions, ClipPlaneOutsideTheBodyIsRefused) {
  const std::string dir = scratch_directory("clip_outside");
  std::string failure;
  const std::string run = write_notched_run_3d(dir, failure);
  ASSERT_FALSE(run.empty()) << failure;
  const std::string post = dir + "/post";
  // The bar's points span x = 1 mm to 99 mm (cell centres of a 100 mm bar at dx = 2 mm).
  const auto outside = postprocess(run, post, {"--figures", "--clip", "x=150mm"});
  expect_refused(outside, post, "--clip x=150 mm: the plane misses the body");
  expect_refused(outside, post, "x = 1 mm to 99 mm");
  expect_refused(postprocess(run, post, {"--movie", "damage", "--clip", "z=-1mm"}), post, "misses the body");
}

TEST(PostPictureOptions, MovieOfAFieldTheRunDoesNotHaveIsRefused) {
  const std::string dir = scratch_directory("movie_field");
  write_run_directory(dir + "/run", RunFixture{});
  const std::string post = dir + "/post";
  const auto unknown = postprocess(dir + "/run", post, {"--movie", "temperature"});
  expect_refused(unknown, post, "--movie: the run has no field 'temperature'");
  expect_refused(unknown, post, "plastic_shear_strain");  // lists what is available
  expect_refused(postprocess(dir + "/run", post, {"--movie", " "}), post, "--movie: expected the name of a field");
}

}  // namespace
