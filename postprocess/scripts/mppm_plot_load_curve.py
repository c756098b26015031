#!/usr/bin/python3
# Plots POST_DIR/load_curve.csv (written by mppm-postprocess) into a PNG: force against time
# and force against displacement, one curve per loaded boundary, axes in readable units.
# Usage: mppm_plot_load_curve.py LOAD_CURVE.csv OUTPUT.png [MAIN_BOUNDARY]
# Run by mppm-postprocess with /usr/bin/python3 (Debian python3-matplotlib).
import csv
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402


def scale_for(values, unit, prefixes):
    """Largest prefix that keeps the largest |value| >= 1 (e.g. s -> us, N -> kN)."""
    peak = max((abs(v) for v in values if v == v), default=0.0)
    for factor, prefix in prefixes:
        if peak >= factor:
            return factor, prefix + unit
    factor, prefix = prefixes[-1]
    return factor, prefix + unit


SMALL = [(1.0, ""), (1e-3, "m"), (1e-6, "u"), (1e-9, "n")]
LARGE = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "u")]


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: mppm_plot_load_curve.py LOAD_CURVE.csv OUTPUT.png [MAIN_BOUNDARY]")
    source, output = sys.argv[1], sys.argv[2]
    main_boundary = sys.argv[3] if len(sys.argv) > 3 else ""
    with open(source, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], [[float(v) for v in r] for r in rows[1:] if r]
    columns = list(zip(*data)) if data else [[] for _ in header]
    time = columns[0]
    boundaries = []
    for c in range(1, len(header), 2):
        u_name, f_name = header[c], header[c + 1]
        name = u_name.rsplit("_u", 1)[0]
        axis = u_name.rsplit("_u", 1)[1][0]
        boundaries.append((name, axis, columns[c], columns[c + 1]))

    figure, (by_time, by_displacement) = plt.subplots(1, 2, figsize=(12, 4.8))
    t_factor, t_unit = scale_for(time, "s", SMALL)
    all_forces = [v for b in boundaries for v in b[3]]
    all_displacements = [v for b in boundaries for v in b[2]]
    f_factor, f_unit = scale_for(all_forces, "N", LARGE)
    u_factor, u_unit = scale_for(all_displacements, "m", SMALL)
    t_unit = t_unit.replace("us", "\u00b5s")
    u_unit = u_unit.replace("um", "\u00b5m")
    for name, axis, u, force in boundaries:
        label = f"{name} ({axis})" + (" - main" if name == main_boundary else "")
        width = 2.0 if name == main_boundary else 1.2
        by_time.plot([t / t_factor for t in time], [v / f_factor for v in force], label=label, linewidth=width)
        by_displacement.plot([v / u_factor for v in u], [v / f_factor for v in force], label=label, linewidth=width)
    by_time.set_xlabel(f"time [{t_unit}]")
    by_time.set_ylabel(f"force along the loading axis [{f_unit}]")
    by_time.set_title("load against time")
    by_displacement.set_xlabel(f"boundary displacement along the loading axis [{u_unit}]")
    by_displacement.set_ylabel(f"force along the loading axis [{f_unit}]")
    by_displacement.set_title("load against displacement")
    for axes in (by_time, by_displacement):
        axes.grid(True, alpha=0.3)
        if boundaries:
            axes.legend(fontsize="small")
    if not boundaries:
        by_time.text(0.5, 0.5, "no loaded boundary", ha="center", transform=by_time.transAxes)
    figure.tight_layout()
    figure.savefig(output, dpi=120, format="png")


if __name__ == "__main__":
    main()
