#!/usr/bin/python3
"""The accuracy-cost report from the study's CSV: a figure (error against wall time, log axes,
one series per swept parameter, the Pareto front marked) and results.md. Every number in
results.md is computed here from the CSV.

usage: report.py accuracy_cost.csv accuracy_cost.png results.md
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import study  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import save_figure, write_text  # noqa: E402

TARGETS = (0.01, 0.05, 0.10)
SWEEP_PARAMETER = {"spacing": "resolution", "horizon_factor": "horizon_factor", "safety": "safety",
                   "stabilization": "stabilization"}


def series_name(r):
    return r["sweep"] + (f", {r['threads']} threads" if r["threads"] > 1 else "")


def pareto_front(rows):
    """Rows not beaten in both wall time and error, fastest first."""
    front, best = [], math.inf
    for r in sorted(rows, key=lambda r: (r["wall_seconds"], r["error"])):
        if r["error"] < best:
            front.append(r)
            best = r["error"]
    return front


def panels(rows):
    keys = []
    for r in rows:
        if (r["problem"], r["dimension"]) not in keys:
            keys.append((r["problem"], r["dimension"]))
    return keys


def write_figure(rows, path):
    keys = panels(rows)
    columns = min(3, len(keys))
    lines = math.ceil(len(keys) / columns)
    figure, axes = plt.subplots(lines, columns, figsize=(5.2 * columns, 4.2 * lines), squeeze=False)
    # One style per series in every panel; each series joined in the order of its parameter.
    markers = "osD^v<>p"
    all_names = sorted({series_name(r) for r in rows})
    style = {name: (f"C{index}", markers[index % len(markers)]) for index, name in enumerate(all_names)}
    for ax, (problem, dimension) in zip(axes.flat, keys):
        panel = [r for r in rows if (r["problem"], r["dimension"]) == (problem, dimension) and r["error"] > 0]
        for name in all_names:
            series = [r for r in panel if series_name(r) == name]
            if not series:
                continue
            series.sort(key=lambda r: r[SWEEP_PARAMETER.get(r["sweep"], "resolution")])
            color, marker = style[name]
            ax.plot([r["wall_seconds"] for r in series], [r["error"] for r in series], color=color, marker=marker,
                    linestyle="-", linewidth=0.8, markersize=5, label=name)
        front = pareto_front(panel)
        ax.step([r["wall_seconds"] for r in front], [r["error"] for r in front], where="post", color="black",
                linewidth=1.6, alpha=0.6, label="Pareto front")
        ax.scatter([r["wall_seconds"] for r in front], [r["error"] for r in front], s=90, facecolors="none",
                   edgecolors="black", linewidths=1.4, zorder=5)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(study.label(problem, dimension))
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("relative error |measured / analytic - 1|")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(keys):]:
        ax.axis("off")
    figure.suptitle("mppm accuracy against cost (one process per run)")
    figure.tight_layout()
    save_figure(figure, path, dpi=110)


def section_head(title, text):
    """A section's title and its opening paragraph."""
    return [f"## {title}\n", text]


def table_head(*columns):
    """The header row and rule of a Markdown table."""
    return ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]


def fmt(value, digits=3):
    return f"{value:.{digits}g}"


def percent(value):
    return f"{100 * value:.3g} %"


def settings(r):
    unit = "rows" if r["problem"] in ("layer_shear", "crack_energy", "terzaghi") else "points/wavelength"
    text = f"{r['resolution']} {unit} (dx = {fmt(r['spacing_m'] * 1e3)} mm), m = {fmt(r['horizon_factor'])}"
    if r["problem"] != "layer_shear":
        text += f", safety {fmt(r['safety'])}"
    return text + f", G_s = {fmt(r['stabilization'])}, {r['threads']} thread(s)"


