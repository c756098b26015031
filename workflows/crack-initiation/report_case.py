#!/usr/bin/python3
"""results.md and figures/start_time.png of the crack-initiation case from its runs (nothing typed in).

usage: report_case.py --out OUT --runs RUN... [--same-spacing RUN...] [--same-horizon RUN...]
                      [--micropolar RUN...] --results results.md --figures figures

Per run (horizon, spacing, calibration): Freund's predicted times and the measured ones, all after the
wave's arrival at the crack plane, with the relative differences; the windows before a reflection can
reach the tip; the arrival check; the wall time. The figure shows the measured times against the
horizon with Freund's prediction. The horizon study's two series (the same spacing at three horizon
factors, the same horizon at three spacings) get a table each, and so do the micro-polar runs.
"""
import argparse
import math
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import initiation_rows as ir  # noqa: E402
from script_exit import run_main  # noqa: E402  (initiation_rows puts tools/ on the path)

CALIBRATIONS = ["lattice", "continuum", "dissipation"]
MEASURES = [  # (label, measured key, predicted key)
    ("first break", "first_break_s", "predicted_start_s"),
    ("advance 2 dx", "advance_2dx_s", "predicted_advance_2dx_s"),
    ("advance one horizon", "advance_horizon_s", "predicted_advance_horizon_s"),
]


def us(value, digits=4):
    return "not reached" if value is None else f"{value * 1e6:.{digits}g}"


def percent(value):
    return "-" if value is None else f"{value * 100:+.1f}"


def advance_time(r, advance):
    """Freund's time after the arrival at which the tip has moved `advance` (v = c_R (1 - t_c / t))."""
    tc, cr = r["predicted_start_s"], r["rayleigh_speed_m_per_s"]
    if advance <= 0:
        return tc
    lo, hi = tc, 2 * tc
    while cr * ((hi - tc) - tc * math.log(hi / tc)) < advance:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cr * ((mid - tc) - tc * math.log(mid / tc)) < advance else (lo, mid)
    return 0.5 * (lo + hi)


