# Renders PNG pictures of mppm-postprocess frames with ParaView (pvbatch, headless under
# xvfb-run): each point drawn as a disc (2-D) or a shaded sphere (3-D) on the deformed
# configuration (Warp By Vector 'displacement'), coloured by a field, with a colour bar and the
# time. The camera is fitted to the body: the picture's height follows the body's shape and the
# body fills the frame left of the colour bar (postprocess/README.md, "Figures").
# Usage: pvbatch mppm_figures_pvbatch.py SPEC.json   (SPEC written by mppm-postprocess:
#   {"spacing": dx, "dimension": 2|3, "warp_scale": 1, "width": 1600,
#    "images": [{"vtu", "field", "title", "time_label", "view", "output"}, ...],
#    "movie": {"field", "title", "view", "width", "frames": [{"vtu", "time_label", "output"}, ...]}}
#   with "view": {"kind": "plane"|"iso"|"clip", "axis": 0|1|2, "position": metres, "label": text};
#   "movie" is optional: its frames share one camera and one colour range.)
import json
import math
import sys

from paraview import servermanager
from paraview.simple import (Clip, ColorBy, CreateView, Delete, GetColorTransferFunction, GetScalarBar, Render,
                             SaveScreenshot, Show, Text, Threshold, WarpByVector, XMLUnstructuredGridReader)
from vtkmodules.util.numpy_support import vtk_to_numpy
import numpy

# Picture layout in pixels of a 1600-pixel-wide picture (scaled with the width): the body's
# area is the picture less these margins; the colour bar and its labels sit in the right one,
# the time label in the top one.
MARGIN_LEFT, MARGIN_RIGHT, MARGIN_TOP, MARGIN_BOTTOM = 24, 210, 56, 24
# The picture's height follows the body's shape within these fractions of its width: a bar
# gets a wide picture, a column a tall one; the colour bar needs some height.
HEIGHT_MIN, HEIGHT_MAX = 0.40, 0.75
# A point is a disc (2-D) or sphere (3-D) circumscribing its lattice cell in the plane: radius
# dx / sqrt(2), so the body looks continuous.
RADIUS_OVER_SPACING = 0.7072


def unit(vector):
    norm = math.sqrt(sum(c * c for c in vector))
    return [c / norm for c in vector]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


# The oblique 3-D view ("iso"): from the front (+z), right (+x) and above (+y), azimuth 30
# degrees from z towards x and elevation 25 degrees. It shows three faces with the x-y face,
# where a plane model's picture would be, the largest; a true isometric view (1, 1, 1) draws a
# bar along x as a steep diagonal band across an otherwise empty frame.
OBLIQUE = [math.cos(math.radians(25)) * math.sin(math.radians(30)), math.sin(math.radians(25)),
           math.cos(math.radians(25)) * math.cos(math.radians(30))]
# The clip view looks at the cut face this far off its normal, towards the oblique view, so that
# the depth of the part behind it shows too.
CLIP_TILT_DEGREES = 35.0


def camera_axes(view):
    """(direction from the focal point to the camera, view up) as unit vectors. plane: down z
    with y up (2-D); iso: the oblique view with y up; clip: the normal of the plane tilted
    towards the oblique view, y up (z towards the camera's bottom for a horizontal cut)."""
    kind = view["kind"]
    if kind == "plane":
        return [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]
    if kind == "iso":
        return unit(OBLIQUE), [0.0, 1.0, 0.0]
    axis = int(view["axis"])
    across = list(OBLIQUE)
    across[axis] = 0.0
    across = unit(across)
    tilt = math.radians(CLIP_TILT_DEGREES)
    direction = [math.sin(tilt) * c for c in across]
    direction[axis] = math.cos(tilt)
    # A horizontal cut (y) is seen from above, x to the right: up is -z there.
    up = [0.0, 0.0, -1.0] if axis == 1 else [0.0, 1.0, 0.0]
    return unit(direction), up


