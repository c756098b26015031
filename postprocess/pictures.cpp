// Pictures of a post directory (see pictures.hpp): the load-curve plot, the pvbatch figures and
// the movie frames.
#include "postprocess/pictures.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "postprocess/external_tools.hpp"
#include "postprocess/field_units.hpp"
#include "postprocess/json_value.hpp"
#include "postprocess/movie_file.hpp"

namespace mppm::post {
namespace fs = std::filesystem;

namespace {

constexpr const char* kPlotScript = "mppm_plot_load_curve.py";
constexpr const char* kFigureScript = "mppm_figures_pvbatch.py";
// Picture widths [pixels]; the height follows the body's shape (the figure script).
constexpr int kFigureWidth = 1600;
constexpr int kMovieWidth = 1280;

// How pvbatch looks at the body: "plane" (2-D, down z), "iso" (3-D, oblique) or "clip".
JsonValue view_spec(const std::string& kind, const ClipPlane& clip) {
  auto view = JsonValue::object();
  view.set("kind", kind);
  if (kind == "clip") {
    view.set("axis", clip.axis);
    view.set("position", clip.position);
    view.set("label", "clipped at " + axis_name(clip.axis) + " = " + format_length(clip.position));
  }
  return view;
}

JsonValue spec_header(const FigureSettings& settings) {
  auto spec = JsonValue::object();
  spec.set("spacing", settings.spacing);
  spec.set("dimension", settings.dimension);
  spec.set("warp_scale", settings.warp_scale);
  spec.set("width", kFigureWidth);
  return spec;
}

std::string colour_bar_title(const std::string& field) {
  const std::string unit = field_unit(field);
  return field + (unit.empty() ? std::string() : " [" + unit + "]");
}

// What pvbatch renders: the figure script's JSON spec, and the images as (temporary, final) paths.
struct FigureJob {
  JsonValue spec;
  std::vector<std::pair<std::string, std::string>> outputs;
};

// The views of each picture and the suffixes of their file names: "" in 2-D, "_iso" and
// "_clip_x" in 3-D.
std::vector<std::pair<std::string, std::string>> figure_views(const FigureSettings& settings) {
  if (settings.dimension != 3) return {{"plane", ""}};
  return {{"iso", "_iso"}, {"clip", "_clip_" + axis_name(settings.clip.axis)}};
}

FigureJob figure_job(const fs::path& post, const FigureSettings& settings, const std::vector<FigureFrame>& frames,
                     const std::vector<std::string>& fields) {
  const fs::path figures = post / "figures";
  FigureJob job;
  job.spec = spec_header(settings);
  auto images = JsonValue::array();
  for (const FigureFrame& frame : frames)
    for (const auto& field : fields)
      for (const auto& [kind, suffix] : figure_views(settings)) {
        char name[200];
        std::snprintf(name, sizeof name, "%s_%06lld%s.png", field.c_str(), static_cast<long long>(frame.step),
                      suffix.c_str());
        const fs::path final_path = figures / name;
        const std::string temporary = temporary_with_extension(final_path.string());
        auto image = JsonValue::object();
        image.set("vtu", fs::absolute(post / frame.vtu).string());
        image.set("field", field);
        image.set("title", colour_bar_title(field));
        image.set("time_label", frame.time_label);
        image.set("view", view_spec(kind, settings.clip));
        image.set("output", fs::absolute(temporary).string());
        images.push(image);
        job.outputs.emplace_back(temporary, final_path.string());
      }
  job.spec.set("images", images);
  return job;
}

// pvbatch under xvfb-run if there is one, else offscreen.
std::vector<std::string> pvbatch_command(const std::string& pvbatch, const std::optional<std::string>& xvfb,
                                         const std::string& script, const std::string& spec_path) {
  // xvfb-run -a starts its search at display 99, so concurrent runs race for the same display;
  // starting from a number derived from the process id avoids that. 24-bit: OpenGL needs it.
  // -noreset: Xvfb otherwise resets when pvbatch's first (probing) connection closes, and a
  // connection made during the reset fails ("bad X server connection") on a loaded machine.
  const std::string display = std::to_string(100 + ::getpid() % 800);
  if (xvfb)
    return {*xvfb,   "-a",   "-n",     display, "-s", "-screen 0 1920x1080x24 -nolisten tcp -noreset",
            pvbatch, script, spec_path};
  return {pvbatch, "--force-offscreen-rendering", script, spec_path};
}

// Runs the figure script on `spec` (written next to the outputs, in `directory`). Throws
// ExternalToolError, with every output removed, unless pvbatch succeeded and wrote them all.
void run_figure_script(const FigureSettings& settings, const fs::path& directory, const JsonValue& spec,
                       const std::vector<std::string>& outputs) {
  const std::string script = companion_script(kFigureScript, settings.script_directory);
  const auto pvbatch = find_program("pvbatch");
  if (!pvbatch)
    throw ExternalToolError(
        "--figures and --movie need ParaView's pvbatch, which is not on PATH: install the Debian "
        "packages paraview, xvfb and xauth");
  const auto xvfb = find_program("xvfb-run");
  const std::vector<std::string> environment = paraview_python_environment();
  const std::string spec_path = (directory / (".figures.tmp-" + std::to_string(::getpid()) + ".json")).string();
  const std::string spec_text = spec.dump();
  write_file_atomically(spec_path, [&](std::ostream& out) { out << spec_text; });
  const std::vector<std::string> command = pvbatch_command(*pvbatch, xvfb, script, spec_path);
  // One retry: under load, Xvfb is sometimes not ready when pvbatch connects ("bad X server
  // connection", SIGABRT); a second attempt on a fresh server succeeds.
  int status = run_program(command, true, environment);
  if (status != 0 && xvfb) status = run_program(command, true, environment);
  std::error_code ec;
  fs::remove(spec_path, ec);
  bool complete = status == 0;
  for (const auto& output : outputs)
    if (!fs::exists(output)) complete = false;
  if (!complete) {
    for (const auto& output : outputs) fs::remove(output, ec);
    throw ExternalToolError("rendering the pictures failed (pvbatch exited with " + std::to_string(status) +
                            (xvfb ? "" : "; xvfb-run is missing: install xvfb and xauth") + ")");
  }
}

void make_directory(const fs::path& directory) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) throw InputError(directory.string() + ": cannot create (" + ec.message() + ")");
}

