// mppm-postprocess RUN_DIR -o POST_DIR: the thin main of the postprocessing stage.
#include <iostream>
#include <sstream>

#include "common/comma_list.hpp"
#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "postprocess/external_tools.hpp"
#include "postprocess/postprocess_run.hpp"

namespace {

// The non-empty items of a list option, trimmed.
std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  for (const std::string& item : mppm::split_commas(text))
    if (std::string trimmed = mppm::trim_blanks(item); !trimmed.empty()) items.push_back(trimmed);
  return items;
}

const char* kUsage =
    "Usage: mppm-postprocess RUN_DIR -o POST_DIR [options]\n"
    "\n"
    "Turns a run directory of mppm-solve into what ParaView and plots open:\n"
    "  POST_DIR/results.pvd + results/*.vtu   one frame per snapshot, points at their reference\n"
    "                                         positions (Warp By Vector 'displacement' deforms them)\n"
    "  POST_DIR/load_curve.csv, load_curve.png  displacement and force of every loaded boundary\n"
    "  POST_DIR/summary.json                  counts, material, boundary conditions, peak load,\n"
    "                                         shear-band and crack metrics (see postprocess/README.md)\n"
    "\n"
    "Options:\n"
    "  -o POST_DIR          output directory (created; an existing non-empty one is refused)\n"
    "  --force              replace an earlier POST_DIR as a whole (no stale frames remain)\n"
    "  --figures            also render PNG contour images (ParaView pvbatch, headless) into\n"
    "                       POST_DIR/figures: FIELD_STEP.png in 2-D; in 3-D an oblique view of\n"
    "                       the surface, FIELD_STEP_iso.png, and a clip, FIELD_STEP_clip_X.png\n"
    "  --fields a,b         fields of the figures (default: damage, plastic_shear_strain,\n"
    "                       pore_pressure, rotation, those the run has)\n"
    "  --times t1,t2|all    snapshot times of the figures, with units ('20 us'); the nearest\n"
    "                       snapshot is used (default: the last one)\n"
    "  --clip AXIS=LENGTH   3-D: the plane of the clip pictures, e.g. 'x=50mm' (plain numbers are\n"
    "                       metres); they show the part of the body behind it, the cut face\n"
    "                       towards the camera (default: the mid-plane across the body's largest\n"
    "                       extent). Given, it is also the view of the movie\n"
    "  --movie FIELD        a movie of FIELD over every snapshot, one frame each, one camera and\n"
    "                       colour range: POST_DIR/movie_FIELD.mp4 when ffmpeg is on PATH, else\n"
    "                       POST_DIR/movie_FIELD.gif; in 3-D the oblique view (the clip with --clip)\n"
    "  --warp-scale S       displacement scale of the deformed configuration in pictures (default 1)\n"
    "  --compression KIND   .vtu compression: zlib (default), lz4 or none\n"
    "  --crack-tip X,Y[,Z]  a pre-crack tip (lengths: '50mm,20mm'; plain numbers are metres),\n"
    "                       repeatable; for notches cut out of the body (default: the tips of\n"
    "                       the damaged pre-crack of the first snapshot)\n"
    "  --crack-direction D  the pre-crack direction at the tip, pointing into the body: an angle\n"
    "                       from +x with its unit ('0deg') or a vector DX,DY; once for all tips\n"
    "                       or once per --crack-tip\n"
    "  --crack-angle-range FROM,TO  distances from the tip where a crack's angle is fitted\n"
    "                       (default: 2 and 12 horizons); measured per tip on the first\n"
    "                       snapshot where the crack reaches TO, else on the last one\n"
    "  --crack-angle-time T measure the crack angles on the last snapshot at or before T\n"
    "                       (a time with its unit: '40us'; plain numbers are seconds)\n"
    "  --no-plot            skip load_curve.png (no matplotlib needed)\n"
    "  --partial            postprocess a run that did not finish (status 'running': it crashed\n"
    "                       or is still running), up to its last snapshot\n"
    "  --threads N          OpenMP threads (results do not depend on it)\n"
    "  --quiet              no progress output\n"
    "  --help, --version\n"
    "\n"
    "Exit codes: 0 success, 2 bad input (not a run directory, missing or truncated snapshot,\n"
    "crashed run, unknown field), 1 anything else (e.g. pvbatch or matplotlib missing).\n";

}  // namespace

