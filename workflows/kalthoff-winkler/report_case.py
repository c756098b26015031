#!/usr/bin/python3
"""results.md of the Kalthoff-Winkler case from its outputs (nothing typed in).

usage: report_case.py --out OUT --runs RUN... [--specimen-runs RUN...] [--runs-3d RUN...]
         --results results.md --figures figures

Writes, for the case's plate (--runs), the experiment's specimen (--specimen-runs) and its 3-D
form (--runs-3d: the crack paths of the mid-thickness layer), the table of crack angles (each
notch's main crack against the notch direction), crack start time, largest tip speed and wall
time per run; the crack paths of every run with their straight-line fits
(figures/crack_paths.png, crack_paths_specimen.png, crack_paths_3d.png); and copies the damage
pictures that mppm-postprocess --figures rendered for the runs.
"""
import argparse
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import kw_case  # noqa: E402
from mppm_outputs import copy_file, save_figure, write_text  # noqa: E402  (kw_case puts tools/ on the path)


def crack_frame(out, run, cracks):
    """The snapshot the angles were measured on: their `measured_at_s` (the latest of the tips),
    else the last one."""
    series = kw_case.frames(out, run)
    when = max((c.get("measured_at_s", series[-1][0]) for c in cracks.values()), default=series[-1][0])
    return min(series, key=lambda frame: abs(frame[0] - when))


def plot_crack_paths(out, runs, summaries, target):
    import meshio  # Debian python3-meshio, under /usr/bin/python3
    frames = {}
    for run in runs:
        time, path = crack_frame(out, run, kw_case.main_cracks(summaries[run]))
        frames[run] = (time, meshio.read(path))
    low, high = frames[runs[0]][1].points.min(axis=0) * 1e3, frames[runs[0]][1].points.max(axis=0) * 1e3
    wide = high[0] - low[0] > high[1] - low[1]
    width, height = (4.2, 3.4) if wide else (2.6, 4.6)  # one panel, inches
    fig, axes = plt.subplots(1, len(runs), figsize=(width * len(runs), height), squeeze=False)
    for ax, run in zip(axes[0], runs):
        s = summaries[run]
        time, mesh = frames[run]
        threshold = s.get("crack_damage_threshold", 0.35)
        layer = s.get("crack_angle_layer_z_m")  # 3-D: the mid-thickness layer the angles are measured on
        in_view = (lambda p: True) if layer is None else (lambda p: abs(p[2] - layer) < 0.25 * s["spacing_m"])
        body = [(p[0] * 1e3, p[1] * 1e3) for p, r, d in  # reference positions, as the series holds them
                zip(mesh.points, mesh.point_data["region"], mesh.point_data["damage"])
                if r == 0 and d >= threshold and in_view(p)]
        ax.scatter([p[0] for p in body], [p[1] for p in body], s=1, color="0.55", label=f"damage >= {threshold:g}")
        for entry in s.get("crack_angles") or []:
            tip, point, direction = entry["tip_m"], entry["fit_point_m"], entry["fit_direction"]
            offset = sum((t - p) * d for t, p, d in zip(tip, point, direction))
            ends = [[(p + (offset + r) * d) * 1e3 for p, d in zip(point, direction)]
                    for r in (entry["range_from_m"], entry["range_to_m"])]
            ax.plot([e[0] for e in ends], [e[1] for e in ends], color="C3", lw=1.6)
            ax.annotate(f"{entry['signed_angle_deg']:+.1f}°", ends[1][:2], fontsize=8, color="C3")
        ax.set_title(f"{run} (t = {time * 1e6:.3g} us)", fontsize=9)
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
    axes[0][0].set_ylabel("y [mm]")
    fig.tight_layout()
    save_figure(fig, target, dpi=110)


def table_row(out, run, s, info, energy):
    cracks = kw_case.main_cracks(s)
    every = kw_case.cracks_by_tip(s)
    fronts = {side: kw_case.front_metrics(kw_case.crack_front(out, run, c, s["spacing_m"], s["horizon_m"]),
                                          s["spacing_m"]) for side, c in cracks.items()}

    def per_side(text):
        return " / ".join(text(side) for side in ("upper", "lower"))

    def angle(side):
        c = cracks.get(side)
        inward = [e for e in every[side] if not kw_case.outward(e, s)]
        return (("-" if c is None else f"**{c['signed_angle_deg']:+.1f}**")
                + "".join(f" ({e['signed_angle_deg']:+.1f})" for e in inward))

    def start(side):
        t = fronts.get(side, (None, None))[0]
        return "-" if t is None else f"{t * 1e6:.3g}"

    def speed(side):
        v = fronts.get(side, (None, None))[1]
        return "-" if v is None else f"{v:.0f}"
    when = max((c.get("measured_at_s", s["last_time_s"]) for c in cracks.values()), default=None)
    balance = max(abs(float(r["balance_error"])) for r in energy)
    return (f"| {run} | {kw_case.model(s)} | {kw_case.spacing_mm(s):g} | {info['points']} | {info['steps']} | "
            f"{per_side(angle)} | {'-' if when is None else f'{when * 1e6:.3g}'} | {per_side(start)} | "
            f"{per_side(speed)} | {kw_case.rayleigh_speed(s['material']):.0f} | {balance:.2g} | "
            f"{s['detached_points']} | {info['threads']} | {info['wall_seconds']:.1f} |")