def convergence_section(rows, out):
    out += section_head("Convergence with the spacing at a fixed horizon factor",
                        "Least-squares slope of log error against log dx over the spacing sweep (1 thread; the runs at 2 "
                        "threads give the same errors). Expected rates: see README.md (waves: nonlocal dispersion "
                        "O((k delta)^2) and central differences O((W dt)^2) with dt proportional to dx; cut-off: exact in "
                        "space, central differences only; layer: faces smeared over a horizon, O(delta / h)).\n")
    out += table_head("problem", "horizon factor", "resolution", "errors", "observed rate", "expected rate")
    groups = study.spacing_groups(rows)
    for (problem, dimension, threads), group in sorted(groups.items()):
        if threads != 1 or len(group) < 2 or problem == "terzaghi":  # its own section (absolute errors)
            continue
        rate = study.log_slope(group, "spacing_m", "error")
        out.append(f"| {study.label(problem, dimension)} | {fmt(group[0]['horizon_factor'])} | "
                   f"{', '.join(str(r['resolution']) for r in group)} | "
                   f"{', '.join(percent(r['error']) for r in group)} | {rate:.2f} | "
                   f"{study.EXPECTED_RATE[problem]:.0f} |")
    cut = groups.get(("cutoff_frequency", 2, 1), [])
    if cut:
        out.append("\nThe cut-off error is the central-difference error alone: the scheme's frequency "
                   "(2 / dt) asin(W dt / 2) at the run's time step predicts it.\n")
        out += table_head("resolution", "time step [us]", "W dt", "predicted error", "measured error")
        for r in cut:
            wdt = r["analytic"] * r["time_step_s"]
            predicted = 2 / wdt * math.asin(wdt / 2) - 1
            out.append(f"| {r['resolution']} | {fmt(r['time_step_s'] * 1e6)} | {fmt(wdt)} | {percent(predicted)} | "
                       f"{percent(r['signed_error'])} |")
    out.append("")


def local_rates(group, key):
    """log2 of the error ratio between successive levels (the spacing halves between them)."""
    return [math.log(a[key] / b[key]) / math.log(b["resolution"] / a["resolution"]) for a, b in zip(group, group[1:])]


def terzaghi_section(rows, out):
    group = study.spacing_groups(rows).get(("terzaghi", 2, 1), [])
    if len(group) < 2:
        return
    out += section_head("Terzaghi consolidation",
                        "The 80 mm column of the pore-fluid test (periodic across, loaded and drained on top, fixed "
                        "impermeable base) at 1 thread, errors against Terzaghi's series over T_v = 0.1, 0.15, ..., 1: "
                        "the degree of consolidation from the settlement, max |U - U_series| (absolute: U is a fraction), "
                        "and the base pressure, max |p_base / p0 - series|. The drained layer acts as a face a = "
                        f"{study.TERZAGHI_FACE_OFFSET} dx beyond the body's top, which lowers U by about a / H at T_v = "
                        "0.1 (first order in dx); what is left (U error - a / H) is the quasi-static run's lag (the load "
                        "ramp over 0.002 t_c and the damping, fixed fractions of t_c at every spacing) on the finer "
                        "columns: a floor that lowers the observed rate as the column is refined (README.md). Costs are "
                        "counts (the wall times are in the figure).\n")
    out += table_head("rows", "dx [mm]", "points", "bonds", "steps", "bond updates", "U error", "a / H",
                      "U error - a / H", "base-pressure error")
    for r in group:
        offset = study.TERZAGHI_FACE_OFFSET / r["resolution"]
        out.append(f"| {r['resolution']} | {fmt(r['spacing_m'] * 1e3)} | {r['points']} | {r['bonds']} | {r['steps']} | "
                   f"{fmt(r['bond_updates'])} | {r['error']:.4f} | {offset:.4f} | {r['error'] - offset:+.4f} | "
                   f"{r['second_error']:.4f} |")
    levels = ", ".join(f"{a['resolution']}->{b['resolution']}" for a, b in zip(group, group[1:]))
    out.append("\nObserved rates (least squares of log error against log dx over every level; between successive "
               f"levels {levels}); expected {study.EXPECTED_RATE['terzaghi']:.0f} above the floor:\n")
    out += table_head("error", "observed rate", "between levels")
    for key, name in (("error", "degree of consolidation U"), ("second_error", "base pressure p / p0")):
        rate = study.log_slope(group, "spacing_m", key)
        out.append(f"| {name} | {rate:.2f} | {', '.join(f'{x:.2f}' for x in local_rates(group, key))} |")
    exponent = -study.log_slope(group, "spacing_m", "bond_updates")
    out.append(f"\nBond updates ~ dx^-{exponent:.2f} (expected {study.cost_exponent('terzaghi', 2):.0f}: the column is "
               "8 points across, its steps grow like its rows at a fixed consolidation time; the 6 layer rows weigh "
               "on the coarsest columns).")
    finest = group[-1]
    if finest["resolution"] >= study.TERZAGHI_TEST_ROWS:
        out.append(f"At {finest['resolution']} rows: U error {finest['error']:.4f} (the test's tolerance "
                   f"{study.TERZAGHI_TOLERANCE['error']}), base-pressure error {finest['second_error']:.4f} (tolerance "
                   f"{study.TERZAGHI_TOLERANCE['second_error']}).")
    out.append("")


