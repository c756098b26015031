#!/usr/bin/python3
"""Runs mppm-damage-calibration over one dimension's matrix and writes its CSV rows, with a
record of the run beside them (OUTPUT.json: date, wall time, command, commit, threads, load
average). Both are written atomically (a temporary file renamed at the end), the record first,
so a CSV that exists is complete and has its record.

usage: measure.py MPPM_DAMAGE_CALIBRATION OUTPUT.csv --dimension D --horizon-factors M1,M2,...
                  --stabilizations G1,G2,...
"""
import datetime
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import write_text  # noqa: E402
from script_exit import InputError, RunError, run_main  # noqa: E402


def commit_of(directory):
    """The repository's commit, '+modified' when the work tree differs from it ('unknown'
    outside a git work tree)."""
    try:
        head = subprocess.run(["git", "-C", directory, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", directory, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+modified" if dirty else "")


def main(argv):
    if len(argv) < 2:
        raise InputError(__doc__.strip().splitlines()[-2].strip() + " ...: expected the program and the CSV")
    program, output, options = argv[0], argv[1], argv[2:]
    if not os.access(program, os.X_OK):
        raise InputError(f"{program}: not an executable (build the target mppm-damage-calibration)")
    command = [program] + options
    started = datetime.datetime.now(datetime.timezone.utc)
    load_before = os.getloadavg()[0]
    clock = time.monotonic()
    # Rows are echoed as they come (a long matrix shows its progress) and written at the end.
    rows = []
    with subprocess.Popen(command, stdout=subprocess.PIPE, text=True) as process:
        for row in process.stdout:
            rows.append(row)
            sys.stdout.write(row)
            sys.stdout.flush()
    wall = time.monotonic() - clock
    if process.returncode != 0:
        raise RunError(f"{' '.join(command)} exited with {process.returncode} (its message is above)")
    record = {
        "date": started.strftime("%Y-%m-%d"),
        "started_utc": started.strftime("%Y-%m-%dT%H:%M:%SZ"),
        "wall_seconds": round(wall, 1),
        "command": " ".join([os.path.basename(program)] + options),
        "commit": commit_of(os.path.dirname(os.path.abspath(__file__))),
        "threads": os.environ.get("OMP_NUM_THREADS", str(os.cpu_count())),
        "load_average_before": round(load_before, 2),
        "load_average_after": round(os.getloadavg()[0], 2),
    }
    write_text(os.path.splitext(output)[0] + ".json", json.dumps(record, indent=2) + "\n")
    write_text(output, "".join(rows))
    return 0


if __name__ == "__main__":
    run_main(main)
