// Pictures of a post directory, made by external tools: load_curve.png through matplotlib, and
// through ParaView's pvbatch (headless under xvfb-run) contour images of chosen frames and a
// movie of one field over every frame. The camera is fitted to the body; in 3-D each image is
// an oblique view of the surface and a clip through a plane (postprocess/README.md, "Figures").
// Each picture is written under a temporary name and committed only when complete.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "postprocess/clip_plane.hpp"

namespace mppm::post {

// POST_DIR/load_curve.png from POST_DIR/load_curve.csv (main_boundary: the curve to mark, or
// empty). Throws ExternalToolError if python3 or matplotlib is missing or the plot fails.
void plot_load_curve(const std::string& post_directory, const std::string& main_boundary,
                     const std::string& script_directory);

struct FigureFrame {
  std::string vtu;         // frame file, relative to the post directory
  std::int64_t step = 0;   // names the image: FIELD_STEP.png
  std::string time_label;  // "t = 20 us"
};

struct FigureSettings {
  double spacing = 0.0;  // dx [m]
  int dimension = 2;
  double warp_scale = 1.0;       // displacement scale of the deformed configuration
  std::string script_directory;  // empty = next to the executable
  ClipPlane clip;                // 3-D: the plane of the clip pictures
};

// The pictures of each field at each frame, in POST_DIR/figures: FIELD_STEP.png in 2-D;
// FIELD_STEP_iso.png (the oblique view of the surface) and FIELD_STEP_clip_AXIS.png (the part
// behind the clip plane) in 3-D. Returns the files written. Throws ExternalToolError if pvbatch
// is missing or rendering fails (no image is left then).
std::vector<std::string> render_figures(const std::string& post_directory, const FigureSettings& settings,
                                        const std::vector<FigureFrame>& frames, const std::vector<std::string>& fields);

// POST_DIR/movie_FIELD.mp4 (ffmpeg on PATH) or movie_FIELD.gif: one frame per entry of
// `frames`, all with one camera and one colour range fitted to every frame; in 3-D the oblique
// view, or the clip view with `clip_view`. Returns the file written. Throws ExternalToolError
// as render_figures does (no movie and no frame is left then).
std::string render_movie(const std::string& post_directory, const FigureSettings& settings,
                         const std::vector<FigureFrame>& frames, const std::string& field, bool clip_view);

}  // namespace mppm::post