class Pipeline:
    """reader -> body (region 0) -> attached points (detached 0) -> [clip] -> warp."""

    def __init__(self, spec, view, vtu):
        self.created = []
        self.reader = self.add(XMLUnstructuredGridReader(FileName=[vtu]))
        self.reader.UpdatePipeline()
        self.names = list(self.reader.PointData.keys())
        source = self.reader
        # Boundary-layer points (region > 0) are fictitious, outside the body; detached points
        # (no acting bond, docs/theory.md) fly off and would only stretch the frame.
        if "region" in self.names:
            source = self.keep(source, "region", 0.0, 0.0)
        if "detached" in self.names:
            source = self.keep(source, "detached", 0.0, 0.5)
        self.body = self.warped(spec, source)
        self.shown = self.body
        if view["kind"] == "clip":
            # Cut on the reference positions (the plane the user named), then warp.
            clip = self.add(Clip(Input=source))
            clip.ClipType = "Plane"
            normal = [0.0, 0.0, 0.0]
            normal[int(view["axis"])] = 1.0
            origin = [0.0, 0.0, 0.0]
            origin[int(view["axis"])] = float(view["position"])
            clip.ClipType.Origin = origin
            clip.ClipType.Normal = normal
            clip.Invert = 1  # keep the side behind the plane, whose cut face looks at the camera
            clip.Crinkleclip = 1  # whole points (vertex cells), none cut
            self.shown = self.warped(spec, clip)

    def add(self, proxy):
        self.created.append(proxy)
        return proxy

    def keep(self, source, array, lower, upper):
        kept = self.add(Threshold(Input=source))
        kept.Scalars = ["POINTS", array]
        kept.LowerThreshold = lower
        kept.UpperThreshold = upper
        kept.ThresholdMethod = "Between"
        return kept

    def warped(self, spec, source):
        if "displacement" not in self.names:
            return source
        warp = self.add(WarpByVector(Input=source))
        warp.Vectors = ["POINTS", "displacement"]
        warp.ScaleFactor = float(spec.get("warp_scale", 1.0))
        return warp

    def set_file(self, vtu):
        self.reader.FileName = [vtu]

    def delete(self):
        for proxy in self.created[::-1]:
            Delete(proxy)


def fetched(proxy):
    proxy.UpdatePipeline()
    return servermanager.Fetch(proxy)


def positions(proxy):
    data = fetched(proxy)
    points = data.GetPoints() if data is not None else None
    if points is None or data.GetNumberOfPoints() == 0:
        return numpy.zeros((0, 3))
    return vtk_to_numpy(points.GetData()).reshape(-1, 3)


def field_range(proxy, field):
    """(low, high) of the field (its magnitude for vectors) over the points of `proxy`, or None."""
    data = fetched(proxy)
    array = data.GetPointData().GetArray(field) if data is not None else None
    if array is None or array.GetNumberOfTuples() == 0:
        return None
    values = vtk_to_numpy(array)
    if values.ndim > 1:
        values = numpy.sqrt((values.astype(float) ** 2).sum(axis=1))
    return float(values.min()), float(values.max())


