#!/usr/bin/python3
"""Physics checks of the Kalthoff-Winkler case (workflows/kalthoff-winkler/README.md).

usage: check_case.py --out OUT --runs mp-1mm np-1mm mp-0.5mm np-0.5mm
         [--max-angle-difference 5] [--max-balance-error 0.01]

Checks (one line each, exit 1 if any fails, 2 if an output is missing):
- every run completed;
- a crack leaves each notch tip toward the unstruck side (the upper notch's crack turns
  counter-clockwise, up, the lower one's clockwise, down); the angles below are those cracks';
- the two cracks of a run are mirror images within the angle tolerance (the case is symmetric
  about y = 50 mm, and so is the lattice);
- the angle of each tip's main crack is the same within the tolerance (5 degrees) at dx = 1 mm and
  0.5 mm, and between the micro-polar and the non-polar model;
- no crack tip faster than the Rayleigh speed of the material: each notch's crack front from the
  run's crack-arrival table (kw_case.crack_front), its speed over advances of at least 3 dx;
- |energy balance error| <= 1 % at every row of energy.csv.
"""
import argparse
import itertools
import sys

import kw_case


class Checks:
    def __init__(self):
        self.failures = 0

    def report(self, ok, text):
        print(("PASS " if ok else "FAIL ") + text)
        self.failures += 0 if ok else 1


def check_run(checks, out, run, s, info, energy, tolerance, max_balance):
    checks.report(info.get("status") == "completed", f"{run}: run status '{info.get('status')}' (expected completed)")
    every = kw_case.cracks_by_tip(s)
    sides = kw_case.main_cracks(s)
    for side in ("upper", "lower"):
        angles = ", ".join(f"{e['signed_angle_deg']:+.1f}" for e in every[side]) or "none"
        checks.report(side in sides, f"{run}: a crack leaves the {side} notch tip toward the unstruck side "
                      f"(cracks leaving it: {angles} deg)")
    if len(sides) == 2:
        up, low = sides["upper"]["signed_angle_deg"], sides["lower"]["signed_angle_deg"]
        checks.report(abs(up + low) <= tolerance,
                      f"{run}: the two cracks are mirror images: {up:+.1f} and {low:+.1f} deg (limit {tolerance:g})")
    c_r = kw_case.rayleigh_speed(s["material"])
    for side, entry in sorted(sides.items()):
        front = kw_case.crack_front(out, run, entry, s["spacing_m"], s["horizon_m"])
        _, speed = kw_case.front_metrics(front, s["spacing_m"])
        checks.report(speed is not None and speed < c_r,
                      f"{run}: the {side} crack's largest tip speed "
                      f"{'(not measured: the front never advanced 3 dx)' if speed is None else f'{speed:.0f} m/s'} "
                      f"below the Rayleigh speed {c_r:.0f} m/s")
    worst = max(abs(float(row["balance_error"])) for row in energy)
    checks.report(worst <= max_balance, f"{run}: largest energy balance error {worst:.3g} (limit {max_balance:g})")
    return {side: c["angle_deg"] for side, c in sides.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--runs", nargs="+", required=True)
    ap.add_argument("--max-angle-difference", type=float, default=5.0)
    ap.add_argument("--max-balance-error", type=float, default=0.01)
    args = ap.parse_args()
    try:
        data = {r: (kw_case.summary(args.out, r), kw_case.run_info(args.out, r), kw_case.energy_rows(args.out, r))
                for r in args.runs}
    except (kw_case.RunOutputError, OSError, ValueError) as e:
        print(f"check_case: cannot read the case outputs: {e} (run make first)", file=sys.stderr)
        return 2
    checks = Checks()
    angles = {r: check_run(checks, args.out, r, *data[r], args.max_angle_difference, args.max_balance_error)
              for r in args.runs}
    # Pairs that differ in one thing only: the spacing (same model) or the model (same spacing).
    for a, b in itertools.combinations(args.runs, 2):
        sa, sb = data[a][0], data[b][0]
        same_model, same_spacing = kw_case.model(sa) == kw_case.model(sb), kw_case.spacing_mm(sa) == kw_case.spacing_mm(sb)
        if same_model == same_spacing:
            continue
        for side in ("upper", "lower"):
            if side in angles[a] and side in angles[b]:
                d = abs(angles[a][side] - angles[b][side])
                checks.report(d <= args.max_angle_difference,
                              f"{a} / {b}: {side} crack angle {angles[a][side]:.1f} / {angles[b][side]:.1f} deg, "
                              f"differ by {d:.1f} (limit {args.max_angle_difference:g})")
    return 1 if checks.failures else 0


if __name__ == "__main__":
    sys.exit(main())
