// view.py (see paraview_state.hpp): a fixed Python template with the run's choices filled in.
// The arrays it hides by are those of postprocess/README.md: `region` (> 0: a boundary layer,
// outside the body) and `detached` (1: a point without acting bonds, docs/theory.md), or, when
// the run did not write `detached`, damage 1 (every bond of the point broken).
#include "postprocess/paraview_state.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "common/atomic_file.hpp"
#include "postprocess/field_units.hpp"

namespace mppm::post {
namespace {

// @FIELD@, @TITLE@, @WARP_SCALE@, @SPACING@ and @DIMENSION@ are filled in by paraview_state_script.
constexpr const char* kTemplate =
    R"PY(# ParaView state of this post directory, written by mppm-postprocess (postprocess/README.md,
# "Opening a run in ParaView"). Open it with
#   paraview --script=view.py
#   pvbatch view.py [--screenshot OUT.png] [--resolution 1280x800]
# It reads results.pvd next to this file (so the folder can be moved), hides the boundary-layer
# and detached points, warps the rest by `displacement`, colours them by the case's main field
# and goes to the last time.
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,
                             GetScalarBar, PVDReader, Render, SaveScreenshot, SetActiveSource, Show, Threshold,
                             WarpByVector)

FIELD = "@FIELD@"  # damage, else plastic_shear_strain, else displacement (its magnitude)
TITLE = "@TITLE@"
WARP_SCALE = @WARP_SCALE@  # mppm-postprocess --warp-scale (1: the true deformed configuration)
SPACING = @SPACING@  # lattice spacing dx [m]: each point is drawn as a disc of radius dx / sqrt(2)
DIMENSION = @DIMENSION@
# Damage 1 means every bond of the point is broken: it is detached (used without `detached`).
DETACHED_DAMAGE = 1.0 - 1e-6


def options(argv):
    screenshot, resolution = None, [1280, 800]
    for k, arg in enumerate(argv[:-1]):
        if arg == "--screenshot":
            screenshot = argv[k + 1]
        elif arg == "--resolution":
            resolution = [int(v) for v in argv[k + 1].lower().split("x")]
    return screenshot, resolution


def script_path():
    try:
        return __file__  # pvbatch and pvpython
    except NameError:  # the GUI runs the text of --script=FILE without naming the file
        try:
            with open("/proc/self/cmdline", "rb") as f:
                args = f.read().decode(errors="replace").split("\0")
        except OSError:
            return None
        for k, arg in enumerate(args):
            if arg.startswith("--script="):
                return arg[len("--script="):]
            if arg == "--script" and k + 1 < len(args):
                return args[k + 1]
    return None


def results_file():
    script = script_path()
    for directory in ([os.path.dirname(os.path.abspath(script))] if script else []) + [os.getcwd()]:
        if os.path.isfile(os.path.join(directory, "results.pvd")):
            return os.path.join(directory, "results.pvd")
    raise SystemExit(f"view.py: no results.pvd next to {script or 'this script'}: keep view.py in its post directory")


def keep(source, array, lower, upper, name):
    kept = Threshold(registrationName=name, Input=source)
    kept.Scalars = ["POINTS", array]
    kept.LowerThreshold = lower
    kept.UpperThreshold = upper
    kept.ThresholdMethod = "Between"
    return kept


def pipeline(pvd):
    reader = PVDReader(registrationName="results.pvd", FileName=pvd)
    reader.UpdatePipelineInformation()
    arrays = list(reader.PointData.keys())
    source = reader
    if "region" in arrays:  # boundary-layer points (region > 0) are outside the body
        source = keep(source, "region", 0, 0, "body (region 0)")
    if "detached" in arrays:
        source = keep(source, "detached", 0, 0.5, "attached points")
    elif "damage" in arrays:
        source = keep(source, "damage", 0, DETACHED_DAMAGE, "attached points (damage < 1)")
    if "displacement" in arrays:
        warp = WarpByVector(registrationName="deformed", Input=source)
        warp.Vectors = ["POINTS", "displacement"]
        warp.ScaleFactor = WARP_SCALE
        source = warp
    return reader, source


def colour(display, view):
    if not FIELD:
        return
    ColorBy(display, ("POINTS", FIELD, "Magnitude") if FIELD == "displacement" else ("POINTS", FIELD))
    lut = GetColorTransferFunction(FIELD)
    if FIELD == "damage":
        lut.ApplyPreset("Viridis (matplotlib)", True)  # as the figures: shading shows on its dark end
        lut.AutomaticRescaleRangeMode = "Never"
        lut.RescaleTransferFunction(0.0, 1.0)
    else:
        lut.ApplyPreset("Turbo", True)
        display.RescaleTransferFunctionToDataRange(False, True)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = TITLE
    bar.ComponentTitle = ""
    bar.WindowLocation = "Lower Center"  # below the body: a vertical bar at the side can cover it
    bar.Orientation = "Horizontal"
    bar.RangeLabelFormat = "%-#.3g"


def camera(view):
    view.ResetCamera(False)
    if DIMENSION == 2:
        view.InteractionMode = "2D"
        view.CameraParallelProjection = 1
        focal = view.CameraFocalPoint
        view.CameraPosition = [focal[0], focal[1], focal[2] + 1.0]
        view.CameraViewUp = [0.0, 1.0, 0.0]
        view.ResetCamera(False)
        view.CameraParallelScale = 1.25 * view.CameraParallelScale  # room for the colour bar below


def main():
    screenshot, resolution = options(sys.argv[1:])
    reader, shown = pipeline(results_file())
    view = GetActiveViewOrCreate("RenderView")
    if screenshot:  # the picture's size, so that the text keeps its size relative to the body
        view.ViewSize = resolution
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.GoToLast()  # the time keeper moves the view to the last time
    display = Show(shown, view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Plain circle"
    display.GaussianRadius = 0.7072 * SPACING
    colour(display, view)
    SetActiveSource(shown)
    Render(view)  # pvbatch resets the camera on a view's first render: place it after that
    camera(view)
    Render(view)
    shown_points = shown.GetDataInformation().GetNumberOfPoints()
    all_points = reader.GetDataInformation().GetNumberOfPoints()
    print(f"view.py: t = {view.ViewTime:g} s, {shown_points} of {all_points} points shown, coloured by '{FIELD}'")
    if screenshot:
        SaveScreenshot(screenshot, view, ImageResolution=resolution)


main()
)PY";

void replace_all(std::string& text, const std::string& key, const std::string& value) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
    text.replace(at, key.size(), value);
}

