#!/usr/bin/python3
"""Writes results.md and its figures for the shear-band case from the outputs of its runs.

Usage: report_case.py --out OUT --runs R... --published-runs R... --cone-run R --results results.md
                      --figures figures/

Every number in results.md is read from the run folders (post/summary.json,
post/load_curve.csv, run/energy.csv, run/run_info.json, the last .vtu, the Makefile's
timing/ files) or computed from them (band_measures.py, the homogeneous response of
homogeneous_response.py from the runs' resolved material, the textbook angle formulas,
labelled as such). The checks are those of check_case.py. Figures are PNG files drawn
headless with matplotlib (Agg). Exit 2 if an output is missing or unreadable.
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
from homogeneous_response import biaxial_response, homogeneous_peak  # noqa: E402
from shear_band_fields import LastSnapshot, parse_run_name  # noqa: E402
# mppm_outputs is in tools/, which shear_band_fields puts on the path.
from mppm_outputs import (RunOutputError, prescribed_displacement, read_csv_columns, resolved_scene,  # noqa: E402
                          save_figure, write_text)
from band_contours import plot_contours  # noqa: E402  (tools/, shared with ../saturated-shear-band)


class Run:
    def __init__(self, out, name):
        self.name = name
        self.folder = os.path.join(out, name)
        self.phi_name, self.psi_name = parse_run_name(name)
        self.m = check_case.run_measures(self.folder)
        self.summary = self.m["summary"]
        self.info = self.m["info"]
        self.curve = read_csv_columns(os.path.join(self.folder, "post", "load_curve.csv"))
        self.material = self.summary["material"]
        vp = self.material["viscoplasticity"]
        self.phi, self.psi = float(vp["friction_angle"]), float(vp["dilatancy_angle"])
        if abs(self.phi - self.phi_name) > 1e-6 or abs(self.psi - self.psi_name) > 1e-6:
            raise RunOutputError(f"{self.folder}: the run's resolved angles ({self.phi:g}, {self.psi:g} deg) "
                                 "do not match its name")
        self.cone_match = vp["cone_match"]
        self.scene = resolved_scene(os.path.join(self.folder, "run"))
        self.snapshot = None

    def last_snapshot(self):
        if self.snapshot is None:
            self.snapshot = LastSnapshot(os.path.join(self.folder, "post"), self.summary["horizon_m"])
        return self.snapshot

    def confinement(self):
        """The lateral pressure [Pa] of the resolved boundary conditions (left and right)."""
        values = [float(bc["value"]) for bc in self.summary["boundary_conditions"] if bc.get("type") == "pressure"]
        if not values:
            raise RunOutputError(f"{self.folder}: no pressure boundary condition in summary.json")
        return values[0]

    def travel(self):
        """Largest platen displacement of the run [m]."""
        return float(np.max(np.abs(self.curve["top_uy_m"])))

    def prescribed_travel(self):
        """How far the top platen is driven [m]: its resolved velocity history integrated over
        the run (speed x time until it stops)."""
        return abs(prescribed_displacement(self.scene, "top", 1))

    def loading_times(self):
        """(time the top platen stops, end of the run) [s], from the resolved scene."""
        history = next(bc for bc in self.scene["boundary_conditions"] if bc["name"] == "top")["history"]
        moving = [float(t) for t, velocity in history if any(velocity)]
        return max(moving), float(self.scene["time"]["end"])

    def specimen_size(self):
        """(width, height) of the specimen [m], from the body points of the last snapshot."""
        snap = self.last_snapshot()
        body = snap.reference[snap.body]
        width = body[:, 0].max() - body[:, 0].min() + self.summary["spacing_m"]
        return width, body[:, 1].max() - body[:, 1].min() + self.summary["spacing_m"]


def fmt(value, spec, missing="none"):
    return missing if value is None else format(value, spec)


def read_timing(out):
    """timing/*.txt: 'STAGE START END INVOCATION JOBS' -> {stage: (start, end, invocation, jobs)}."""
    stages = {}
    folder = os.path.join(out, "timing")
    if not os.path.isdir(folder):
        return stages
    for file in sorted(os.listdir(folder)):
        with open(os.path.join(folder, file)) as f:
            parts = f.read().split()
        if len(parts) == 5:
            stages[parts[0]] = (float(parts[1]), float(parts[2]), parts[3], parts[4])
    return stages


def case_wall_time(out, runs):
    """(seconds, jobs) from the first stage's start to the last stage's end, if the points and
    every run's solve and post stages come from one make invocation; else None."""
    stages = read_timing(out)
    names = ["points"] + [f"{stage}-{r.name}" for r in runs for stage in ("solve", "post")]
    if any(n not in stages for n in names):
        return None
    chosen = [stages[n] for n in names]
    if len({s[2] for s in chosen}) != 1:
        return None
    return max(s[1] for s in chosen) - min(s[0] for s in chosen), chosen[0][3]


def homogeneous(run):
    """Homogeneous plane-strain estimate for the run's material: (peak load [N], platen
    displacement at the peak [m] or None beyond twice the case's travel, load at the case's travel)."""
    width, height = run.specimen_size()
    area = width * CASE_THICKNESS  # the platen's area
    peak, at, at_travel = homogeneous_peak(run.material, run.confinement(), height, CASE_TRAVEL)
    return peak * area, at, at_travel * area


def homogeneous_text(peak, at):
    if at is None:
        return f"> {peak:.0f} (still rising at {2e3 * CASE_TRAVEL:.0f} mm)"
    return f"{peak:.0f} at {1e3 * at:.1f}"


def run_table(runs, with_homogeneous=True):
    head = ("| run | friction [deg] | dilatancy [deg] | peak load [N] | platen displacement at peak [mm] | "
            + ("homogeneous peak [N] at [mm] | " if with_homogeneous else "")
            + "band angles [deg] | mean band angle [deg] | band width [mm] | arm / outside strain | "
              "inside / outside mean abs(w) | max plastic shear strain | dissipated / work | "
              "max abs(balance error) | solver wall [s] (threads) |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in runs:
        s, m = r.summary, r.m
        angles = s.get("shear_band_angles_deg") or []
        homog = ""
        if with_homogeneous:
            peak, at, _ = homogeneous(r)
            homog = homogeneous_text(peak, at) + " | "
        contrasts = [c for c in m["contrasts"] if c is not None]
        lines.append(
            f"| {r.name} | {r.phi:g} | {r.psi:g} | {fmt(s.get('peak_load_N'), '.0f')} | "
            f"{fmt(s.get('displacement_at_peak_m') and 1e3 * s['displacement_at_peak_m'], '.2f')} | {homog}"
            f"{', '.join(f'{a:.1f}' for a in angles) or 'none'} | {fmt(s.get('shear_band_angle_deg'), '.1f')} | "
            f"{fmt(s.get('shear_band_width_m') and 1e3 * s['shear_band_width_m'], '.1f')} | "
            f"{', '.join(f'{c:.2f}' for c in contrasts) or 'n/a'} | {fmt(m['rotation_ratio'], '.2f', 'n/a')} | "
            f"{m['max_plastic_shear_strain']:.3f} | {m['plastic_dissipation_J'] / m['external_work_J']:.2f} | "
            f"{m['worst_balance_error']:.1e} | {r.info['wall_seconds']:.0f} ({r.info['threads']}) |")
    return lines


def sweeps(runs):
    friction, dilatancy = check_case.sweep_centre([r.name for r in runs])
    return [([r for r in runs if r.psi_name == dilatancy],
             f"friction sweep (dilatancy {dilatancy:g} deg)", lambda r: f"phi = {r.phi:g} deg"),
            ([r for r in runs if r.phi_name == friction],
             f"dilatancy sweep (friction {friction:g} deg)", lambda r: f"psi = {r.psi:g} deg")]


def mm(length):
    return f"{1e3 * length:g} mm"


def plot_load_curves(case_runs, published_runs, path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), sharey=True)
    published_by_angles = {(r.phi, r.psi): r for r in published_runs}
    for ax, (members, title, label) in zip(axes, sweeps(case_runs)):
        for k, r in enumerate(sorted(members, key=lambda r: (r.phi, r.psi))):
            colour = f"C{k}"
            ax.plot(np.abs(r.curve["top_uy_m"]) * 1e3, np.abs(r.curve["top_Fy_N"]) / 1e3, color=colour, lw=1.6,
                    label=f"{label(r)}, case ({mm(CASE_TRAVEL)})")
            shorter = published_by_angles.get((r.phi, r.psi))
            if shorter is not None:
                ax.plot(np.abs(shorter.curve["top_uy_m"]) * 1e3, np.abs(shorter.curve["top_Fy_N"]) / 1e3,
                        color=colour, lw=0.9, ls="--", label=f"{label(r)}, as published ({mm(PUBLISHED_TRAVEL)})")
        ax.axvline(1e3 * PUBLISHED_TRAVEL, color="0.5", lw=0.8, ls=":")
        ax.set_title(title)
        ax.set_xlabel("top platen displacement [mm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("platen load [kN]")
    fig.suptitle("Load on the top platen against its displacement (the bottom platen moves the same the other way)",
                 fontsize=9)
    fig.tight_layout()
    save_figure(fig, path, 110)


def plot_cone_match(plane_strain, triaxial, path):
    fig, ax = plt.subplots(figsize=(6.5, 4.4))
    for k, r in enumerate((plane_strain, triaxial)):
        ax.plot(np.abs(r.curve["top_uy_m"]) * 1e3, np.abs(r.curve["top_Fy_N"]) / 1e3, color=f"C{k}", lw=1.4,
                label=f"run, cone match {r.cone_match}")
        width, height = r.specimen_size()
        eyy, syy, _, _ = biaxial_response(r.material, r.confinement(), -2.0 * r.travel() / height)
        ax.plot(-eyy * height / 2 * 1e3, -syy * width * CASE_THICKNESS / 1e3, color=f"C{k}", lw=1.0, ls="--",
                label=f"homogeneous plane strain, {r.cone_match}")
    ax.set_xlabel("top platen displacement [mm]")
    ax.set_ylabel("platen load [kN]")
    ax.set_title(f"{plane_strain.name}: cone match", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, path, 110)


CASE_TRAVEL = None  # platen travel of the case runs [m], set from their resolved scenes in main()
PUBLISHED_TRAVEL = None  # the same for the published form
CASE_THICKNESS = None  # the scene's thickness [m], set from the case runs' resolved scenes in main()


def main():
    global CASE_TRAVEL, PUBLISHED_TRAVEL, CASE_THICKNESS
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--runs", nargs="+", required=True, help="the case's runs")
    ap.add_argument("--published-runs", nargs="+", required=True,
                    help="the same runs with the published platen travel")
    ap.add_argument("--cone-run", required=True, help="phi35-psi15 with the other cone match")
    ap.add_argument("--results", default="results.md")
    ap.add_argument("--figures", default="figures")
    args = ap.parse_args()
    try:
        case = [Run(args.out, n) for n in args.runs]
        published = [Run(args.out, n) for n in args.published_runs]
        cone = Run(args.out, args.cone_run)
        CASE_TRAVEL = case[0].prescribed_travel()
        PUBLISHED_TRAVEL = published[0].prescribed_travel()
        CASE_THICKNESS = float(case[0].scene["thickness"])
        case_checks, case_failures = check_lines(check_case.check, args.out, args.runs)
        published_checks, published_failures = check_lines(check_case.check, args.out, args.published_runs)
    except (RunOutputError, KeyError, ValueError) as e:
        print(f"report_case: cannot read the outputs: {e}", file=sys.stderr)
        return 2
    reference = next((r for r in case if (r.phi, r.psi) == (cone.phi, cone.psi)), None)
    if reference is None:
        print(f"report_case: no case run with the angles of {cone.name}", file=sys.stderr)
        return 2

    os.makedirs(args.figures, exist_ok=True)
    results_dir = os.path.dirname(os.path.abspath(args.results))
    rel = lambda p: os.path.relpath(p, results_dir)  # noqa: E731
    figures = {k: os.path.join(args.figures, f"{k}.png") for k in ("load_curves", "contours_case",
                                                                    "contours_published", "cone_match")}
    plot_load_curves(case, published, figures["load_curves"])
    plot_contours(case, figures["contours_case"], f"The case ({mm(CASE_TRAVEL)} per platen)")
    plot_contours(published, figures["contours_published"], f"As published ({mm(PUBLISHED_TRAVEL)} per platen)")
    plot_cone_match(reference, cone, figures["cone_match"])

    vp = case[0].material["viscoplasticity"]
    width, height = case[0].specimen_size()
    stop, end = case[0].loading_times()
    published_stop, published_end = published[0].loading_times()
    total = case_wall_time(args.out, case)
    if total is None:
        wall = ("not measured: the points and the five runs did not all come from one `make` invocation "
                "(`make clean && make -j2` measures it)")
    else:
        wall = (f"**{total[0]:.0f} s** with `make -j{total[1]}` (points, five runs with `--threads 1` and their "
                "postprocessing, from the first stage's start to the last one's end)"
                + ("" if total[1] == "2" else "; this is not the 2-core figure: run `make -j2`"))
    homog_case = [homogeneous(r) for r in case]
    beyond = [r.name for r, (_, at, _) in zip(case, homog_case) if at is None or at > PUBLISHED_TRAVEL]
    lines = [
        "# Shear-band case (workflows/shear-band/README.md): results",
        "",
        f"Written by `make report` from `{args.out}/<run>/`; do not edit. Specimen {1e3 * width:.0f} x "
        f"{1e3 * height:.0f} mm, dx = {1e3 * case[0].summary['spacing_m']:g} mm, horizon {1e3 * case[0].summary['horizon_m']:.3g} mm, "
        f"{case[0].info['points']} points. Material of every run (their resolved scenes): cohesion "
        f"{float(vp['cohesion']) / 1e6:g} MPa, hardening {float(vp['hardening']) / 1e6:g} MPa, viscosity "
        f"{float(vp['viscosity']) / 1e6:g} MPa s, cone match `{case[0].cone_match}`, lateral pressure "
        f"{case[0].confinement() / 1e6:g} MPa. Band angles are acute angles to the x axis (the direction of the "
        "minor compressive principal stress, the confinement). How the columns are measured: README.md.",
        "",
        f"## The case: {mm(CASE_TRAVEL)} per platen ({stop:g} s, hold until {end:g} s)",
        "",
    ] + run_table(case) + [
        "",
        f"Wall time of the whole case on this 2-core machine: {wall}.",
        "",
        "Homogeneous peak: the peak of the homogeneous plane-strain response of the run's material under the "
        "same confinement (`homogeneous_response.py`, no specimen, no rate), as a load on the platen.",
        "",
        f"`make check` ({case_failures} failed):",
        "",
    ] + case_checks + [
        "",
        f"## As published: {mm(PUBLISHED_TRAVEL)} per platen ({published_stop:g} s, hold until {published_end:g} s)",
        "",
        f"`make as-published`: the same runs, stopped where the published case stops them (bitwise the case's runs "
        f"up to {mm(PUBLISHED_TRAVEL)}). The homogeneous peak lies beyond {mm(PUBLISHED_TRAVEL)} for "
        f"{', '.join(beyond) if beyond else 'no run'}: there the material is still hardening when these platens "
        "stop, which is why the case's default travel is doubled (README.md, \"Why the default travel is 9 mm\").",
        "",
    ] + run_table(published, with_homogeneous=False) + [
        "",
        f"`make check-published` ({published_failures} failed):",
        "",
    ] + published_checks + [
        "",
        "Textbook band angles (formulas, not run outputs): Roscoe 45 + psi/2, Arthur 45 + (phi + psi)/4, "
        "Coulomb 45 + phi/2 [deg], against the measured mean angle:",
        "",
        f"| run | Roscoe | Arthur | Coulomb | case ({mm(CASE_TRAVEL)}) | as published ({mm(PUBLISHED_TRAVEL)}) |",
        "|---|---|---|---|---|---|",
    ]
    published_by_angles = {(r.phi, r.psi): r for r in published}
    for r in case:
        shorter = published_by_angles.get((r.phi, r.psi))
        lines.append(f"| phi{r.phi:g}-psi{r.psi:g} | {45 + r.psi / 2:.1f} | {45 + (r.phi + r.psi) / 4:.1f} | "
                     f"{45 + r.phi / 2:.1f} | {fmt(r.summary.get('shear_band_angle_deg'), '.1f')} | "
                     f"{fmt(shorter and shorter.summary.get('shear_band_angle_deg'), '.1f')} |")
    hp, hp_at, hp_travel = homogeneous(reference)
    ht, ht_at, ht_travel = homogeneous(cone)
    lines += [
        "",
        "## Load curves",
        "",
        f"![load curves]({rel(figures['load_curves'])})",
        "",
        "Solid: the case; dashed: the published form, which is the same runs up to "
        f"{mm(PUBLISHED_TRAVEL)} (dotted line); the drops at the ends are the relaxation during the holds.",
        "",
        "## Plastic shear strain and micro-rotation on the deformed configuration",
        "",
        f"![contours, case]({rel(figures['contours_case'])})",
        "",
        f"![contours, as published]({rel(figures['contours_published'])})",
        "",
        f"ParaView: `{args.out}/<run>/post/results.pvd` (Warp By Vector on `displacement`).",
        "",
        "## Cone match",
        "",
        f"| run | cone match | peak load [N] | homogeneous load at {1e3 * CASE_TRAVEL:.1f} mm [N] | homogeneous peak [N] "
        "at [mm] | max plastic shear strain | dissipated / work | bands (postprocessor) | arm / outside strain | "
        "inside / outside mean abs(w) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r, (peak, at, at_travel) in ((reference, (hp, hp_at, hp_travel)), (cone, (ht, ht_at, ht_travel))):
        contrasts = [c for c in r.m["contrasts"] if c is not None]
        lines.append(f"| {r.name} | `{r.cone_match}` | {fmt(r.summary.get('peak_load_N'), '.0f')} | {at_travel:.0f} | "
                     f"{homogeneous_text(peak, at)} | "
                     f"{r.m['max_plastic_shear_strain']:.4f} | "
                     f"{r.m['plastic_dissipation_J'] / r.m['external_work_J']:.3f} | "
                     f"{len(r.m['bands'])} | {', '.join(f'{c:.2f}' for c in contrasts) or 'n/a'} | "
                     f"{fmt(r.m['rotation_ratio'], '.2f', 'n/a')} |")
    lines += [
        "",
        f"![cone match]({rel(figures['cone_match'])})",
        "",
        "Solid: the runs; dashed: the homogeneous plane-strain response of the same material "
        "(`homogeneous_response.py`). The postprocessor reports a band for any localized pattern of plastic shear "
        "strain, however small; `make check` also asks the arms of a band to carry at least twice the strain "
        "outside it.",
        "",
    ]
    write_text(args.results, "\n".join(lines))
    print(f"wrote {args.results} and {', '.join(figures.values())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