// Removes a directory of temporary frames when it goes out of scope, whatever happened.
struct ScratchDirectory {
  fs::path path;
  ~ScratchDirectory() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

void plot_load_curve(const std::string& post_directory, const std::string& main_boundary,
                     const std::string& script_directory) {
  const fs::path post(post_directory);
  const std::string script = companion_script(kPlotScript, script_directory);
  const std::string python = "/usr/bin/python3";
  if (::access(python.c_str(), X_OK) != 0)
    throw ExternalToolError("/usr/bin/python3 is missing: install the Debian packages python3 and python3-matplotlib");
  const fs::path png = post / "load_curve.png";
  const std::string temporary = temporary_with_extension(png.string());
  const int status = run_program({python, script, (post / "load_curve.csv").string(), temporary, main_boundary}, true);
  if (status != 0 || !fs::exists(temporary)) {
    std::error_code ec;
    fs::remove(temporary, ec);
    throw ExternalToolError("plotting load_curve.png failed (" + python + " " + script + " exited with " +
                            std::to_string(status) + "; is python3-matplotlib installed?)");
  }
  commit_temporary(temporary, png.string());
}

std::vector<std::string> render_figures(const std::string& post_directory, const FigureSettings& settings,
                                        const std::vector<FigureFrame>& frames,
                                        const std::vector<std::string>& fields) {
  const fs::path post(post_directory);
  const fs::path figures = post / "figures";
  make_directory(figures);
  const FigureJob job = figure_job(post, settings, frames, fields);
  std::vector<std::string> temporaries;
  for (const auto& output : job.outputs) temporaries.push_back(output.first);
  run_figure_script(settings, figures, job.spec, temporaries);
  std::vector<std::string> written;
  for (const auto& [temporary, final_path] : job.outputs) {
    commit_temporary(temporary, final_path);
    written.push_back(final_path);
  }
  return written;
}

std::string render_movie(const std::string& post_directory, const FigureSettings& settings,
                         const std::vector<FigureFrame>& frames, const std::string& field, bool clip_view) {
  const fs::path post(post_directory);
  const ScratchDirectory scratch{post / (".movie_" + field + ".tmp-" + std::to_string(::getpid()))};
  std::error_code ec;
  fs::remove_all(scratch.path, ec);
  make_directory(scratch.path);
  auto movie = JsonValue::object();
  movie.set("field", field);
  movie.set("title", colour_bar_title(field));
  const std::string kind = settings.dimension != 3 ? "plane" : (clip_view ? "clip" : "iso");
  movie.set("view", view_spec(kind, settings.clip));
  movie.set("width", kMovieWidth);
  auto movie_frames = JsonValue::array();
  std::vector<std::string> outputs;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    auto frame = JsonValue::object();
    frame.set("vtu", fs::absolute(post / frames[k].vtu).string());
    frame.set("time_label", frames[k].time_label);
    outputs.push_back(fs::absolute(scratch.path / movie_frame_name(k)).string());
    frame.set("output", outputs.back());
    movie_frames.push(frame);
  }
  movie.set("frames", movie_frames);
  JsonValue spec = spec_header(settings);
  spec.set("movie", movie);
  run_figure_script(settings, scratch.path, spec, outputs);
  return assemble_movie(scratch.path.string(), frames.size(), (post / ("movie_" + field)).string(),
                        settings.script_directory);
}

}  // namespace mppm::post