TABLE_HEAD = ["| run | model | dx [mm] | points | steps | crack angle, upper / lower [deg] | measured at [us] | "
              "crack start [us] | largest tip speed [m/s] | Rayleigh speed [m/s] | max balance error | "
              "detached points | threads | wall time [s] |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]


def ring_text(run_summary):
    entry = (run_summary.get("crack_angles") or [{}])[0]
    if "range_from_m" not in entry:
        return "(no crack measured)"
    return f"between {entry['range_from_m'] * 1e3:.3g} and {entry['range_to_m'] * 1e3:.3g} mm"


def plate_section(args, runs, figure_name):
    """The table and the crack-path figure of one plate's runs, as lines of results.md."""
    summaries = {r: kw_case.summary(args.out, r) for r in runs}
    plot_crack_paths(args.out, runs, summaries, os.path.join(args.figures, figure_name))
    lines = [f"Crack angles measured on the crack path {ring_text(summaries[runs[0]])} from the notch tip.", ""]
    lines += TABLE_HEAD
    lines += [table_row(args.out, run, summaries[run], kw_case.run_info(args.out, run), kw_case.energy_rows(args.out, run))
              for run in runs]
    return lines + ["", f"![crack paths](figures/{figure_name})", ""]


def damage_pictures(args, runs):
    """Copies each run's damage pictures to the figures folder; their lines of results.md."""
    lines = []
    for run in runs:
        pictures = sorted(glob.glob(os.path.join(args.out, run, "post", "figures", "damage_*.png")))
        if not pictures:
            continue
        lines += [f"## Damage on the deformed plate: {run}", ""]
        for p in pictures:
            name = f"{run}_{os.path.basename(p)}"
            copy_file(p, os.path.join(args.figures, name))
            lines.append(f"![{name}](figures/{name})")
        lines.append("")
    return lines


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--runs", nargs="+", required=True)
    ap.add_argument("--specimen-runs", nargs="*", default=[])
    ap.add_argument("--runs-3d", nargs="*", default=[])
    ap.add_argument("--results", required=True)
    ap.add_argument("--figures", required=True)
    args = ap.parse_args()
    os.makedirs(args.figures, exist_ok=True)
    lines = ["# Kalthoff-Winkler (workflows/kalthoff-winkler/README.md): results", "",
             "Written by `make report` from the run outputs under `out/` (nothing typed in). Crack angles: "
             "each notch's main crack (the fit through the most points) against the notch direction, "
             "counter-clockwise positive (postprocess/README.md, crack angle).", "",
             "In bold the crack toward the unstruck side (the experiment's crack), in brackets damage the tip "
             "sheds toward the struck block, where it is sheared off. "
             "Crack start and largest tip speed per notch (upper / lower), from the run's crack-arrival table: "
             "the arrivals within two horizons of the fitted line, the start when one lies more than 2 dx "
             "along it, the speed over advances of at least 3 dx (kw_case.py). Wall times on 2 cores with "
             "`make -j2` (two runs at a time, one thread each), on the machine that ran `make`.", "",
             "## The case's plate (200 mm along the notches, 100 mm along the struck edge)", ""]
    lines += plate_section(args, args.runs, "crack_paths.png")
    if args.specimen_runs:
        lines += ["## The experiment's specimen (100 mm along the notches, 200 mm along the struck edge)", ""]
        lines += plate_section(args, args.specimen_runs, "crack_paths_specimen.png")
    if args.runs_3d:
        lines += ["## The 3-D form (the experiment's specimen through its 9 mm thickness, to 50 us)", "",
                  "Crack angles and the crack paths drawn on the mid-thickness layer (postprocess/README.md, crack "
                  "angle); crack start and tip speed from the crack-arrival table of every layer.", ""]
        lines += plate_section(args, args.runs_3d, "crack_paths_3d.png")
    for stale in glob.glob(os.path.join(args.figures, "*_damage_*.png")):  # an earlier report's pictures
        os.remove(stale)
    lines += damage_pictures(args, args.runs + args.specimen_runs + args.runs_3d)
    write_text(args.results, "\n".join(lines))
    print(f"report: {os.path.abspath(args.results)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
