#!/usr/bin/python3
"""Writes results.md and its figures for the saturated shear-band case from the outputs of its runs.

Usage: report_case.py --out OUT --runs R... --results results.md --figures figures/

Every number in results.md is read from the run folders (post/summary.json,
post/load_curve.csv, the snapshots, run/energy.csv, run/run_info.json, the Makefile's timing/
files) or computed from them (saturated_measures.py, with case 1's band measures); the
consolidation times are the formula H^2 / c_v of the resolved material, labelled as such. The
checks are those of check_case.py. Figures: PNG files drawn headless with matplotlib (Agg), the
contour pictures with the shared band_contours.plot_contours of case 1. Exit 2 if an output is
missing or unreadable.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import check_case  # noqa: E402
from case_checks import check_lines  # noqa: E402  (tools/)
from band_contours import STRAIN_AND_ROTATION, plot_contours  # noqa: E402  (../tools)
from mppm_outputs import RunOutputError, save_figure, write_text  # noqa: E402
from shear_band_fields import Snapshot  # noqa: E402

PRESSURE_ROW = [("pore_pressure", "RdBu_r", "pore pressure [Pa]", True)]


class Run:
    """What plot_contours needs (name, m, last_snapshot) over the measures of one run."""

    def __init__(self, m, out):
        self.name, self.m = m["name"], m
        self.post = os.path.join(out, m["name"], "post")
        self.snapshot = None

    def last_snapshot(self):
        if self.snapshot is None:
            self.snapshot = Snapshot(self.post, self.m["summary"]["horizon_m"])
        return self.snapshot


def fmt(value, spec, missing="none"):
    return missing if value is None else format(value, spec)


def consolidation_time(m):
    """H^2 / c_v [s] over half the specimen's height (drained top and bottom), with
    c_v = (k / mu_f) / (1 / M + b^2 / (lambda + 2 mu)), the one-dimensional consolidation
    coefficient of the resolved material (docs/theory.md section 12)."""
    material = m["summary"]["material"]
    fluid = material["pore_fluid"]
    constrained = float(material["lambda"]) + 2.0 * float(material["mu"])
    storage = 1.0 / float(fluid["biot_modulus"]) + float(fluid["biot_coefficient"]) ** 2 / constrained
    c_v = float(fluid["permeability"]) / float(fluid["fluid_viscosity"]) / storage
    snap = Snapshot(os.path.join(m["folder"], "post"), m["summary"]["horizon_m"])
    body = snap.reference[snap.body]
    height = body[:, 1].max() - body[:, 1].min() + m["summary"]["spacing_m"]
    return (0.5 * height) ** 2 / c_v


def run_table(results, runs):
    head = ("| run | dilatancy [deg] | k [m^2] | H^2/c_v / loading time | peak load [N] | travel at peak [mm] | "
            "band angle [deg] | band width [mm] | band onset: travel [mm] | band pore pressure [MPa] | "
            "outside the bands [MPa] | lowest / highest pore pressure [MPa] | max abs fluid balance / pore volume | "
            "max abs energy balance | solver wall [s] (threads) | load average during the run |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for name in runs:
        m = results[name]
        s = m["summary"]
        pressure = fmt(m["band_pressure_Pa"] and m["band_pressure_Pa"] / 1e6, "+.3f", "n/a")
        if m["pressure_bands"] == "reference":
            pressure += " (dry run's bands)"
        extremes = ("n/a" if m["dry"] else
                    f"{s['pore_pressure_min_Pa'] / 1e6:+.3f} / {s['pore_pressure_peak_Pa'] / 1e6:+.3f}")
        ratio = "dry" if m["dry"] else f"{consolidation_time(m) / m['platen_stop_s']:.2g}"
        balance = "n/a" if m["dry"] else f"{m['worst_fluid_balance_m3'] / m['pore_volume_m3']:.1e}"
        permeability = "dry" if m["dry"] else f"{m['permeability']:g}"
        # A peak at the platens' stop is only the load there: the curve was still rising.
        at_stop = s.get("time_at_peak_s") is not None and s["time_at_peak_s"] >= m["platen_stop_s"] - 1e-3
        rising = " (still rising at the stop)" if at_stop else ""
        lines.append(
            f"| {name} | {m['psi']:g} | {permeability} | {ratio} | "
            f"{s['peak_load_N']:.0f}{rising} | {fmt(s.get('displacement_at_peak_m') and 1e3 * s['displacement_at_peak_m'], '.2f')} | "
            f"{fmt(s.get('shear_band_angle_deg'), '.1f')} | {fmt(s.get('shear_band_width_m') and 1e3 * s['shear_band_width_m'], '.1f')} | "
            f"{fmt(m['onset_travel_m'] and 1e3 * m['onset_travel_m'], '.2f', 'no band')} | {pressure} | "
            f"{fmt(m['outside_pressure_Pa'] and m['outside_pressure_Pa'] / 1e6, '+.3f', 'n/a')} | {extremes} | {balance} | "
            f"{m['worst_balance_error']:.1e} | {m['info']['wall_seconds']:.0f} ({m['info']['threads']}) | "
            f"{fmt(m['load_average'], '.1f', 'not sampled')} |")
    return lines


def case_wall_seconds(out):
    """From the first stage's start to the last one's end (timing/<stage>.txt: name, start, end, ...)."""
    starts, ends = [], []
    timing = os.path.join(out, "timing")
    for name in os.listdir(timing) if os.path.isdir(timing) else []:
        if name.endswith(".txt"):
            with open(os.path.join(timing, name)) as f:
                fields = f.read().split()
            if len(fields) >= 3:
                starts.append(float(fields[1]))
                ends.append(float(fields[2]))
    return max(ends) - min(starts) if starts else None


def wall_time_statement(results, out):
    """What the wall times are worth: `make -j2` runs two runs at a time with one thread each, so a
    load average up to about 2.5 is the case itself on the 2 cores (an idle machine otherwise);
    above that something else ran beside it. A run whose load was not sampled is not vouched for."""
    loads = [m["load_average"] for m in results.values()]
    if any(load is None for load in loads) or max(loads) > 2.5:
        return ("**Wall times were measured on a shared 2-core machine** (something else ran beside some runs, or "
                "their load was not sampled; `make -j2` ran two runs at a time with `--threads 1` each); the last "
                "column is the mean 1-minute load average sampled during each run's solve. They are not idle-machine "
                "figures.")
    whole = case_wall_seconds(out)
    total = f" The whole case, points to postprocessing, took {whole / 60:.1f} min." if whole else ""
    return (f"Wall times on the 2-core machine running only this case (`make -j2`: two runs at a time with "
            f"`--threads 1` each, so a load average of about 2 is the case itself; largest {max(loads):.1f}); the last "
            f"column is the mean 1-minute load average sampled during each run's solve.{total}")


def plot_load_curves(results, runs, path):
    dilatancies = sorted({results[n]["psi"] for n in runs}, reverse=True)
    fig, axes = plt.subplots(1, len(dilatancies), figsize=(6 * len(dilatancies), 4.6), sharey=True, squeeze=False)
    for ax, psi in zip(axes[0], dilatancies):
        members = sorted((results[n] for n in runs if results[n]["psi"] == psi),
                         key=lambda m: (not m["dry"], m["permeability"] or 0))
        for k, m in enumerate(members):
            label = "dry (case 1)" if m["dry"] else f"k = {m['permeability']:g} m^2"
            ax.plot(np.abs(m["curve"]["top_uy_m"]) * 1e3, np.abs(m["curve"]["top_Fy_N"]) / 1e3,
                    color="k" if m["dry"] else f"C{k}", lw=2.2 if m["dry"] else 1.3,
                    ls="--" if m["dry"] else "-", label=label)
            if m["onset_travel_m"] is not None:
                load = np.interp(m["onset_travel_m"], *(np.abs(m["curve"][c]) for c in ("top_uy_m", "top_Fy_N")))
                ax.plot(1e3 * m["onset_travel_m"], load / 1e3, "o", color="k" if m["dry"] else f"C{k}", ms=6,
                        mec="w", zorder=5)
        ax.set_title(f"dilatancy {psi:g} deg")
        ax.set_xlabel("top platen displacement [mm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("platen load [kN]")
    fig.suptitle("Load on the top platen against its displacement; dots: band onset (README.md)", fontsize=9)
    fig.tight_layout()
    save_figure(fig, path, 110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--runs", nargs="+", required=True)
    ap.add_argument("--results", default="results.md")
    ap.add_argument("--figures", default="figures")
    args = ap.parse_args()
    try:
        results = check_case.measure_all(args.out, args.runs)
        for name, m in results.items():
            m["folder"] = os.path.join(args.out, name)
        checks, failures = check_lines(check_case.check, args.out, args.runs)
    except (RunOutputError, KeyError, ValueError) as e:
        print(f"report_case: cannot read the outputs: {e}", file=sys.stderr)
        return 2
    ordered = sorted(args.runs, key=lambda n: (-results[n]["psi"], results[n]["dry"], results[n]["permeability"] or 0))
    os.makedirs(args.figures, exist_ok=True)
    results_dir = os.path.dirname(os.path.abspath(args.results))
    rel = lambda p: os.path.relpath(p, results_dir)  # noqa: E731
    figures = {"load_curves": os.path.join(args.figures, "load_curves.png")}
    plot_load_curves(results, ordered, figures["load_curves"])
    for psi in sorted({results[n]["psi"] for n in ordered}, reverse=True):
        saturated = [Run(results[n], args.out) for n in ordered if results[n]["psi"] == psi and not results[n]["dry"]]
        key = f"contours_psi{psi:g}"
        figures[key] = os.path.join(args.figures, f"{key}.png")
        plot_contours(saturated, figures[key], f"Dilatancy {psi:g} deg, saturated",
                      rows=PRESSURE_ROW + STRAIN_AND_ROTATION)
    dry = [Run(results[n], args.out) for n in ordered if results[n]["dry"]]
    figures["contours_dry"] = os.path.join(args.figures, "contours_dry.png")
    plot_contours(dry, figures["contours_dry"], "Dry reference runs (case 1)")

    first = results[ordered[0]]
    saturated = next(m for m in results.values() if not m["dry"])
    fluid = saturated["summary"]["material"]["pore_fluid"]
    lines = [
        "# Saturated shear-band case (workflows/saturated-shear-band/README.md): results",
        "",
        f"Written by `make report` from `{args.out}/<run>/`; do not edit. Case 1's specimen, material and loading "
        f"(../shear-band), friction {float(first['summary']['material']['viscoplasticity']['friction_angle']):g} deg, "
        f"each platen moving until {first['platen_stop_s']:g} s, then held; water: permeability k as in the table, "
        f"viscosity {float(fluid['fluid_viscosity']) * 1e3:g} mPa s, density {float(fluid['fluid_density']):g} kg/m^3, "
        f"Biot coefficient {float(fluid['biot_coefficient']):g}, Biot modulus {float(fluid['biot_modulus']) / 1e9:g} GPa; "
        f"top and bottom platens drained at 0 Pa, sides impermeable. Time step of the saturated runs "
        f"{saturated['info']['time_step_s'] * 1e6:.3g} us (auto: 0.8 x the undrained critical step), "
        f"of the dry runs {next(m for m in results.values() if m['dry'])['info']['time_step_s'] * 1e6:.3g} us.",
        "",
        "Columns (README.md, \"What is measured\"): H^2/c_v is the one-dimensional consolidation time over half the "
        "height (a formula of the resolved material, not a run output), over the loading time; band angle and width "
        "are the postprocessor's (summary.json) at the last snapshot; the band onset is the platen travel at the first "
        "snapshot from which both bands carry at least twice the mean plastic shear strain outside them (case 1's "
        f"band criterion), to one output interval ({1e3 * check_case.snapshot_travel(saturated):g} mm of travel); the band pore pressure is the mean over the "
        "interior points inside the bands at the platens' stop (a run without bands of its own: over the dry run's "
        "bands of its dilatancy); the fluid balance is energy.csv's fluid_mass_balance over the pore volume.",
        "",
    ] + run_table(results, ordered) + [
        "",
        wall_time_statement(results, args.out),
        "",
        f"`make check` ({failures} failed):",
        "",
    ] + checks + [
        "",
        "## Load curves",
        "",
        f"![load curves]({rel(figures['load_curves'])})",
        "",
        "## Pore pressure, plastic shear strain and micro-rotation on the deformed specimen",
        "",
    ]
    for key in sorted(k for k in figures if k.startswith("contours_psi")):
        lines += [f"![{key}]({rel(figures[key])})", ""]
    lines += [f"![dry runs]({rel(figures['contours_dry'])})", "",
              f"ParaView: `{args.out}/<run>/post/results.pvd` (Warp By Vector on `displacement`), or "
              "`mppm-postprocess <run>/run -o <dir> --figures --fields pore_pressure,plastic_shear_strain,rotation`.",
              ""]
    write_text(args.results, "\n".join(lines))
    print(f"wrote {args.results} and {', '.join(figures.values())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
