"""Reading one shear-band run's outputs for check_case.py and report_case.py.

A run folder (out/<run-name>/) holds run/ (solver) and post/ (postprocessor). Everything here
comes from those files: post/summary.json, post/load_curve.csv, run/energy.csv,
run/run_info.json and the last snapshot post/results/*.vtu (through post/results.pvd, so the
frame order is the postprocessor's).
"""
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import RunOutputError, frames  # noqa: E402


def parse_run_name(name):
    """'phi35-psi15' or 'phi35-psi15-published' -> (35.0, 15.0): the angles the Makefile sets for
    that run (the optional last word names the variant: published, quick, triaxial)."""
    m = re.fullmatch(r"phi([\d.]+)-psi([\d.]+)(-(published|quick|triaxial))?", name)
    if not m:
        raise RunOutputError(f"run name '{name}': expected phi<deg>-psi<deg>[-published|-quick|-triaxial]")
    return float(m.group(1)), float(m.group(2))


class Snapshot:
    """One frame of post/results.pvd (default the last): body points, deformed positions and
    fields; `pore_pressure` too when the run has it (None otherwise: a dry run)."""

    def __init__(self, post_dir, horizon, frame=-1):
        import meshio  # imported here so the table-only paths do not need it

        self.time, path = frames(post_dir)[frame]
        try:
            mesh = meshio.read(path)
        except Exception as e:  # meshio raises several types on a bad file
            raise RunOutputError(f"{path}: {e}") from e
        self.path = path
        data = mesh.point_data
        for name in ("region", "boundary_id", "displacement", "rotation", "plastic_shear_strain"):
            if name not in data:
                raise RunOutputError(f"{path}: no point array '{name}' (the scene's output.fields must hold it)")
        self.reference = mesh.points[:, :2]
        self.displacement = data["displacement"][:, :2]
        self.rotation = np.asarray(data["rotation"]).reshape(len(self.reference), -1)[:, -1]
        self.plastic_shear_strain = np.asarray(data["plastic_shear_strain"]).ravel()
        self.pore_pressure = np.asarray(data["pore_pressure"]).ravel() if "pore_pressure" in data else None
        self.body = np.asarray(data["region"]).ravel() == 0
        # Same interior as the postprocessor's shear-band metrics (postprocess/README.md):
        # body points farther than 2 horizons from every boundary-layer or loaded point,
        # because strain and rotation concentrate under the platens and the pressure layers.
        boundary = (np.asarray(data["region"]).ravel() != 0) | (np.asarray(data["boundary_id"]).ravel() != 0)
        from scipy.spatial import cKDTree

        distance, _ = cKDTree(self.reference[boundary]).query(self.reference)
        self.interior = self.body & (distance > 2.0 * horizon)

    @property
    def deformed(self):
        return self.reference + self.displacement


LastSnapshot = Snapshot  # the name check_case.py and report_case.py use for the last frame
