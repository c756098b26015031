"""Measures of the bands of one run, shared by check_case.py and report_case.py.

Everything starts from the postprocessor's bands (summary.json `shear_bands`: direction,
a point on the centre line, full width at half maximum) and the last snapshot's interior
points (the same interior as the postprocessor's metrics: body points farther than two
horizons from every boundary-layer or loaded point; shear_band_fields.LastSnapshot).

- inside a band: interior points within half the band's width of its centre line;
- arms: the inside points farther than one band width from the crossing of the two lines,
  because at the crossing the strains of both bands add and their micro-rotations, of
  opposite sense, cancel, so only the arms show what a band alone carries;
- ridge angle: an independent estimate of each band's angle, from the row-by-row maxima of
  the strain instead of the postprocessor's Hough transform and slice centroids.
"""
import math

import numpy as np


class Band:
    def __init__(self, entry):
        self.angle = float(entry["angle_deg"])
        self.direction = float(entry["direction_deg"])
        self.centre = np.array(entry["centre_m"], dtype=float)
        self.width = None if entry.get("width_m") is None else float(entry["width_m"])
        a = math.radians(self.direction)
        self.tangent = np.array([math.cos(a), math.sin(a)])
        self.normal = np.array([-math.sin(a), math.cos(a)])

    def distance(self, points):
        return (points - self.centre) @ self.normal

    @property
    def slope_sign(self):
        """+1 for a line rising to the right (direction < 90 deg), -1 for one falling."""
        return 1 if self.direction < 90.0 else -1


def bands_of(summary):
    return [Band(entry) for entry in summary.get("shear_bands") or []]


def crossing(first, second):
    """Intersection of the two centre lines, or None if they are (nearly) parallel."""
    matrix = np.column_stack([first.tangent, -second.tangent])
    if abs(np.linalg.det(matrix)) < 1e-6:
        return None
    t = np.linalg.solve(matrix, second.centre - first.centre)
    return first.centre + t[0] * first.tangent


class BandRegions:
    """Inside / arms / outside masks over the interior points of a snapshot."""

    def __init__(self, snapshot, bands):
        interior = snapshot.interior
        self.points = snapshot.reference[interior]
        self.strain = snapshot.plastic_shear_strain[interior]
        self.rotation = np.abs(snapshot.rotation[interior])
        self.bands = bands
        self.inside_each = [np.abs(b.distance(self.points)) <= 0.5 * b.width for b in bands]
        self.inside = np.logical_or.reduce(self.inside_each)
        self.outside = ~self.inside
        self.crossing = crossing(*bands) if len(bands) == 2 else None
        if self.crossing is not None:
            near = np.linalg.norm(self.points - self.crossing, axis=1) <= max(b.width for b in bands)
        else:
            near = np.zeros(len(self.points), dtype=bool)
        self.arms = [inside & ~near for inside in self.inside_each]

    def strain_contrast(self, k):
        """Mean strain on band k's arms over the mean strain outside every band."""
        if not self.arms[k].any() or not self.outside.any():
            return None
        return float(self.strain[self.arms[k]].mean() / max(self.strain[self.outside].mean(), 1e-300))

    def rotation_ratio(self):
        """Mean |micro-rotation| inside the bands over the mean outside them."""
        if not self.inside.any() or not self.outside.any():
            return None
        return float(self.rotation[self.inside].mean() / max(self.rotation[self.outside].mean(), 1e-300))

    def ridge_angle(self, k, spacing):
        """Band k's acute angle to the x axis from the strain maxima of the lattice rows.

        Each lattice row (constant y) that crosses band k's arms, within one band width of its
        centre line and nearer it than the other band, gives the x of its largest strain,
        refined by a parabola through the maximum and its two row neighbours; a least-squares
        line x(y) through these ridge points gives the angle. Returns (angle, rows used)."""
        band = self.bands[k]
        distance = np.abs(band.distance(self.points))
        use = (distance <= band.width) & self._not_near_crossing(1.5 * max(b.width for b in self.bands))
        for o, other in enumerate(self.bands):
            if o != k:
                use &= distance <= np.abs(other.distance(self.points))
        rows = np.floor(self.points[:, 1] / spacing).astype(int)  # cell-centred rows: y / dx = j + 1/2
        ridge_x, ridge_y = [], []
        for row in np.unique(rows[use]):
            members = np.flatnonzero(use & (rows == row))
            if len(members) < 3:
                continue
            members = members[np.argsort(self.points[members, 0])]
            values = self.strain[members]
            top = int(np.argmax(values))
            if top == 0 or top == len(members) - 1:
                continue  # the maximum at the window's edge is not the ridge
            left, centre, right = values[top - 1], values[top], values[top + 1]
            curvature = left - 2 * centre + right
            shift = 0.0 if curvature >= 0 else 0.5 * (left - right) / curvature
            ridge_x.append(self.points[members[top], 0] + shift * spacing)
            ridge_y.append(self.points[members[top], 1])
        if len(ridge_x) < 4:
            return None, len(ridge_x)
        slope = np.polyfit(ridge_y, ridge_x, 1)[0]  # dx/dy along the ridge
        direction = math.degrees(math.atan2(1.0, slope))  # (0, 180)
        return min(direction, 180.0 - direction), len(ridge_x)

    def _not_near_crossing(self, radius):
        if self.crossing is None:
            return np.ones(len(self.points), dtype=bool)
        return np.linalg.norm(self.points - self.crossing, axis=1) > radius
