#!/usr/bin/python3
"""The physics checks of the crack-initiation case (workflows/crack-initiation/README.md, "make check").

usage: check_case.py --out OUT --runs RUN... [--quick] [--convergence | --set-up-only]

Every run: the wave arrives when c_p says (the front's centroid within half a spacing's travel), the
first break comes after the arrival and at the tip (within one horizon of it), the crack stays on its
plane, the energy balance closes, and every measured time lies before a reflection can reach the tip.
Every level: the start time orders with the critical bond work (continuum < lattice < dissipation; the
continuum w_cr is 5 % below the lattice one at horizon factor 3.05, the dissipation one 40 % above).
The coarsest level (and with --quick the only one): the first break of the lattice and continuum
calibrations lies within delta / (c_R t_c) of Freund's t_c (README.md, "The band").
--set-up-only: the checks of every run only (the horizon study's runs and the micro-polar ones,
README.md: other horizon factors, two calibrations, another model).
--convergence checks instead that the difference to Freund shrinks from each horizon to the next smaller
one, for every calibration and measure, over the runs given: one series (the same factor, or the same
spacing; it does not shrink in either: results.md). Exit 1 when a check fails.
"""
import argparse

import initiation_rows as ir
from script_exit import RunError, run_main

MEASURES = [("first break", "first_break_s", "predicted_start_s"),
            ("advance 2 dx", "advance_2dx_s", "predicted_advance_2dx_s"),
            ("advance one horizon", "advance_horizon_s", "predicted_advance_horizon_s")]


def set_up_checks(rows, args_out, check):
    for r in rows:
        name = r["run"]
        lag = r["measured_arrival_s"] - r["predicted_arrival_s"]
        limit = 0.5 * r["spacing_m"] / r["wave_speed_m_per_s"]
        check(abs(lag) <= limit, f"{name}: arrival {lag * 1e6:+.3f} us from the computed one (limit {limit * 1e6:.3f} us)")
        fb = r["first_break_s"]
        check(fb is not None and fb > 0, f"{name}: a bond ahead of the tip broke after the arrival "
              f"({'-' if fb is None else f'{fb * 1e6:.4g} us'})")
        if fb is not None:
            check(r["first_break_x_m"] < r["horizon_m"],
                  f"{name}: first break {r['first_break_x_m'] * 1e3:.3g} mm ahead of the tip (within a horizon, "
                  f"{r['horizon_m'] * 1e3:.3g} mm)")
        # The crack stays a crack: few broken pairs off its plane (branching or spurious breaks at the
        # loaded rows would multiply them), as in tests/verification/test_solver_crack_energy.cpp.
        crossing = ir.broken_crossing_pairs(args_out, name)
        check(r["other_pairs_broken"] < crossing / 2,
              f"{name}: {r['other_pairs_broken']:.0f} pairs off the crack plane broken, {crossing} across it")
        check(abs(r["balance_error"]) < 1e-9, f"{name}: energy balance error {r['balance_error']:.2g}")
        check(r["finite"] == 1, f"{name}: the run stayed finite")
        for label, key, _ in MEASURES:
            if r[key] is not None:
                check(r[key] <= ir.window(r), f"{name}: {label} at {r[key] * 1e6:.4g} us, before any reflection "
                      f"({ir.window(r) * 1e6:.4g} us)")


def ordering_checks(rows, check):
    for dx, factor in sorted({(r["spacing_m"], r["horizon_factor"]) for r in rows}):
        level = {r["calibration"]: r for r in rows if (r["spacing_m"], r["horizon_factor"]) == (dx, factor)}
        if set(level) != {"lattice", "continuum", "dissipation"}:
            continue
        t = [level[c]["first_break_s"] for c in ("continuum", "lattice", "dissipation")]
        check(None not in t and t[0] <= t[1] < t[2],
              f"dx {dx * 1e3:g} mm, horizon factor {factor:g}: first break continuum <= lattice < dissipation "
              f"({', '.join(f'{x * 1e6:.4g}' if x is not None else '-' for x in t)} us)")


def band_checks(rows, check):
    coarse = max(r["spacing_m"] for r in rows)
    for r in rows:
        if r["spacing_m"] != coarse or r["calibration"] == "dissipation":
            continue
        band = r["horizon_m"] / (r["rayleigh_speed_m_per_s"] * r["predicted_start_s"])
        d = ir.difference(r["first_break_s"], r["predicted_start_s"])
        check(d is not None and abs(d) <= band,
              f"{r['run']}: first break {d * 100:+.1f} % from Freund's t_c (band delta / (c_R t_c) = {band * 100:.0f} %)"
              if d is not None else f"{r['run']}: no break")


def convergence_checks(rows, check):
    for cal in ("lattice", "continuum", "dissipation"):
        level = sorted((r for r in rows if r["calibration"] == cal), key=lambda r: -r["horizon_m"])
        for label, key, pred in MEASURES:
            d = [ir.difference(r[key], r[pred]) for r in level]
            for k in range(1, len(level)):
                ok = d[k] is not None and d[k - 1] is not None and abs(d[k]) < abs(d[k - 1])
                check(ok, f"{cal}, {label}: |difference| shrinks from horizon {level[k - 1]['horizon_m'] * 1e3:.3g} to "
                      f"{level[k]['horizon_m'] * 1e3:.3g} mm ({', '.join('-' if x is None else f'{x * 100:+.1f} %' for x in d[k - 1:k + 1])})")


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--runs", nargs="+", required=True)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--set-up-only", action="store_true")
    args = ap.parse_args(argv)
    rows = [ir.row(args.out, run) for run in args.runs]
    failed = []

    def check(ok, text):
        print(("ok    " if ok else "FAIL  ") + text)
        if not ok:
            failed.append(text)

    if args.convergence:
        convergence_checks(rows, check)
    else:
        set_up_checks(rows, args.out, check)
        if not args.set_up_only:
            ordering_checks(rows, check)
            band_checks(rows, check)
    if failed:
        raise RunError(f"{len(failed)} check(s) failed")
    print("all checks passed")
    return 0


if __name__ == "__main__":
    run_main(main)