int main(int argc, char** argv) {
  const mppm::CommandLineSpec spec{"mppm-postprocess",
                                   kUsage,
                                   {"-o", "--fields", "--times", "--warp-scale", "--clip", "--movie", "--compression",
                                    "--crack-tip", "--crack-direction", "--crack-angle-range", "--crack-angle-time"},
                                   {"--figures", "--partial", "--no-plot", "--force"}};
  return mppm::run_stage(argc, argv, spec, [](const mppm::CommandLine& cl) -> int {
    using mppm::InputError;
    if (cl.positional.size() != 1)
      throw InputError("expected one run directory (mppm-postprocess RUN_DIR -o POST_DIR; see --help)");
    const auto output = cl.option("-o");
    if (!output) throw InputError("missing -o POST_DIR (the output directory; see --help)");
    if (!cl.overrides.empty())
      throw InputError("--set does not apply to mppm-postprocess (it reads the resolved scene)");
    mppm::post::PostprocessOptions options;
    options.run_directory = cl.positional[0];
    options.output_directory = *output;
    options.quiet = cl.quiet;
    options.force = cl.has_flag("--force");
    options.allow_unfinished = cl.has_flag("--partial");
    options.plot_load_curve = !cl.has_flag("--no-plot");
    options.figures = cl.has_flag("--figures");
    if (const auto fields = cl.option("--fields")) options.figure_fields = split_list(*fields);
    if (const auto times = cl.option("--times")) options.figure_times = split_list(*times);
    if ((cl.option("--fields") || cl.option("--times")) && !options.figures)
      throw InputError("--fields and --times choose the figures: add --figures");
    if (const auto clip = cl.option("--clip")) options.clip = mppm::post::parse_clip_plane(*clip);
    if (const auto movie = cl.option("--movie")) {
      options.movie_field = mppm::trim_blanks(*movie);
      if (options.movie_field.empty()) throw InputError("--movie: expected the name of a field, e.g. --movie damage");
    }
    if (options.clip && !options.figures && options.movie_field.empty())
      throw InputError("--clip chooses the plane of the 3-D pictures: add --figures or --movie FIELD");
    if (const auto scale = cl.option("--warp-scale")) {
      try {
        std::size_t used = 0;
        options.warp_scale = std::stod(*scale, &used);
        if (used != scale->size()) throw std::invalid_argument("trailing text");
      } catch (const std::exception&) {
        throw InputError("--warp-scale: '" + *scale + "' is not a number");
      }
    }
    if (const auto kind = cl.option("--compression")) {
      if (*kind == "zlib")
        options.compression = mppm::post::VtuCompression::zlib;
      else if (*kind == "lz4")
        options.compression = mppm::post::VtuCompression::lz4;
      else if (*kind == "none")
        options.compression = mppm::post::VtuCompression::none;
      else
        throw InputError("--compression: '" + *kind + "' (expected zlib, lz4 or none)");
    }
    mppm::post::parse_crack_angle_options({cl.all_values("--crack-tip"), cl.all_values("--crack-direction"),
                                           cl.option("--crack-angle-range"), cl.option("--crack-angle-time")},
                                          options.crack_angle);
    try {
      const auto result = mppm::post::postprocess_run(options);
      for (const auto& note : result.notes) std::cerr << "mppm-postprocess: note: " << note << "\n";
      if (!cl.quiet) {
        std::cout << "mppm-postprocess: " << result.frames << " frames -> " << options.output_directory
                  << "/results.pvd, load_curve.csv" << (options.plot_load_curve ? ", load_curve.png" : "")
                  << ", summary.json";
        if (!result.figures.empty()) std::cout << ", " << result.figures.size() << " figures";
        if (!result.movie.empty()) std::cout << ", " << result.movie;
        std::cout << "\n";
      }
    } catch (const mppm::post::ExternalToolError& e) {
      std::cerr << "mppm-postprocess: error: " << e.what() << "\n";
      return mppm::kExitOther;
    }
    return mppm::kExitSuccess;
  });
}
