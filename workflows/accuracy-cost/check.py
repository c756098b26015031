#!/usr/bin/python3
"""Checks the trends of the accuracy-cost study in a CSV written by sweeps.py.

usage: check.py accuracy_cost.csv

For every spacing sweep (problem, dimension, threads) at its fixed horizon factor:
- the error falls strictly as the lattice is refined;
- the observed convergence rate (least squares of log error against log dx) is within 0.5 of
  the rate expected for the scheme (README.md);
- the cost grows: bond updates strictly, wall time from the coarsest to the finest lattice;
- bond updates grow like dx^-(d+1) (the fitted exponent within 0.5 of d + 1): d from the
  points, 1 from the time step, at a fixed number of bonds per point (the Terzaghi column, a
  fixed number of points across: dx^-2).
crack_energy: its error is the work of each bond's last step before it breaks, so at a fixed
safety factor the spacing sweep's rate is expected to be 0 (within 0.5; the error need not
fall), and the safety sweep must show the error falling with the safety factor at rate 1 +- 0.5.
terzaghi: the base-pressure error (second_error) must fall too, at rate 1 +- 0.5, and a column
of at least the pore-fluid test's 80 rows must meet that test's tolerances (|U - series| <= 0.02,
|p_base / p0 - series| <= 0.03); the quick study's columns (10..40 rows) are coarser than the
test's and are checked for the trends only.
Every row must have run (status ok).
Exit 1 with every failed check listed.
"""
import sys

import study


def check_terzaghi(name, group):
    """The base pressure's trend and, on a column as fine as the test's, the test's tolerances."""
    failures = []
    pressure = [r["second_error"] for r in group]
    resolutions = [r["resolution"] for r in group]
    if any(b >= a for a, b in zip(pressure, pressure[1:])):
        failures.append(f"{name}: base-pressure error does not fall with the spacing: {list(zip(resolutions, pressure))}")
    rate = study.log_slope(group, "spacing_m", "second_error")
    expected = study.EXPECTED_RATE["terzaghi"]
    print(f"  base-pressure errors {', '.join(f'{e:.3g}' for e in pressure)}; observed rate {rate:.2f}, "
          f"expected {expected:.0f}")
    if abs(rate - expected) > 0.5:
        failures.append(f"{name}: base-pressure observed rate {rate:.2f}, expected {expected:.0f} +- 0.5")
    finest = group[-1]
    if finest["resolution"] < study.TERZAGHI_TEST_ROWS:
        print(f"  the test's tolerances not checked: the finest column has {finest['resolution']} rows "
              f"(the test's: {study.TERZAGHI_TEST_ROWS})")
        return failures
    for key, tolerance in study.TERZAGHI_TOLERANCE.items():
        print(f"  {finest['resolution']} rows: {key} {finest[key]:.4f} (the test's tolerance {tolerance})")
        if finest[key] > tolerance:
            failures.append(f"{name}: {finest['resolution']} rows: {key} {finest[key]:.4f} above the test's {tolerance}")
    return failures


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    rows = study.load(sys.argv[1])
    failures = []
    for r in rows:
        if r["status"] != "ok":
            failures.append(f"{r['problem']} resolution {r['resolution']}: status {r['status']} (expected ok)")
    groups = study.spacing_groups(rows)
    if not groups:
        failures.append("no spacing sweep in the CSV")
    for (problem, dimension, threads), group in sorted(groups.items()):
        name = f"{study.label(problem, dimension)}, {threads} thread(s)"
        if len(group) < 3:
            failures.append(f"{name}: {len(group)} spacing levels (at least 3 needed for a trend)")
            continue
        errors = [r["error"] for r in group]
        resolutions = [r["resolution"] for r in group]
        if problem not in study.EXPECTED_SAFETY_RATE and any(b >= a for a, b in zip(errors, errors[1:])):
            failures.append(f"{name}: error does not fall with the spacing: {list(zip(resolutions, errors))}")
        rate = study.log_slope(group, "spacing_m", "error")
        expected = study.EXPECTED_RATE[problem]
        print(f"{name}: errors {', '.join(f'{e:.3g}' for e in errors)} at resolutions {resolutions}; "
              f"observed rate {rate:.2f}, expected {expected:.0f}")
        if abs(rate - expected) > 0.5:
            failures.append(f"{name}: observed rate {rate:.2f}, expected {expected:.0f} +- 0.5")
        updates = [r["bond_updates"] for r in group]
        if any(b <= a for a, b in zip(updates, updates[1:])):
            failures.append(f"{name}: bond updates do not grow with refinement: {updates}")
        if group[-1]["wall_seconds"] <= group[0]["wall_seconds"]:
            failures.append(f"{name}: the finest lattice ran faster than the coarsest")
        if problem != "layer_shear":  # the static layer is a strip: its cost is not a dx^-(d+1) law
            exponent = -study.log_slope(group, "spacing_m", "bond_updates")
            expected_exponent = study.cost_exponent(problem, dimension)
            print(f"  bond updates ~ dx^-{exponent:.2f} (expected {expected_exponent:.0f})")
            if abs(exponent - expected_exponent) > 0.5:
                failures.append(f"{name}: bond updates ~ dx^-{exponent:.2f}, expected dx^-{expected_exponent:.0f} +- 0.5")
        if problem == "terzaghi":
            failures += check_terzaghi(name, group)
    for problem, expected in study.EXPECTED_SAFETY_RATE.items():
        group = sorted((r for r in study.ok(rows) if r["problem"] == problem and r["sweep"] == "safety"),
                       key=lambda r: r["safety"])
        if not group:
            continue
        name = f"{study.label(problem, group[0]['dimension'])}, safety sweep"
        errors = [r["error"] for r in group]
        if any(b <= a for a, b in zip(errors, errors[1:])):
            failures.append(f"{name}: error does not grow with the safety factor: "
                            f"{[(r['safety'], r['error']) for r in group]}")
        rate = study.log_slope(group, "safety", "error")
        print(f"{name}: errors {', '.join(f'{e:.3g}' for e in errors)} at safety "
              f"{[r['safety'] for r in group]}; observed rate {rate:.2f}, expected {expected:.0f}")
        if abs(rate - expected) > 0.5:
            failures.append(f"{name}: observed rate {rate:.2f} in the safety factor, expected {expected:.0f} +- 0.5")
    if failures:
        print("accuracy-cost check FAILED:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("accuracy-cost check passed")


if __name__ == "__main__":
    main()
