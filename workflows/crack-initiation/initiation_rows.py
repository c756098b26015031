"""The rows of the crack-initiation runs (workflows/crack-initiation/README.md): OUT/<run>/row.csv, written
by mppm-crack-initiation (one header and one row: Freund's predictions and the measured times, every
time after the wave's arrival at the crack plane) and OUT/<run>/history.csv. Standard library only."""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from script_exit import InputError  # noqa: E402

TEXT = {"calibration"}


def csv_rows(out, run, name):
    """The rows of OUT/RUN/NAME (a CSV file with a header row), as dictionaries of strings."""
    path = os.path.join(out, run, name)
    if not os.path.isfile(path):
        raise InputError(f"{path}: missing (run `make` first)")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def row(out, run):
    """The run's row with numbers as floats; a time of -1 (not reached in the run) becomes None."""
    rows = csv_rows(out, run, "row.csv")
    if len(rows) != 1:
        path = os.path.join(out, run, "row.csv")
        raise InputError(f"{path}: expected one row, found {len(rows)}")
    r = {}
    for key, value in rows[0].items():
        r[key] = value if key in TEXT else float(value)
        if key.endswith("_s") and key not in TEXT and r[key] < 0:
            r[key] = None
    r["run"] = run
    return r


def history(out, run):
    """(time after the arrival [s], crack advance [m]) at every step where the count of broken crossing pairs changed."""
    return [(float(r["time_after_arrival_s"]), float(r["advance_m"])) for r in csv_rows(out, run, "history.csv")]


def broken_crossing_pairs(out, run):
    """The broken pairs across the crack plane ahead of the tip at the end of the run."""
    rows = csv_rows(out, run, "history.csv")
    return int(rows[-1]["broken_crossing_pairs"]) if rows else 0


def difference(measured, predicted):
    """(measured - predicted) / predicted, None when the run did not reach it."""
    return None if measured is None else (measured - predicted) / predicted


def window(r):
    """The first time after the arrival at which a reflection can reach the tip [s]."""
    return min(r["window_loaded_edges_s"], r["window_left_corners_s"], r["window_right_corners_s"])