// A Python float literal that reads back to the same double.
std::string python_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

}  // namespace

std::string view_field(const std::vector<std::string>& array_names) {
  for (const char* name : {"damage", "plastic_shear_strain", "pore_pressure", "displacement"})
    if (std::find(array_names.begin(), array_names.end(), name) != array_names.end()) return name;
  return {};
}

std::string paraview_state_script(const ParaViewStateSettings& settings) {
  const std::string unit = field_unit(settings.field);
  std::string title = settings.field == "displacement" ? "displacement magnitude" : settings.field;
  if (!unit.empty()) title += " [" + unit + "]";
  std::string text = kTemplate;
  replace_all(text, "@FIELD@", settings.field);
  replace_all(text, "@TITLE@", title);
  replace_all(text, "@WARP_SCALE@", python_number(settings.warp_scale));
  replace_all(text, "@SPACING@", python_number(settings.spacing));
  replace_all(text, "@DIMENSION@", std::to_string(settings.dimension));
  return text;
}

void write_paraview_state(const std::string& post_directory, const ParaViewStateSettings& settings) {
  const std::string text = paraview_state_script(settings);
  write_file_atomically((std::filesystem::path(post_directory) / "view.py").string(),
                        [&](std::ostream& out) { out << text; });
}

}  // namespace mppm::post
