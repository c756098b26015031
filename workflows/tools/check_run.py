#!/usr/bin/python3
"""Physics checks of a finished run directory, shared by the case folders' `make check`.

Usage: check_run.py RUN_DIR [--max-balance-error 0.01] [--mirror top:bottom:y] [--moves top:+y]
Prints one line per check and exits 1 if any fails (2 if the run directory is unusable).
"""
import argparse
import sys

from mppm_outputs import RunOutputError, energy_rows, load_rows, run_info


def nonempty(rows, name):
    if not rows:
        raise RunOutputError(f"{name}: no rows")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--max-balance-error", type=float, default=0.01,
                    help="largest |balance_error| allowed in energy.csv (relative)")
    ap.add_argument("--mirror", action="append", default=[],
                    help="A:B:axis: boundaries A and B move as mirror images along axis (u_A = -u_B)")
    ap.add_argument("--moves", action="append", default=[],
                    help="A:+y or A:-x: boundary A ends displaced in that direction")
    args = ap.parse_args()
    try:
        info = run_info(args.run_dir)
        energy = nonempty(energy_rows(args.run_dir), f"{args.run_dir}/energy.csv")
        load = nonempty(load_rows(args.run_dir), f"{args.run_dir}/load.csv")
    except RunOutputError as e:
        print(f"check: cannot read the run directory: {e}", file=sys.stderr)
        return 2
    failures = 0

    def report(ok, text):
        nonlocal failures
        print(("PASS " if ok else "FAIL ") + text)
        failures += 0 if ok else 1

    report(info.get("status") == "completed", f"run status is '{info.get('status')}' (expected completed)")
    worst = max(abs(float(r["balance_error"])) for r in energy[1:]) if len(energy) > 1 else 0.0
    report(worst <= args.max_balance_error,
           f"largest energy balance error {worst:.3g} (limit {args.max_balance_error:g})")
    last = load[-1]
    for spec in args.mirror:
        a, b, axis = spec.split(":")
        ua, ub = float(last[f"{a}_u{axis}_m"]), float(last[f"{b}_u{axis}_m"])
        scale = max(abs(ua), abs(ub), 1e-300)
        # Mirror symmetry of geometry and load holds to round-off; 1e-6 leaves room for the
        # lattice (the notch lies half-way between two point rows, so the lattice is symmetric too).
        report(abs(ua + ub) <= 1e-6 * scale, f"{a} and {b} mirror each other along {axis}: u = {ua:.6g}, {ub:.6g} m")
    for spec in args.moves:
        name, direction = spec.split(":")
        sign, axis = (1.0 if direction[0] == "+" else -1.0), direction[1]
        u = float(last[f"{name}_u{axis}_m"])
        report(sign * u > 0, f"{name} moves along {direction}: u{axis} = {u:.6g} m")
    print(f"{failures} failed" if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
