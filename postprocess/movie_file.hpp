// Joins rendered PNG frames into one movie file: MP4 (H.264) through ffmpeg when it is on PATH,
// else an animated GIF through /usr/bin/python3 and PIL (python3-pil, which python3-matplotlib
// depends on), so that a movie needs no package beyond those of the plots. The file is written
// under a temporary name and renamed: it is complete or not there.
#pragma once
#include <cstddef>
#include <string>

namespace mppm::post {

// Frames per second of the movies: one frame per snapshot, five snapshots a second.
inline constexpr int kMovieFramesPerSecond = 5;

// The name of frame k in a frame directory: frame_00000.png, frame_00001.png, ...
std::string movie_frame_name(std::size_t k);

// `stem`.mp4 or `stem`.gif from frames 0 .. count - 1 of `frame_directory` (PNG, one size);
// returns the file written. Throws ExternalToolError when the tool fails (nothing is left).
std::string assemble_movie(const std::string& frame_directory, std::size_t count, const std::string& stem,
                           const std::string& script_directory);

}  // namespace mppm::post
