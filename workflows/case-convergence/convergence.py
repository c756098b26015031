"""Case-level convergence and cost (README.md), the runs: the reference cases at a sequence of
spacings and two horizon factors, each run estimated first (mppm-solve --estimate), then timed on one
thread with the machine watched (the load average and the CPU time other processes took during the
run), then postprocessed; the case metrics from summary.json. The report and the check read its
tables (convergence_report.py), so that a change to them reruns nothing.

usage:
  convergence.py run BIN CASE OUT.csv WORK [--quick]   run CASE's levels -> OUT.csv (one row per run)
"""
import csv
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from run_timing import OtherWork, estimate_numbers, run  # noqa: E402
from script_exit import InputError, RunError, run_main  # noqa: E402

# A run counts as taken on a busy machine when other processes took more than this fraction of one
# core during it (the run itself uses one thread of the two cores).
BUSY_FRACTION = 0.10

# Per case: its scene, the spacings [mm] and horizon factors of the study (the case's own factor
# first: its series gives the reference), the quick form's spacings, and the metrics of summary.json
# (key, label, unit scale, unit).
CASES = {
    "shear-band": {
        "scene": "workflows/shear-band/scene.yaml",
        "spacings_mm": [5.0, 2.5, 1.25],
        "factors": [2.05, 3.05],
        "quick_spacings_mm": [5.0],
        "case_step": (7e-6, 2.5),  # the scene's time step [s] at its spacing [mm]
        "metrics": [("peak_load_N", "peak load", 1.0, "N"),
                    ("shear_band_angle_deg", "band angle", 1.0, "deg"),
                    ("shear_band_width_m", "band width", 1e3, "mm")],
    },
    "crack-branching": {
        "scene": "workflows/crack-branching/scene.yaml",
        "spacings_mm": [1.0, 0.5, 0.25],
        "factors": [4.05, 3.05],
        "quick_spacings_mm": [1.0],
        "case_step": (0.025e-6, 0.5),
        "metrics": [("crack_start_time_s", "crack start", 1e6, "us"),
                    ("crack_branch_time_s", "branching", 1e6, "us"),
                    ("crack_end_time_s", "crack end", 1e6, "us"),
                    ("crack_tip_speed_max_m_per_s", "largest tip speed", 1.0, "m/s")],
    },
}

COLUMNS = ["case", "spacing_m", "horizon_factor", "points", "bonds", "steps", "time_step_s", "wall_seconds", "predicted_seconds",
           "peak_mib", "predicted_mib", "load_before", "load_after", "other_cpu_seconds", "busy"]


def metric_keys(case):
    return [m[0] for m in CASES[case]["metrics"]]


def run_level(bin_dir, case, spacing_mm, factor, work):
    """One run of CASE at the spacing and horizon factor: its row."""
    scene = os.path.join(ROOT, CASES[case]["scene"])
    name = f"dx{spacing_mm:g}mm-h{factor:g}"
    folder = os.path.join(work, case, name)
    os.makedirs(folder, exist_ok=True)
    # The case's time step scaled with the spacing: the same Courant number at every level (the
    # crack case's step is a tenth of its critical one, for the event times' resolution).
    # Where that step is above the level's critical step (the critical step does not fall with the
    # spacing everywhere: on the coarse shear-band lattice another mode limits it) the solver's own
    # choice, time.step=auto, is taken instead; the row keeps the step used.
    step, at_mm = CASES[case]["case_step"]
    sets = [f"geometry.spacing={spacing_mm:g}mm", f"geometry.horizon_factor={factor:g}"]
    set_args = [a for s in sets for a in ("--set", s)]
    points = os.path.join(folder, "points.vtp")
    run([os.path.join(bin_dir, "mppm-preprocess"), scene, "-o", points, "--quiet"] + set_args)
    estimate_command = [os.path.join(bin_dir, "mppm-solve"), scene, "--points", points, "--estimate", "--threads", "1"]
    scaled = ["--set", f"time.step={step * spacing_mm / at_mm:.6g}s"]
    try:
        estimate = run(estimate_command + set_args + scaled).stdout
        set_args += scaled
    except RunError as e:
        if "above the critical step" not in str(e):
            raise
        set_args += ["--set", "time.step=auto"]
        estimate = run(estimate_command + set_args).stdout
    predicted_seconds, predicted_mib = estimate_numbers(estimate)
    run_dir = os.path.join(folder, "run")
    with OtherWork() as other:
        timed = run(["/usr/bin/time", "-f", "peak_rss_kib %M", os.path.join(bin_dir, "mppm-solve"), scene, "--points",
                     points, "-o", run_dir, "--force", "--quiet", "--threads", "1"] + set_args)
    post = os.path.join(folder, "post")
    run([os.path.join(bin_dir, "mppm-postprocess"), run_dir, "-o", post, "--force", "--quiet"])
    with open(os.path.join(run_dir, "run_info.json")) as f:
        info = json.load(f)
    with open(os.path.join(post, "summary.json")) as f:
        summary = json.load(f)
    peak = re.search(r"peak_rss_kib (\d+)", timed.stderr)
    wall = float(info["wall_seconds"])
    row = {"case": case, "spacing_m": spacing_mm * 1e-3, "horizon_factor": factor, "points": info["points"],
           "bonds": info["bonds"], "steps": info["steps"], "time_step_s": info["time_step_s"], "wall_seconds": wall,
           "predicted_seconds": predicted_seconds, "peak_mib": int(peak.group(1)) / 1024 if peak else float("nan"),
           "predicted_mib": predicted_mib, "load_before": other.load_before, "load_after": other.load_after,
           "other_cpu_seconds": other.seconds, "busy": int(other.seconds > BUSY_FRACTION * wall)}
    for key in metric_keys(case):
        value = summary.get(key)
        row[key] = "" if value is None else float(value)
    print(f"{case} {name}: {wall:.1f} s (estimate {predicted_seconds:.3g} s), other processes "
          f"{other.seconds:.1f} CPU s" + (" BUSY" if row["busy"] else ""), flush=True)
    return row


def run_case(bin_dir, case, out_csv, work, quick):
    if case not in CASES:
        raise InputError(f"unknown case {case!r} (expected one of {', '.join(CASES)})")
    c = CASES[case]
    spacings = c["quick_spacings_mm"] if quick else c["spacings_mm"]
    rows = [run_level(bin_dir, case, dx, h, work) for h in c["factors"] for dx in spacings]
    temporary = out_csv + ".part"
    with open(temporary, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS + metric_keys(case))
        writer.writeheader()
        writer.writerows(rows)
    os.replace(temporary, out_csv)  # never a half-written table
    return 0


def main(argv):
    if len(argv) >= 5 and argv[0] == "run":
        return run_case(argv[1], argv[2], argv[3], argv[4], "--quick" in argv[5:])
    raise InputError(__doc__.strip())


if __name__ == "__main__":
    run_main(main)