def figure(rows, path):
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    horizon_max = max(r["horizon_m"] for r in rows) * 1.15e3
    factor = rows[0]["horizon_factor"]
    grid = [horizon_max * k / 100 for k in range(101)]  # horizon [mm]
    ref = rows[0]
    lines = [
        [ref["predicted_start_s"] * 1e6 for _ in grid],
        [advance_time(ref, 2 * d / factor * 1e-3) * 1e6 for d in grid],
        [advance_time(ref, d * 1e-3) * 1e6 for d in grid],
    ]
    markers = {"lattice": "o", "continuum": "s", "dissipation": "^"}
    for ax, (label, key, _), line in zip(axes, MEASURES, lines):
        ax.plot(grid, line, "k-", label="Freund")
        for cal in CALIBRATIONS:
            pts = [(r["horizon_m"] * 1e3, r[key] * 1e6) for r in rows if r["calibration"] == cal and r[key] is not None]
            pts.sort()
            if pts:
                ax.plot(*zip(*pts), marker=markers[cal], linestyle="--", label=cal)
        ax.set_title(label)
        ax.set_xlabel("horizon [mm]")
        ax.set_xlim(0, horizon_max)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("time after the wave's arrival [us]")
    axes[0].legend()
    fig.suptitle(f"Crack start under a plane step wave against Freund (horizon factor {factor:g}, non-polar)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def advance_figure(out, rows, path):
    """The crack advance (broken crossing pairs ahead of the tip over those per unit length) against time,
    per calibration and level, with Freund's l(t) = c_R [(t - t_c) - t_c ln(t / t_c)]."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    ref = rows[0]
    tc, cr = ref["predicted_start_s"], ref["rayleigh_speed_m_per_s"]
    t_end = max(ir.window(r) for r in rows)
    grid = [tc + (t_end - tc) * k / 200 for k in range(201)]
    for ax, cal in zip(axes, CALIBRATIONS):
        ax.plot([0, tc * 1e6] + [t * 1e6 for t in grid],
                [0, 0] + [cr * ((t - tc) - tc * math.log(t / tc)) * 1e3 for t in grid], "k-", label="Freund")
        for r in rows:
            if r["calibration"] != cal:
                continue
            h = ir.history(out, r["run"])
            t = [0.0] + [x[0] * 1e6 for x in h]
            a = [0.0] + [x[1] * 1e3 for x in h]
            ax.step(t, a, where="post", label=f"horizon {r['horizon_m'] * 1e3:.3g} mm")
        ax.set_title(cal)
        ax.set_xlabel("time after the wave's arrival [us]")
        ax.set_xlim(0, t_end * 1e6)
        ax.set_ylim(0, 1.2 * max(r["horizon_m"] for r in rows) * 1e3)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("crack advance [mm]")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def table(rows):
    head = ("| horizon [mm] | dx [mm] | calibration | predicted start t_c [us] | first break [us] | diff % "
            "| predicted 2 dx [us] | advance 2 dx [us] | diff % | predicted horizon [us] | advance horizon [us] "
            "| diff % | window [us] | steps | wall time [s] |")
    out = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        cells = [f"{r['horizon_m'] * 1e3:.4g}", f"{r['spacing_m'] * 1e3:.3g}", r["calibration"]]
        for _, key, pred in MEASURES:
            cells.append(us(r[pred]))
            cells += [us(r[key]), percent(ir.difference(r[key], r[pred]))]
        flag = "" if all(r[k] is None or r[k] <= ir.window(r) for _, k, _ in MEASURES) else " (exceeded)"
        cells += [f"{ir.window(r) * 1e6:.4g}{flag}", f"{r['steps']:.0f}", f"{r['wall_s']:.1f}"]
        out.append("| " + " | ".join(cells) + " |")
    return out


def study_table(rows):
    """One series of the horizon study: each measure's time and its difference to Freund's."""
    out = ["| horizon [mm] | dx [mm] | horizon factor | calibration | first break [us] (diff %) "
           "| advance 2 dx [us] (diff %) | advance one horizon [us] (diff %) |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [f"{r['horizon_m'] * 1e3:.4g}", f"{r['spacing_m'] * 1e3:.3g}", f"{r['horizon_factor']:g}", r["calibration"]]
        cells += [f"{us(r[key])} ({percent(ir.difference(r[key], r[pred]))})" for _, key, pred in MEASURES]
        out.append("| " + " | ".join(cells) + " |")
    return out


def ordered_rows(out, runs):
    """The runs' rows by calibration, then from the largest horizon and spacing down."""
    return sorted((ir.row(out, run) for run in runs),
                  key=lambda r: (CALIBRATIONS.index(r["calibration"]), -r["horizon_m"], -r["spacing_m"]))


def study_section(out, same_spacing, same_horizon):
    if not same_spacing and not same_horizon:
        return []
    text = ["", "## The same spacing, and the same horizon", "",
            "The series above keeps the horizon factor and refines the lattice with the horizon. Two more series "
            "(README.md, \"The same spacing, and the same horizon\"): the horizon shrinks on one lattice, and the "
            "lattice is refined within one horizon. The dissipation calibration is measured only for horizon factors "
            "2.55-5.05, so these series use the other two.", ""]
    if same_spacing:
        text += ["### The same spacing: the horizon shrinks on one lattice", ""] + study_table(ordered_rows(out, same_spacing)) + [""]
    if same_horizon:
        text += ["### The same horizon: the lattice refined within it", ""] + study_table(ordered_rows(out, same_horizon)) + [""]
    return text


def micropolar_section(out, runs):
    if not runs:
        return []
    return ["", "## Micro-polar", "",
            "The nine runs with the crack-branching material's micro-rotations (characteristic length 2 mm, "
            "mu_c = mu / 3, bending modulus 56 kN), against the same classical prediction: the P wave that loads "
            "the crack is the classical one, the field at the tip is not (README.md, \"Micro-polar\").", ""
            ] + study_table(ordered_rows(out, runs)) + [""]


def arrival_table(rows):
    out = ["| dx [mm] | horizon factor | ramp [us] | computed arrival [us] | measured (centroid) [us] | difference [us] "
           "| 0.5 dx / c_p [us] |", "|---|---|---|---|---|---|---|"]
    seen = set()
    for r in sorted(rows, key=lambda r: (-r["spacing_m"], r["horizon_factor"])):
        if (r["spacing_m"], r["horizon_factor"]) in seen:
            continue
        seen.add((r["spacing_m"], r["horizon_factor"]))
        out.append(f"| {r['spacing_m'] * 1e3:.3g} | {r['horizon_factor']:g} | {r['ramp_s'] * 1e6:.4g} | "
                   f"{r['predicted_arrival_s'] * 1e6:.4g} | "
                   f"{r['measured_arrival_s'] * 1e6:.4g} | {(r['measured_arrival_s'] - r['predicted_arrival_s']) * 1e6:+.3f} | "
                   f"{0.5 * r['spacing_m'] / r['wave_speed_m_per_s'] * 1e6:.3f} |")
    return out


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--runs", nargs="+", required=True)
    ap.add_argument("--same-spacing", nargs="*", default=[])
    ap.add_argument("--same-horizon", nargs="*", default=[])
    ap.add_argument("--micropolar", nargs="*", default=[])
    ap.add_argument("--results", required=True)
    ap.add_argument("--figures", required=True)
    args = ap.parse_args(argv)
    rows = [ir.row(args.out, run) for run in args.runs]
    rows.sort(key=lambda r: (-r["spacing_m"], CALIBRATIONS.index(r["calibration"])))
    os.makedirs(args.figures, exist_ok=True)
    figure(rows, os.path.join(args.figures, "start_time.png"))
    advance_figure(args.out, rows, os.path.join(args.figures, "advance.png"))
    r = rows[0]
    text = [
        "# Crack initiation under a stress wave (workflows/crack-initiation/README.md): results",
        "",
        "Written by `make report` from the runs under `out/` (nothing typed in). Plane-strain plate "
        "160 x 56 mm, pre-crack 80 mm from the left edge along the mid-plane, traction "
        f"{r['traction_Pa'] / 1e6:g} MPa on the top and bottom edges (so sigma = {2 * r['traction_Pa'] / 1e6:g} MPa on the "
        "crack plane), rising over 2 dx / c_p; crack-branching material, non-polar, G_cr = 160 N/m, horizon factor "
        f"{r['horizon_factor']:g}, G_s = 0.1. c_p = {r['wave_speed_m_per_s']:.1f} m/s, c_R = {r['rayleigh_speed_m_per_s']:.1f} m/s, "
        f"K_c = {r['critical_intensity_Pa_sqrtm'] / 1e6:.4g} MPa sqrt(m). Every time is after the wave's arrival at the "
        "crack plane (the front's centroid, computed: H / (2 c_p) + half the ramp). Freund: the start t_c = "
        "pi (1 - nu)^2 K_c^2 / (4 sigma^2 c_p (1 - 2 nu)); the advances from his equation of motion "
        "v = c_R (1 - t_c / t). Measured: the first step in which a bond across the crack plane ahead of the tip broke, "
        "and the first step at which the broken crossing bonds ahead of the tip equal those of 2 dx and of one horizon of "
        "crack (README.md, \"What is measured\"). Window: the first time a reflection can reach the tip; a measured time "
        "beyond it is marked. Wall time: the time integration (model build excluded), on a busy shared 2-core machine "
        "(one thread per run, two runs at a time): indicative only.",
        "",
    ]
    text += table(rows)
    text += study_section(args.out, args.same_spacing, args.same_horizon)
    text += micropolar_section(args.out, args.micropolar)
    text += ["", "## Arrival of the wave at the crack plane", "",
             "The centroid of the front in the mid-plane strain half-way between the tip and the right edge (its "
             "equal-area arrival against the uncracked strain 2 sigma0 / (lambda + 2 mu)) against the computed arrival; "
             "the front's half-value point lags behind the centroid by the lattice's dispersion.", ""]
    text += arrival_table(rows + [ir.row(args.out, run) for run in args.same_spacing + args.same_horizon])
    text += ["", "## Start time against the horizon", "", "![start time against the horizon](figures/start_time.png)", "",
             "## Crack advance against time", "",
             "The advance is the broken crossing pairs ahead of the tip over the lattice's crossing pairs per unit "
             "length; Freund's line is his equation of motion from t_c. Each run stops once the crack has advanced "
             "1.05 horizons.", "", "![crack advance against time](figures/advance.png)", ""]
    with open(args.results, "w") as f:
        f.write("\n".join(text))
    print(f"wrote {args.results}, {args.figures}/start_time.png and {args.figures}/advance.png")
    return 0


if __name__ == "__main__":
    run_main(main)
