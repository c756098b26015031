// The postprocessing stage as a library call: run directory -> post directory (docs/stages.md):
// results.pvd + results/*.vtu, load_curve.csv + load_curve.png, summary.json, view.py (a ParaView
// state of the series), and with `figures` PNG contour images through ParaView's pvbatch, with
// `movie_field` a movie.
// mppm-postprocess is a thin main.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "postprocess/clip_plane.hpp"
#include "postprocess/crack_angle.hpp"
#include "postprocess/json_value.hpp"
#include "postprocess/vtu_series_writer.hpp"

namespace mppm::post {

struct PostprocessOptions {
  std::string run_directory;
  std::string output_directory;
  bool force = false;  // --force: replace an earlier post directory
  bool quiet = false;
  bool allow_unfinished = false;  // --partial: a run whose status is still "running"
  bool plot_load_curve = true;    // load_curve.png through matplotlib
  VtuCompression compression = VtuCompression::zlib;
  std::string script_directory;  // helper scripts; empty = next to the executable
  // Figures (--figures, --fields, --times, --warp-scale).
  bool figures = false;
  std::vector<std::string> figure_fields;  // empty = damage, plastic_shear_strain, rotation (those present)
  std::vector<std::string> figure_times;   // texts with units ("20 us"); {"all"}; empty = last snapshot
  double warp_scale = 1.0;
  // 3-D pictures (--clip): the plane of the clip pictures; none = the mid-plane across the
  // body's largest extent. Given, it is also the view of the movie.
  std::optional<ClipPlane> clip;
  std::string movie_field;  // --movie FIELD: a movie of the field over every snapshot
  // Crack angle (--crack-tip, --crack-direction, --crack-angle-range): the tips and the range;
  // spacing and horizon come from the run.
  CrackAngleSettings crack_angle;
};

struct PostprocessResult {
  JsonValue summary;
  std::vector<std::string> notes;  // also in summary.json "notes"
  std::size_t frames = 0;
  std::vector<std::string> figures;  // PNG files written
  std::string movie;                 // the movie file written, if any
};

// Throws InputError (bad run directory or options), ExternalToolError (python/pvbatch).
PostprocessResult postprocess_run(const PostprocessOptions& options);

}  // namespace mppm::post
