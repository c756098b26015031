// Pictures of a post directory, made by external tools: load_curve.png through matplotlib and
// contour images of chosen frames through ParaView's pvbatch (headless under xvfb-run). Each
// picture is written under a temporary name and committed only when complete.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

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
};

// POST_DIR/figures/FIELD_STEP.png of each field at each frame; returns the files written.
// Throws ExternalToolError if pvbatch is missing or rendering fails (no image is left then).
std::vector<std::string> render_figures(const std::string& post_directory, const FigureSettings& settings,
                                        const std::vector<FigureFrame>& frames, const std::vector<std::string>& fields);

}  // namespace mppm::post
