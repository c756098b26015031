"""Shared reading of the Kalthoff-Winkler case outputs (check_case.py, report_case.py).

A run folder OUT/RUN/ holds points.vtp, run/ and post/. Everything comes from these files: the
crack angles from summary.json (`crack_angles`, postprocess/README.md), the material from the
resolved scene echoed there, the timings from run_info.json.
"""
import functools
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
import mppm_outputs  # noqa: E402
from elastic_waves import rayleigh_speed  # noqa: E402,F401  (for the scripts)
from mppm_outputs import RunOutputError  # noqa: E402,F401  (the readers' error, for the scripts)
import case_runs  # noqa: E402
from case_runs import energy_rows, frames, run_info  # noqa: E402,F401  (for the scripts)


def summary(out, run):
    """The run's summary.json, with the plate's mirror line added (`mirror_line_y_m`)."""
    run_summary = case_runs.summary(out, run)
    run_summary["mirror_line_y_m"] = mirror_line_y(out, run)
    return run_summary


@functools.lru_cache(maxsize=None)
def crack_path_rows(out, run):
    """The rows of the run's crack-arrival table (run/crack_path.csv), read once per run: the
    mirror line and each notch's crack front read them (a 3-D run's table has every plane's
    arrivals)."""
    return tuple(mppm_outputs.read_csv_rows(os.path.join(out, run, "run", "crack_path.csv")))


def mirror_line_y(out, run):
    """The height half-way between the two notches: the mean of the lowest and the highest point
    damaged at the start (the notches' pre-crack) in the run's crack-arrival table. The struck
    edge lies between the notches, and the case is symmetric about this line."""
    heights = [float(row["y_m"]) for row in crack_path_rows(out, run) if float(row["time_s"]) == 0]
    if not heights:
        raise RunOutputError(f"{os.path.join(out, run, 'run', 'crack_path.csv')}: no pre-crack point at t = 0")
    return (min(heights) + max(heights)) / 2


def cracks_by_tip(run_summary):
    """{'upper' | 'lower': [entries of crack_angles leaving that notch's tip]}."""
    out = {"upper": [], "lower": []}
    for entry in run_summary.get("crack_angles") or []:
        out[tip_side(entry, run_summary)].append(entry)
    return out


def outward(entry, run_summary):
    """Whether a crack runs toward the unstruck side: the upper notch's up (counter-clockwise,
    positive), the lower one's down."""
    return (entry["signed_angle_deg"] > 0) == (tip_side(entry, run_summary) == "upper")


def main_cracks(run_summary):
    """The crack of each notch the case is about, {'upper' | 'lower': entry}: of the cracks that
    leave the tip toward the unstruck side (the mode-I crack of the experiment), the one fitted
    through the most points. A tip may also shed damage toward the struck block (where the block
    is sheared off); report_case.py lists those too."""
    best = {}
    for side, entries in cracks_by_tip(run_summary).items():
        candidates = [e for e in entries if outward(e, run_summary)]
        if candidates:
            best[side] = max(candidates, key=lambda e: e["points"])
    return best


def tip_side(entry, run_summary):
    """'upper' or 'lower' notch: the tip above or below the plate's mirror line."""
    return "upper" if entry["tip_m"][1] > run_summary["mirror_line_y_m"] else "lower"


def spacing_mm(run_summary):
    return run_summary["spacing_m"] * 1e3


def model(run_summary):
    return "micro-polar" if "micropolar" in run_summary.get("effects", []) else "non-polar"


def crack_front(out, run, entry, spacing, horizon):
    """The front of one notch's crack from the run's crack-arrival table (run/crack_path.csv: when
    each point's damage reached the crack threshold): the arrivals after t = 0 within two horizons
    of the fitted line, from the tip to the ring's outer radius, that the crack reaches from the tip
    through links of up to 2.3 dx (the crack metrics' links; damage that appears ahead, unconnected,
    joins when the crack reaches it), as (time joined, distance along the line) in time order. The
    postprocessor's crack metrics follow one crack from one pre-crack (the crack-branching plate);
    the two notches of this plate need one front each."""
    tip, direction = entry["tip_m"], entry["fit_direction"]
    candidates = []
    for row in crack_path_rows(out, run):
        t = float(row["time_s"])
        rel = (float(row["x_m"]) - tip[0], float(row["y_m"]) - tip[1])
        along = rel[0] * direction[0] + rel[1] * direction[1]
        across = abs(rel[0] * direction[1] - rel[1] * direction[0])
        if t > 0 and 0 <= along <= entry["range_to_m"] and across <= 2 * horizon:
            candidates.append((t, rel, along))
    candidates.sort()
    link = 2.3 * spacing
    joined, front, waiting = [(0.0, 0.0)], [], []
    for t, rel, along in candidates:
        waiting.append((rel, along))
        grew = True
        while grew:  # join every waiting point the crack now reaches
            grew = False
            for point in list(waiting):
                if any(math.dist(point[0], j) <= link for j in joined):
                    waiting.remove(point)
                    joined.append(point[0])
                    front.append((t, point[1]))
                    grew = True
    return front


def front_metrics(front, spacing):
    """Start time (the first arrival more than 2 dx along the line) and the largest speed of the
    front over an advance of at least 3 dx (shorter advances are the lattice's quantization)."""
    start = next((t for t, s in front if s > 2 * spacing), None)
    records = []  # the front's new farthest points, in time order
    for t, s in front:
        if not records or s > records[-1][1]:
            records.append((t, s))
    speed = None
    for k, (t, s) in enumerate(records):
        j = max((i for i in range(k) if s - records[i][1] >= 3 * spacing), default=None)
        if j is not None and t > records[j][0]:
            v = (s - records[j][1]) / (t - records[j][0])
            speed = v if speed is None or v > speed else speed
    return start, speed
