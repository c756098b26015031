// Movie files from PNG frames (see movie_file.hpp).
#include "postprocess/movie_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/atomic_file.hpp"
#include "postprocess/external_tools.hpp"

namespace mppm::post {
namespace fs = std::filesystem;

namespace {

constexpr const char* kGifScript = "mppm_assemble_gif.py";

void fail(const std::string& temporary, const std::string& message) {
  std::error_code ec;
  fs::remove(temporary, ec);
  throw ExternalToolError(message);
}

// H.264 in yuv420p, the form every player reads; it needs even sizes (the pad keeps them even).
std::string mp4_from_frames(const std::string& ffmpeg, const fs::path& frames, const std::string& stem) {
  const std::string final_path = stem + ".mp4";
  const std::string temporary = temporary_with_extension(final_path);
  const int status = run_program(
      {ffmpeg, "-hide_banner", "-loglevel", "error", "-y", "-framerate", std::to_string(kMovieFramesPerSecond), "-i",
       (frames / "frame_%05d.png").string(), "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt",
       "yuv420p", "-movflags", "+faststart", temporary},
      true);
  if (status != 0 || !fs::exists(temporary))
    fail(temporary, "joining the movie frames failed (" + ffmpeg + " exited with " + std::to_string(status) + ")");
  commit_temporary(temporary, final_path);
  return final_path;
}

std::string gif_from_frames(const fs::path& frames, std::size_t count, const std::string& stem,
                            const std::string& script_directory) {
  const std::string python = "/usr/bin/python3";
  if (::access(python.c_str(), X_OK) != 0)
    throw ExternalToolError("/usr/bin/python3 is missing: install the Debian packages python3 and python3-pil");
  const std::string script = companion_script(kGifScript, script_directory);
  const std::string final_path = stem + ".gif";
  const std::string temporary = temporary_with_extension(final_path);
  std::vector<std::string> command{python, script, temporary, std::to_string(1000 / kMovieFramesPerSecond)};
  for (std::size_t k = 0; k < count; ++k) command.push_back((frames / movie_frame_name(k)).string());
  const int status = run_program(command, true);
  if (status != 0 || !fs::exists(temporary))
    fail(temporary, "joining the movie frames into a GIF failed (" + python + " " + script + " exited with " +
                        std::to_string(status) + "; is python3-pil installed?)");
  commit_temporary(temporary, final_path);
  return final_path;
}

}  // namespace

std::string movie_frame_name(std::size_t k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05zu.png", k);
  return name;
}

std::string assemble_movie(const std::string& frame_directory, std::size_t count, const std::string& stem,
                           const std::string& script_directory) {
  if (const auto ffmpeg = find_program("ffmpeg")) return mp4_from_frames(*ffmpeg, frame_directory, stem);
  return gif_from_frames(frame_directory, count, stem, script_directory);
}

}  // namespace mppm::post
