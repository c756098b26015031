"""Shared reading of the crack-branching case outputs (check_case.py, report_case.py).

A run folder OUT/RUN/ holds points.vtp (its copy of the case's points file), run/ and post/.
Set-up values (plate, lattice, pre-crack, loading) come from these files, never from a copy.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
import mppm_outputs  # noqa: E402
from mppm_outputs import RunOutputError  # noqa: E402,F401  (the readers' error, for the scripts)
from elastic_waves import rayleigh_speed  # noqa: E402,F401  (for the scripts)
from case_runs import energy_rows, frames, load_rows, run_info, summary  # noqa: E402,F401  (for the scripts)


def crack_damage_threshold(run_summary):
    """The postprocessor's crack-path threshold (points with damage >= it), from summary.json."""
    try:
        return float(run_summary["crack_damage_threshold"])
    except (KeyError, TypeError, ValueError):
        raise RunOutputError("summary.json has no crack_damage_threshold: postprocess the run with "
                             "this version of mppm-postprocess") from None


def lattice(out, run):
    """(width, height, nx, ny) of the run's plate: the points file's cell-centred lattice."""
    points_file = os.path.join(out, run, "points.vtp")
    spacing = mppm_outputs.vtk_field_array(points_file, "spacing")[0]
    xyz = mppm_outputs.vtk_field_array(points_file, "Points")
    xs, ys = xyz[0::3], xyz[1::3]
    width, height = max(xs) - min(xs) + spacing, max(ys) - min(ys) + spacing
    return width, height, round(width / spacing), round(height / spacing)


def precrack_tip(out, run):
    """(x, y) of the pre-crack's tip: of the ends of the pre-crack polyline the points file
    holds (precrack_vertices, the scene's geometry.precracks as the preprocessor cut them), the
    one deepest inside the lattice's bounding box (an edge crack's inner end)."""
    points_file = os.path.join(out, run, "points.vtp")
    vertices = mppm_outputs.vtk_field_array(points_file, "precrack_vertices")
    ends = {}
    for k in range(0, len(vertices), 3):  # each end appears once, every inner vertex twice
        key = (round(vertices[k], 12), round(vertices[k + 1], 12))
        ends[key] = ends.get(key, 0) + 1
    ends = [p for p, n in ends.items() if n == 1]
    if not ends:
        raise RunOutputError(f"{points_file}: no pre-crack")
    xyz = mppm_outputs.vtk_field_array(points_file, "Points")
    xs, ys = xyz[0::3], xyz[1::3]
    depth = lambda p: min(p[0] - min(xs), max(xs) - p[0], p[1] - min(ys), max(ys) - p[1])  # noqa: E731
    return max(ends, key=depth)


def traction(out, run, boundary="top"):
    """Largest |traction| [Pa] of the run's condition on BOUNDARY (its resolved history)."""
    scene = mppm_outputs.resolved_scene(os.path.join(out, run, "run"))
    condition = next(bc for bc in scene["boundary_conditions"] if bc["name"] == boundary)
    return max(math.hypot(*value) for _, value in condition["history"])


def crack_points(path, threshold):
    """Body points (region 0) with damage >= threshold of one frame: a set of (x, y) rounded to
    a micrometre (the lattice is exact in the files up to round-off)."""
    import meshio  # Debian python3-meshio, under /usr/bin/python3
    m = meshio.read(path)
    region = m.point_data["region"]
    damage = m.point_data["damage"]
    return {(round(p[0], 6), round(p[1], 6)) for p, r, d in zip(m.points, region, damage) if r == 0 and d >= threshold}
