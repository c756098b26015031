"""Contour pictures of the shear-band cases (workflows/shear-band, workflows/saturated-shear-band):
fields of the last snapshot drawn on the deformed body, one column per run, with the
postprocessor's band centre lines. Headless matplotlib (Agg, chosen by the caller)."""
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np

from mppm_outputs import save_figure


# The rows of plot_contours: (field of a Snapshot, colour map, label, symmetric colour range).
STRAIN_AND_ROTATION = [("plastic_shear_strain", "viridis", "plastic shear strain [-]", False),
                       ("rotation", "RdBu_r", "micro-rotation [rad]", True)]


def plot_contours(runs, path, title, rows=STRAIN_AND_ROTATION):
    """One column per run, one row per field of `rows`, on the deformed body of the last snapshot
    (run: name, m["bands"] (band_measures.Band), last_snapshot() (shear_band_fields.Snapshot))."""
    fig, axes = plt.subplots(len(rows), len(runs), figsize=(2.7 * len(runs) + 0.5, 4.6 * len(rows)), squeeze=False)
    for col, run in enumerate(runs):
        snap = run.last_snapshot()
        body = snap.body
        xy = snap.deformed[body] * 1e3
        # Triangulate the reference lattice (regular) and draw it on the deformed positions, so
        # no triangle bridges points that are not neighbours.
        triangles = mtri.Triangulation(*(snap.reference[body] * 1e3).T).triangles
        tri = mtri.Triangulation(xy[:, 0], xy[:, 1], triangles)
        for row, (field, cmap, label, symmetric) in enumerate(rows):
            values = getattr(snap, field)[body]
            ax = axes[row][col]
            top = float(np.max(np.abs(values))) or 1.0
            levels = np.linspace(-top, top, 21) if symmetric else np.linspace(0.0, top, 21)
            cs = ax.tricontourf(tri, values, levels=levels, cmap=cmap)
            for band in run.m["bands"]:  # the postprocessor's centre lines, on the reference frame
                along = np.array([-0.25, 0.25])
                line = band.centre[None, :] + along[:, None] * band.tangent[None, :]
                ax.plot(line[:, 0] * 1e3, line[:, 1] * 1e3, color="k" if symmetric else "w", lw=0.7, ls="--")
            ax.set_xlim(xy[:, 0].min() - 2, xy[:, 0].max() + 2)
            ax.set_ylim(xy[:, 1].min() - 2, xy[:, 1].max() + 2)
            ax.set_aspect("equal")
            ax.set_title(f"{run.name}\n{label}", fontsize=8)
            ax.tick_params(labelsize=7)
            fig.colorbar(cs, ax=ax, shrink=0.8).ax.tick_params(labelsize=7)
        axes[-1][col].set_xlabel("x [mm]", fontsize=8)
    for row in range(len(rows)):
        axes[row][0].set_ylabel("y [mm], deformed (true scale)", fontsize=8)
    fig.suptitle(f"{title}: last snapshot (t = {runs[0].last_snapshot().time:g} s), body points; dashed: the "
                 "postprocessor's band centre lines", fontsize=9)
    fig.tight_layout()
    save_figure(fig, path, 100)
