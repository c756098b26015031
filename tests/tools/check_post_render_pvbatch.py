# A real ParaView (run as: xvfb-run -a pvbatch check_post_render_pvbatch.py RESULTS.pvd OUT.png)
# opens the series written by mppm-postprocess, goes to the last time, applies Warp By Vector
# with 'displacement', colours by 'damage' and saves a PNG. Exit code != 0 on any problem.
import sys

from paraview.simple import (ColorBy, CreateView, GetAnimationScene, PVDReader, Render, SaveScreenshot,
                             Show, WarpByVector)


def main():
    pvd, output = sys.argv[1], sys.argv[2]
    reader = PVDReader(FileName=pvd)
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    if len(times) < 2:
        raise SystemExit(f"{pvd}: expected a time series, got times {times}")
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = times[-1]
    reader.UpdatePipeline(times[-1])
    arrays = list(reader.PointData.keys())
    for name in ("displacement", "damage"):
        if name not in arrays:
            raise SystemExit(f"{pvd}: no point array '{name}' (has {arrays})")
    warp = WarpByVector(Input=reader)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = 20.0
    warp.UpdatePipeline(times[-1])
    bounds_before = reader.GetDataInformation().GetBounds()
    bounds_after = warp.GetDataInformation().GetBounds()
    if bounds_before == bounds_after:
        raise SystemExit("Warp By Vector did not move the points")
    view = CreateView("RenderView")
    view.ViewSize = [800, 500]
    view.ViewTime = times[-1]
    display = Show(warp, view)
    display.SetRepresentationType("Points")
    display.PointSize = 6
    ColorBy(display, ("POINTS", "damage"))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    view.ResetCamera(False)
    Render(view)
    SaveScreenshot(output, view, ImageResolution=[800, 500])
    print(f"rendered {output} at t = {times[-1]}; bounds {bounds_before} -> {bounds_after}")


if __name__ == "__main__":
    main()
