#!/usr/bin/python3
"""results.md of the crack-branching case from its outputs (nothing typed in).

usage: report_case.py --out OUT --base base --rate-runs RUN... --results results.md --figures figures

Writes the timing table (t0, crack start, branching and end times, largest tip speed, wall
time) of every run, the loading curves (reaction of the top boundary against time) on one plot,
and copies the base run's damage and micro-rotation pictures (rendered by mppm-postprocess
--figures) next to results.md.
"""
import argparse
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import crack_case  # noqa: E402
from mppm_outputs import copy_file, save_figure, write_text  # noqa: E402  (crack_case puts tools/ on the path)


def us(value):
    return "-" if value is None else f"{value * 1e6:.4g}"


def event_resolution(summary):
    """The resolution of the crack event times [us] and where they come from: the time step with
    the solver's crack-arrival table (crack_path.csv), the snapshot interval without it."""
    resolution = summary.get("crack_metrics_resolution_s")
    if resolution is None:  # a summary written before the postprocessor said it
        if summary["snapshots"] < 2:
            return "-"
        resolution = (summary["last_time_s"] - summary["first_time_s"]) / (summary["snapshots"] - 1)
    source = summary.get("crack_metrics_source", "snapshots")
    return f"{resolution * 1e6:.3g} ({'table' if source == 'crack_path table' else source})"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--base", required=True)
    ap.add_argument("--rate-runs", nargs="+", required=True)
    ap.add_argument("--results", required=True)
    ap.add_argument("--figures", required=True)
    args = ap.parse_args()
    runs = [args.base] + args.rate_runs
    os.makedirs(args.figures, exist_ok=True)
    rows, curves = [], {}
    for run in runs:
        s = crack_case.summary(args.out, run)
        info = crack_case.run_info(args.out, run)
        energy = crack_case.energy_rows(args.out, run)
        ramp = s["boundary_conditions"][0]["history"][1][0]
        rows.append((run, s, info, ramp, max(abs(float(r["balance_error"])) for r in energy),
                     crack_case.rayleigh_speed(s["material"])))
        load = crack_case.load_rows(args.out, run)
        curves[run] = ([float(r["time_s"]) * 1e6 for r in load], [float(r["top_Fy_N"]) for r in load],
                       [float(r["top_uy_m"]) * 1e6 for r in load])

    fig, (ax_f, ax_u) = plt.subplots(1, 2, figsize=(11, 4))
    for run, (t, force, disp) in curves.items():
        label = f"{run} (t0 = {next(r[3] for r in rows if r[0] == run) * 1e6:.4g} us)"
        ax_f.plot(t, force, label=label)
        ax_u.plot(t, disp, label=label)
    ax_f.set_xlabel("time [us]")
    ax_f.set_ylabel("force on the top boundary [N]")
    ax_f.set_title("applied load (traction x area)")
    ax_u.set_xlabel("time [us]")
    ax_u.set_ylabel("mean displacement of the top boundary [um]")
    ax_u.set_title("response")
    for ax in (ax_f, ax_u):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    curve_png = os.path.join(args.figures, "loading_curves.png")
    save_figure(fig, curve_png, dpi=110)

    pictures = sorted(glob.glob(os.path.join(args.out, args.base, "post", "figures", "*.png")))
    copied = []
    for p in pictures:
        target = os.path.join(args.figures, "base_" + os.path.basename(p))
        copy_file(p, target)
        copied.append(os.path.basename(target))

    base = rows[0]
    width, height, nx, ny = crack_case.lattice(args.out, args.base)
    spacing, horizon = base[1]["spacing_m"], base[1]["horizon_m"]
    lines = ["# Crack branching (workflows/crack-branching/README.md): results", "",
             "Written by `make report` from the run outputs under `out/` (nothing typed in). "
             f"Plate {width * 1e3:.4g} x {height * 1e3:.4g} mm, {nx} x {ny} points (dx = {spacing * 1e3:g} mm), "
             f"horizon factor {horizon / spacing:.4g}, pre-crack from the left edge to the centre, traction "
             f"{crack_case.traction(args.out, args.base) / 1e6:.4g} MPa on top and bottom ramped over t0; see README.md "
             "for the set-up and the methods.", "",
             "| run | solid fraction | t0 [us] | crack start [us] | branching [us] | end [us] | end reason | "
             "largest tip speed [m/s] | Rayleigh speed [m/s] | crack length [mm] | max balance error | event time resolution [us] | steps | threads | wall time [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for run, s, info, ramp, balance, c_r in rows:
        speed = s.get("crack_tip_speed_max_m_per_s")
        length = s.get("crack_length_m")
        lines.append(f"| {run} | {s['material']['solid_fraction']:g} | {ramp * 1e6:.4g} | {us(s.get('crack_start_time_s'))} | "
                     f"{us(s.get('crack_branch_time_s'))} | {us(s.get('crack_end_time_s'))} | {s.get('crack_end_reason') or '-'} | "
                     f"{'-' if speed is None else f'{speed:.0f}'} | {c_r:.0f} | {'-' if length is None else f'{length * 1e3:.1f}'} | "
                     f"{balance:.2g} | {event_resolution(s)} | {info['steps']} | {info['threads']} | {info['wall_seconds']:.1f} |")
    lines += ["", f"Wall time of the base run: **{base[2]['wall_seconds']:.1f} s** with {base[2]['threads']} threads "
              f"({base[2]['steps']} steps, {base[2]['points']} points, {base[2]['bonds']} bonds), on the machine that ran "
              "`make`.", "",
              "## Loading curves", "", "![loading curves](figures/loading_curves.png)", ""]
    damage = [c for c in copied if "damage" in c]
    rotation = [c for c in copied if "rotation" in c]
    if damage:
        lines += [f"## Damage on the deformed plate (base run; crack path = damage >= "
                  f"{crack_case.crack_damage_threshold(base[1]):g})", ""]
        lines += [f"![{c}](figures/{c})" for c in damage] + [""]
    if rotation:
        lines += ["## Micro-rotation (base run)", ""]
        lines += [f"![{c}](figures/{c})" for c in rotation] + [""]
    write_text(args.results, "\n".join(lines))
    print(f"report: {os.path.abspath(args.results)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