def cost_section(rows, out):
    out += section_head("Cost of a 2x finer lattice",
                        "P wave, whole d-dimensional lattice refined (half a wavelength across the wave, so the points grow "
                        "like dx^-d). Expected: points x 2^d, time steps x 2 (the critical step is proportional to dx at a "
                        "fixed horizon factor), bonds per point unchanged: cost x 2^(d+1) = 8 in 2-D, 16 in 3-D. Wall time is "
                        "the critical-step estimate plus the time integration (the periodic family search of the test "
                        "lattices is left out: mppm-solve uses cell lists).\n")
    out += table_head("lattice", "threads", "resolution", "points x", "steps x", "bond updates x", "wall time x",
                      "expected x")
    fits = []
    groups = study.spacing_groups(rows)
    for (problem, dimension, threads), group in sorted(groups.items()):
        if problem != "p_wave":
            continue
        by_resolution = {r["resolution"]: r for r in group}
        for r in group:
            finer = by_resolution.get(2 * r["resolution"])
            if not finer:
                continue
            out.append(f"| {dimension}-D | {threads} | {r['resolution']} -> {finer['resolution']} | "
                       f"{finer['points'] / r['points']:.2f} | {finer['steps'] / r['steps']:.2f} | "
                       f"{finer['bond_updates'] / r['bond_updates']:.2f} | "
                       f"{finer['wall_seconds'] / r['wall_seconds']:.2f} | {2 ** (dimension + 1)} |")
        if len(group) >= 2:
            fits.append((dimension, threads, -study.log_slope(group, "spacing_m", "bond_updates"),
                         -study.log_slope(group, "spacing_m", "wall_seconds"), group))
    out.append("\nFitted over every level of the sweep (least squares in log-log):\n")
    out += table_head("lattice", "threads", "resolutions", "bond updates ~ dx^-p", "wall time ~ dx^-p",
                      "expected p = d + 1", "2x finer costs (wall, from the fit)")
    for dimension, threads, p_updates, p_wall, group in fits:
        out.append(f"| {dimension}-D | {threads} | {', '.join(str(r['resolution']) for r in group)} | {p_updates:.2f} | "
                   f"{p_wall:.2f} | {dimension + 1} | {2 ** p_wall:.1f}x |")
    speedups = []
    for (problem, dimension, threads), group in sorted(groups.items()):
        if threads == 2 and (problem, dimension, 1) in groups:
            serial = {r["resolution"]: r for r in groups[(problem, dimension, 1)]}
            finest = group[-1]
            if finest["resolution"] in serial:
                speedups.append((problem, dimension, finest, serial[finest["resolution"]]))
    if speedups:
        out.append("\nTwo threads against one on the finest lattice of each spacing sweep (wall time ratio; "
                   "throughput in bond updates per second of the time integration):\n")
        out += table_head("problem", "resolution", "1 thread [s]", "2 threads [s]", "speed-up",
                          "M bond updates/s (1 / 2 threads)")
        for problem, dimension, two, one in speedups:
            out.append(f"| {study.label(problem, dimension)} | {two['resolution']} | {fmt(one['wall_seconds'])} | "
                       f"{fmt(two['wall_seconds'])} | {one['wall_seconds'] / two['wall_seconds']:.2f} | "
                       f"{one['bond_updates_per_second'] / 1e6:.1f} / {two['bond_updates_per_second'] / 1e6:.1f} |")
    out.append("")


