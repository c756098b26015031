# Renders PNG contour images of mppm-postprocess frames with ParaView (pvbatch, headless under
# xvfb-run): each point drawn as a disc of one lattice spacing on the deformed configuration
# (Warp By Vector 'displacement'), coloured by a field, with a colour bar and the time.
# Usage: pvbatch mppm_figures_pvbatch.py SPEC.json   (SPEC written by mppm-postprocess:
#   {"spacing": dx, "dimension": 2, "warp_scale": 1, "images": [{"vtu", "field", "title",
#    "time_label", "output"}, ...]})
import json
import sys

from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, Show, Text, Threshold,
                             WarpByVector, XMLUnstructuredGridReader, SaveScreenshot, Render)


def new_view():
    view = CreateView("RenderView")
    view.ViewSize = [1600, 1000]
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    return view


def render(spec, image):
    # A fresh view per image: colour bars and labels of the previous image must not remain.
    view = new_view()
    reader = XMLUnstructuredGridReader(FileName=[image["vtu"]])
    reader.UpdatePipeline()
    names = list(reader.PointData.keys())
    source = reader
    created = [reader]
    if "region" in names:
        # The body only: boundary-layer points (region > 0) are fictitious, outside the body.
        body = Threshold(Input=reader)
        body.Scalars = ["POINTS", "region"]
        body.LowerThreshold = 0
        body.UpperThreshold = 0
        body.ThresholdMethod = "Between"
        source = body
        created.append(body)
    if "displacement" in names:
        source = WarpByVector(Input=source)
        source.Vectors = ["POINTS", "displacement"]
        source.ScaleFactor = float(spec.get("warp_scale", 1.0))
        source.UpdatePipeline()
        created.append(source)
    field = image["field"]
    if field not in names:
        raise SystemExit(f"{image['vtu']}: no point array '{field}' (has {', '.join(names)})")
    display = Show(source, view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Plain circle"
    # Discs circumscribing each lattice cell (radius dx / sqrt(2)): the body looks continuous.
    display.GaussianRadius = 0.7072 * float(spec["spacing"])
    components = source.PointData[field].GetNumberOfComponents()
    if components > 1:
        ColorBy(display, ("POINTS", field, "Magnitude"))
        title = image["title"].replace(" [", " magnitude [", 1) if "[" in image["title"] else image["title"]
    else:
        ColorBy(display, ("POINTS", field))
        title = image["title"]
    display.RescaleTransferFunctionToDataRange(True, False)
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Turbo" if field != "damage" else "Inferno (matplotlib)", True)
    display.SetScalarBarVisibility(view, True)
    bar = lut.GetScalarBar(view) if hasattr(lut, "GetScalarBar") else None
    if bar is None:
        from paraview.simple import GetScalarBar
        bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.TitleColor = [0.0, 0.0, 0.0]  # the default palette writes white text: invisible on white
    bar.LabelColor = [0.0, 0.0, 0.0]
    bar.ComponentTitle = ""
    bar.TitleFontSize = 20
    bar.LabelFontSize = 16
    bar.RangeLabelFormat = "%-#.3g"
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    bar.Position = [0.89, 0.15]
    bar.ScalarBarLength = 0.7
    label = Text(Text=image["time_label"] + ("" if float(spec.get("warp_scale", 1.0)) == 1.0
                                             else f"   (displacement x {spec['warp_scale']})"))
    label_display = Show(label, view)
    label_display.FontSize = 20
    label_display.Color = [0.0, 0.0, 0.0]
    label_display.WindowLocation = "Upper Left Corner"
    view.ResetCamera(False)
    view.CameraParallelProjection = 1
    if int(spec.get("dimension", 2)) == 2:
        view.InteractionMode = "2D"
        focal = view.CameraFocalPoint
        view.CameraPosition = [focal[0], focal[1], focal[2] + 1.0]
        view.CameraViewUp = [0.0, 1.0, 0.0]
        view.ResetCamera(False)
    Render(view)
    SaveScreenshot(image["output"], view, ImageResolution=[1600, 1000])
    for proxy in [label] + created[::-1]:
        Delete(proxy)
    Delete(view)


def main():
    if len(sys.argv) != 2:
        raise SystemExit("usage: pvbatch mppm_figures_pvbatch.py SPEC.json")
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    for image in spec["images"]:
        render(spec, image)


if __name__ == "__main__":
    main()
