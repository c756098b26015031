"""The command line of the band cases' check_case.py (../shear-band, ../saturated-shear-band):
--out (the folder with one sub-folder per run), --runs (the run names), --quick (the reduced form);
one PASS / FAIL / SKIP line per check, exit 1 when any failed, 2 when the outputs cannot be read."""
import argparse
import sys

from mppm_outputs import RunOutputError


def label(ok):
    """A check's outcome: ok True (PASS), False (FAIL) or None (SKIP: measured, not asserted)."""
    return "SKIP" if ok is None else "PASS" if ok else "FAIL"


def check_lines(check, out, runs, quick=False):
    """check(out, runs, report, quick=...)'s lines for these runs as a Markdown list (for results.md),
    and the number of failures."""
    lines, failures = [], 0

    def report(ok, text):
        nonlocal failures
        lines.append(f"- `{label(ok)}` {text}")
        failures += 1 if ok is False else 0

    check(out, runs, report, quick=quick)
    return lines, failures


def run_case_checks(doc, check, runs_help):
    """Parses the command line and runs check(out, runs, report, quick=...), whose report(ok, text)
    takes ok True (PASS), False (FAIL) or None (SKIP: measured, not asserted)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="folder holding one sub-folder per run")
    ap.add_argument("--runs", nargs="+", required=True, help=runs_help)
    ap.add_argument("--quick", action="store_true", help="the reduced form: see above")
    args = ap.parse_args()
    failures = 0

    def report(ok, text):
        nonlocal failures
        print(f"{label(ok)} {text}")
        failures += 1 if ok is False else 0

    try:
        check(args.out, args.runs, report, quick=args.quick)
    except (RunOutputError, KeyError) as e:
        print(f"check_case: cannot read the outputs: {e}", file=sys.stderr)
        return 2
    print(f"{failures} check(s) failed" if failures else "all checks passed")
    return 1 if failures else 0