def sweep_section(rows, out):
    out.append("## The other parameters (80 points per wavelength, 40 layer rows, 1 thread)\n")
    for sweep, title in (("horizon_factor", "Horizon factor m (delta = m dx)"),
                         ("safety", "Time-step safety factor (dt = safety x critical step)"),
                         ("stabilization", "Stabilization coefficient G_s")):
        chosen = [r for r in study.ok(rows) if r["sweep"] == sweep]
        if not chosen:
            continue
        key = SWEEP_PARAMETER[sweep]
        values = sorted({r[key] for r in chosen})
        problems = []
        for r in chosen:
            if (r["problem"], r["dimension"]) not in problems:
                problems.append((r["problem"], r["dimension"]))
        out.append(f"### {title}\n")
        out += table_head("problem", *[fmt(v) for v in values])
        for problem, dimension in problems:
            cells = []
            for v in values:
                match = [r for r in chosen if (r["problem"], r["dimension"]) == (problem, dimension) and r[key] == v]
                cells.append(f"{percent(match[0]['signed_error'])}, {fmt(match[0]['wall_seconds'], 2)} s" if match else "")
            out.append("| " + " | ".join([study.label(problem, dimension)] + cells) + " |")
        if sweep == "horizon_factor":
            # what the horizon costs per step: the bonds per point of the lattice
            cells = []
            for v in values:
                match = [r for r in chosen if r[key] == v and r["problem"] == "p_wave"]
                cells.append(f"{match[0]['bonds'] / match[0]['points']:.1f}" if match else "")
            out.append("| " + " | ".join(["bonds per point (P-wave lattice)"] + cells) + " |")
        out.append("\n(signed error measured / analytic - 1, wall time)\n")


def recommendation_section(rows, out):
    out += section_head("Recommended settings for a target error",
                        "The cheapest run (wall time) of the whole study whose error is within the target, per problem; "
                        "its settings are the recommendation, its measured cost the price.\n")
    out += table_head("problem", "target", "settings", "error", "wall time [s]", "bond updates", "peak memory [MiB]")
    for problem, dimension in panels(study.ok(rows)):
        candidates = [r for r in study.ok(rows) if (r["problem"], r["dimension"]) == (problem, dimension)]
        for target in TARGETS:
            good = [r for r in candidates if r["error"] <= target]
            if not good:
                out.append(f"| {study.label(problem, dimension)} | {percent(target)} | none of the runs reached it | | | | |")
                continue
            best = min(good, key=lambda r: r["wall_seconds"])
            out.append(f"| {study.label(problem, dimension)} | {percent(target)} | {settings(best)} | "
                       f"{percent(best['error'])} | {fmt(best['wall_seconds'])} | {fmt(best['bond_updates'])} | "
                       f"{best['peak_memory_bytes'] / 2**20:.0f} |")
    out.append("")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    source, figure_path, markdown_path = sys.argv[1:]
    rows = study.load(source)
    good = study.ok(rows)
    if not good:
        sys.exit(f"report.py: {source}: no run with status ok")
    write_figure(good, figure_path)
    out = ["# Accuracy and cost: results\n",
           f"Generated by `make report` from `{os.path.basename(source)}` ({len(rows)} runs, "
           f"{len(good)} with an error); how the runs are made and what each error means: README.md. "
           "Figure: error against wall time, one series per swept parameter, Pareto front circled.\n",
           f"![error against wall time]({os.path.relpath(figure_path, os.path.dirname(os.path.abspath(markdown_path)))})\n"]
    loads = [r["load_average"] for r in good if r.get("load_average") is not None]
    if loads:
        out.append(f"Machine load (1-minute load average at the end of each run): {min(loads):.2f} to {max(loads):.2f} "
                   "(the runs record it). Wall times and the 2-thread speed-up "
                   "are only as clean as the machine was idle; bond updates are counts.\n")
    convergence_section(rows, out)
    terzaghi_section(rows, out)
    cost_section(rows, out)
    sweep_section(rows, out)
    recommendation_section(rows, out)
    write_text(markdown_path, "\n".join(out))


if __name__ == "__main__":
    main()