def union(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return min(a[0], b[0]), max(a[1], b[1])


class Framing:
    """The camera axes and the body's extent across them (screen coordinates, metres)."""

    def __init__(self, view):
        self.direction, up = camera_axes(view)
        # The view up as seen on the screen: its part across the viewing direction.
        along = sum(u * d for u, d in zip(up, self.direction))
        self.up = unit([u - along * d for u, d in zip(up, self.direction)])
        # Screen right = view direction x up, the view direction pointing away from the camera.
        self.right = cross(self.up, self.direction)
        self.box = None  # (xmin, xmax, ymin, ymax, depth min, depth max)

    def include(self, points):
        if len(points) == 0:
            return
        coordinates = [points @ numpy.array(axis) for axis in (self.right, self.up, self.direction)]
        box = []
        for values in coordinates:
            box += [float(values.min()), float(values.max())]
        if self.box is None:
            self.box = box
        else:
            self.box = [min(self.box[k], box[k]) if k % 2 == 0 else max(self.box[k], box[k]) for k in range(6)]

    def picture_size(self, width, radius):
        """(width, height): the height follows the body's shape (even, for video encoders)."""
        k = width / 1600.0
        if self.box is None:
            return width, 2 * round(0.3 * width)
        extent_x = self.box[1] - self.box[0] + 2 * radius
        extent_y = self.box[3] - self.box[2] + 2 * radius
        area_width = width - k * (MARGIN_LEFT + MARGIN_RIGHT)
        wanted = area_width * extent_y / max(extent_x, 1e-300) + k * (MARGIN_TOP + MARGIN_BOTTOM)
        height = min(max(wanted, HEIGHT_MIN * width), HEIGHT_MAX * width)
        return width, 2 * round(height / 2)

    def place(self, render_view, size, radius):
        """Parallel projection whose scale and centre put the body's extent in the body's area."""
        render_view.CameraParallelProjection = 1
        if self.box is None:
            render_view.ResetCamera(False)
            return
        width, height = size
        k = width / 1600.0
        area_width = width - k * (MARGIN_LEFT + MARGIN_RIGHT)
        area_height = height - k * (MARGIN_TOP + MARGIN_BOTTOM)
        extent_x = self.box[1] - self.box[0] + 2 * radius
        extent_y = self.box[3] - self.box[2] + 2 * radius
        metres_per_pixel = max(extent_x / area_width, extent_y / area_height, 1e-300)
        # Shift the focal point so the body's centre falls on the area's centre, not the picture's.
        shift_x = (k * MARGIN_LEFT + 0.5 * area_width - 0.5 * width) * metres_per_pixel
        shift_y = (k * MARGIN_BOTTOM + 0.5 * area_height - 0.5 * height) * metres_per_pixel
        centre = [0.5 * (self.box[0] + self.box[1]) - shift_x, 0.5 * (self.box[2] + self.box[3]) - shift_y,
                  0.5 * (self.box[4] + self.box[5])]
        focal = [centre[0] * self.right[c] + centre[1] * self.up[c] + centre[2] * self.direction[c] for c in range(3)]
        depth = self.box[5] - self.box[4] + extent_x + extent_y
        render_view.CameraFocalPoint = focal
        render_view.CameraPosition = [focal[c] + depth * self.direction[c] for c in range(3)]
        render_view.CameraViewUp = self.up
        render_view.CameraParallelScale = 0.5 * height * metres_per_pixel


def new_view(size, dimension):
    view = CreateView("RenderView")
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    if dimension == 2:
        view.InteractionMode = "2D"
    return view


def show_points(pipeline, view, spec):
    display = Show(pipeline.shown, view)
    display.SetRepresentationType("Point Gaussian")
    # 3-D: shaded spheres, so that faces and the cut read as surfaces; 2-D: flat discs.
    display.ShaderPreset = "Sphere" if int(spec.get("dimension", 2)) == 3 else "Plain circle"
    display.GaussianRadius = RADIUS_OVER_SPACING * float(spec["spacing"])
    return display


def colour(display, view, pipeline, field, title, value_range):
    components = pipeline.reader.PointData[field].GetNumberOfComponents()
    if components > 1:
        ColorBy(display, ("POINTS", field, "Magnitude"))
        title = title.replace(" [", " magnitude [", 1) if "[" in title else title + " magnitude"
    else:
        ColorBy(display, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    # Viridis for damage: its low end (an undamaged body) is a mid-dark blue on which the shading
    # of 3-D spheres still shows, where Inferno's black hides the body's shape.
    lut.ApplyPreset("Turbo" if field != "damage" else "Viridis (matplotlib)", True)
    lut.AutomaticRescaleRangeMode = "Never"
    if value_range is not None:
        low, high = value_range
        if high <= low:  # a uniform field: a range of its own size around it
            pad = max(abs(low) * 1e-6, 1e-30)
            low, high = low - pad, high + pad
        lut.RescaleTransferFunction(low, high)
    display.SetScalarBarVisibility(view, True)
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
    bar.Position = [1.0 - (MARGIN_RIGHT - 20) / 1600.0, 0.15]  # 20 pixels into the right margin
    bar.ScalarBarLength = 0.7


def label_text(spec, time_label, view_spec):
    parts = [time_label]
    scale = float(spec.get("warp_scale", 1.0))
    if scale != 1.0:
        parts.append(f"displacement drawn x {scale:g}")
    if view_spec.get("label"):
        parts.append(view_spec["label"])
    return "     ".join(parts)


def add_label(view, text):
    label = Text(Text=text)
    label_display = Show(label, view)
    label_display.FontSize = 20
    label_display.Color = [0.0, 0.0, 0.0]
    label_display.WindowLocation = "Upper Left Corner"
    return label


def check_field(pipeline, field, vtu):
    if field not in pipeline.names:
        raise SystemExit(f"{vtu}: no point array '{field}' (has {', '.join(pipeline.names)})")


def render_image(spec, image):
    # A fresh view per image: colour bars and labels of the previous image must not remain.
    radius = RADIUS_OVER_SPACING * float(spec["spacing"])
    pipeline = Pipeline(spec, image["view"], image["vtu"])
    check_field(pipeline, image["field"], image["vtu"])
    framing = Framing(image["view"])
    framing.include(positions(pipeline.shown))
    size = framing.picture_size(int(spec.get("width", 1600)), radius)
    view = new_view(size, int(spec.get("dimension", 2)))
    display = show_points(pipeline, view, spec)
    # The range of the whole body, so that the clip and the surface of one time compare.
    colour(display, view, pipeline, image["field"], image["title"], field_range(pipeline.body, image["field"]))
    label = add_label(view, label_text(spec, image["time_label"], image["view"]))
    Render(view)  # pvbatch resets the camera on a view's first render: place it after that
    framing.place(view, size, radius)
    Render(view)
    SaveScreenshot(image["output"], view, ImageResolution=list(size))
    Delete(label)
    pipeline.delete()
    Delete(view)


def render_movie(spec, movie):
    """One picture per frame, all with the camera and colour range fitted to every frame."""
    radius = RADIUS_OVER_SPACING * float(spec["spacing"])
    frames = movie["frames"]
    pipeline = Pipeline(spec, movie["view"], frames[0]["vtu"])
    check_field(pipeline, movie["field"], frames[0]["vtu"])
    framing = Framing(movie["view"])
    value_range = None
    for frame in frames:
        pipeline.set_file(frame["vtu"])
        framing.include(positions(pipeline.shown))
        value_range = union(value_range, field_range(pipeline.body, movie["field"]))
    size = framing.picture_size(int(movie.get("width", 1280)), radius)
    view = new_view(size, int(spec.get("dimension", 2)))
    display = show_points(pipeline, view, spec)
    colour(display, view, pipeline, movie["field"], movie["title"], value_range)
    label = add_label(view, "")
    Render(view)
    framing.place(view, size, radius)
    for frame in frames:
        pipeline.set_file(frame["vtu"])
        label.Text = label_text(spec, frame["time_label"], movie["view"])
        Render(view)
        SaveScreenshot(frame["output"], view, ImageResolution=list(size))
    Delete(label)
    pipeline.delete()
    Delete(view)


def main():
    if len(sys.argv) != 2:
        raise SystemExit("usage: pvbatch mppm_figures_pvbatch.py SPEC.json")
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    for image in spec.get("images", []):
        render_image(spec, image)
    if spec.get("movie"):
        render_movie(spec, spec["movie"])


if __name__ == "__main__":
    main()
