// Pictures of a post directory (see pictures.hpp): the load-curve plot and the pvbatch figures.
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

namespace mppm::post {
namespace fs = std::filesystem;

namespace {

constexpr const char* kPlotScript = "mppm_plot_load_curve.py";
constexpr const char* kFigureScript = "mppm_figures_pvbatch.py";

// A temporary name that keeps the extension (matplotlib and ParaView choose the format by it).
std::string temporary_with_extension(const fs::path& path) {
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR105329) on "." + std::string.
  std::string name(1, '.');
  name += path.stem().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  name += path.extension().string();
  return (path.parent_path() / name).string();
}

// What pvbatch renders: the figure script's JSON spec, and the images as (temporary, final) paths.
struct FigureJob {
  JsonValue spec;
  std::vector<std::pair<std::string, std::string>> outputs;
};

FigureJob figure_job(const fs::path& post, const FigureSettings& settings, const std::vector<FigureFrame>& frames,
                     const std::vector<std::string>& fields) {
  const fs::path figures = post / "figures";
  FigureJob job;
  job.spec = JsonValue::object();
  job.spec.set("spacing", settings.spacing);
  job.spec.set("dimension", settings.dimension);
  job.spec.set("warp_scale", settings.warp_scale);
  auto images = JsonValue::array();
  for (const FigureFrame& frame : frames)
    for (const auto& field : fields) {
      char name[160];
      std::snprintf(name, sizeof name, "%s_%06lld.png", field.c_str(), static_cast<long long>(frame.step));
      const fs::path final_path = figures / name;
      const std::string temporary = temporary_with_extension(final_path);
      std::string unit = field_unit(field);
      auto image = JsonValue::object();
      image.set("vtu", fs::absolute(post / frame.vtu).string());
      image.set("field", field);
      image.set("title", field + (unit.empty() ? std::string() : " [" + unit + "]"));
      image.set("time_label", frame.time_label);
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

}  // namespace

void plot_load_curve(const std::string& post_directory, const std::string& main_boundary,
                     const std::string& script_directory) {
  const fs::path post(post_directory);
  const std::string script = companion_script(kPlotScript, script_directory);
  const std::string python = "/usr/bin/python3";
  if (::access(python.c_str(), X_OK) != 0)
    throw ExternalToolError("/usr/bin/python3 is missing: install the Debian packages python3 and python3-matplotlib");
  const fs::path png = post / "load_curve.png";
  const std::string temporary = temporary_with_extension(png);
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
  const std::string script = companion_script(kFigureScript, settings.script_directory);
  const auto pvbatch = find_program("pvbatch");
  if (!pvbatch)
    throw ExternalToolError(
        "--figures needs ParaView's pvbatch, which is not on PATH: install the Debian "
        "packages paraview, xvfb and xauth");
  const auto xvfb = find_program("xvfb-run");
  const std::vector<std::string> environment = paraview_python_environment();
  const fs::path post(post_directory);
  const fs::path figures = post / "figures";
  std::error_code ec;
  fs::create_directories(figures, ec);
  if (ec) throw InputError(figures.string() + ": cannot create (" + ec.message() + ")");
  const FigureJob job = figure_job(post, settings, frames, fields);
  const std::string spec_path = (figures / (".figures.tmp-" + std::to_string(::getpid()) + ".json")).string();
  const std::string spec_text = job.spec.dump();
  write_file_atomically(spec_path, [&](std::ostream& out) { out << spec_text; });
  const std::vector<std::string> command = pvbatch_command(*pvbatch, xvfb, script, spec_path);
  // One retry: under load, Xvfb is sometimes not ready when pvbatch connects ("bad X server
  // connection", SIGABRT); a second attempt on a fresh server succeeds.
  int status = run_program(command, true, environment);
  if (status != 0 && xvfb) status = run_program(command, true, environment);
  fs::remove(spec_path, ec);
  bool complete = status == 0;
  for (const auto& [temporary, final_path] : job.outputs)
    if (!fs::exists(temporary)) complete = false;
  if (!complete) {
    for (const auto& output : job.outputs) fs::remove(output.first, ec);
    throw ExternalToolError("rendering the figures failed (pvbatch exited with " + std::to_string(status) +
                            (xvfb ? "" : "; xvfb-run is missing: install xvfb and xauth") + ")");
  }
  std::vector<std::string> written;
  for (const auto& [temporary, final_path] : job.outputs) {
    commit_temporary(temporary, final_path);
    written.push_back(final_path);
  }
  return written;
}

}  // namespace mppm::post
