#!/usr/bin/python3
"""Physics checks of the crack-branching case (workflows/crack-branching/README.md).

usage: check_case.py --out OUT --base base --rate-runs rate-2.5us rate-6.25us rate-12.5us
         [--notch-tip X,Y] [--max-balance-error 0.02]

Checks (one line each, exit 1 if any fails, 2 if an output is missing):
- base run: the crack grows from the notch tip: the first points that join the crack path
  (the postprocessor's damage threshold) beyond the pre-crack lie within two horizons of the
  notch tip (the inner end of the pre-crack in the base run's points file, unless --notch-tip);
- base run: the crack branches (crack_branch_time_s is not null);
- rate study: crack start, branching and end times all exist and increase strictly with t0;
- every run: the largest tip speed is below the Rayleigh wave speed of the material
  (classical long-wave value from lambda, mu and rho = solid_fraction x density);
- every run: |energy balance error| <= 2 % at every row of energy.csv.
"""
import argparse
import math
import sys

import crack_case


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--base", required=True)
    ap.add_argument("--rate-runs", nargs="+", required=True)
    ap.add_argument("--notch-tip", help="x,y of the pre-crack tip [m] (default: from the base run's points file)")
    ap.add_argument("--max-balance-error", type=float, default=0.02)
    args = ap.parse_args()
    failures = 0

    def report(ok, text):
        nonlocal failures
        print(("PASS " if ok else "FAIL ") + text)
        failures += 0 if ok else 1

    runs = [args.base] + args.rate_runs
    try:
        summaries = {r: crack_case.summary(args.out, r) for r in runs}
        energies = {r: crack_case.energy_rows(args.out, r) for r in runs}
        base_frames = crack_case.frames(args.out, args.base)
        tip = (tuple(float(v) for v in args.notch_tip.split(",")) if args.notch_tip
               else crack_case.precrack_tip(args.out, args.base))
    except (crack_case.RunOutputError, OSError, ValueError) as e:
        print(f"check_case: cannot read the case outputs: {e} (run make first)", file=sys.stderr)
        return 2

    # The crack starts at the notch tip.
    base = summaries[args.base]
    horizon = base["horizon_m"]
    threshold = crack_case.crack_damage_threshold(base)
    pre = crack_case.crack_points(base_frames[0][1], threshold)
    first_new, when = set(), None
    for time, path in base_frames[1:]:
        new = crack_case.crack_points(path, threshold) - pre
        if new:
            first_new, when = new, time
            break
    if not first_new:
        report(False, f"base run: no point joins the crack path (damage >= {threshold:g}) beyond the pre-crack")
    else:
        far = max(math.dist(p, tip) for p in first_new)
        report(far <= 2 * horizon, f"base run: the crack grows from the notch tip: the {len(first_new)} points that join "
               f"the crack first (t = {when * 1e6:.3g} us) lie within {far * 1e3:.3g} mm of it (limit 2 horizons = "
               f"{2 * horizon * 1e3:.3g} mm)")
    branch = base.get("crack_branch_time_s")
    report(branch is not None, "base run: the crack branches" +
           (f" at {branch * 1e6:.4g} us" if branch is not None else " (crack_branch_time_s is null)"))

    # Slower loading delays every event.
    def ramp_of(run):
        return summaries[run]["boundary_conditions"][0]["history"][1][0]
    study = sorted(args.rate_runs, key=ramp_of)
    for key, what in (("crack_start_time_s", "start"), ("crack_branch_time_s", "branching"), ("crack_end_time_s", "end")):
        times = [summaries[r].get(key) for r in study]
        text = ", ".join(f"t0 = {ramp_of(r) * 1e6:.4g} us: " + ("none" if t is None else f"{t * 1e6:.4g} us")
                         for r, t in zip(study, times))
        ok = all(t is not None for t in times) and all(a < b for a, b in zip(times, times[1:]))
        report(ok, f"rate study: crack {what} time increases with t0 ({text})")

    for run in runs:
        s = summaries[run]
        speed, c_r = s.get("crack_tip_speed_max_m_per_s"), crack_case.rayleigh_speed(s["material"])
        report(speed is not None and speed < c_r,
               f"{run}: largest crack tip speed {speed if speed is None else round(speed)} m/s below the Rayleigh speed "
               f"{c_r:.0f} m/s")
        worst = max(abs(float(row["balance_error"])) for row in energies[run])
        report(worst <= args.max_balance_error,
               f"{run}: largest energy balance error {worst:.3g} (limit {args.max_balance_error:g})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
