"""How close mppm's run estimate comes to the runs (mppm-solve --estimate against the same runs
measured): wall time (run_info.json wall_seconds) and peak memory (/usr/bin/time's maximum resident
set). Five cases of different sizes, dimensions and effect sets; each is estimated, then run.
Time it on an idle machine: the script records the load average before and after, and marks the
table busy when either is above 0.5 per core.

usage: check_estimates.py BIN WORK OUT.md
"""
import json
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from run_timing import estimate_numbers, load_average, run  # noqa: E402
from script_exit import InputError, run_main  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

# (name, scene relative to the repository, threads, extra --set)
CASES = [
    ("quickstart plate, 2-D micropolar", "workflows/quickstart/scene.yaml", 1, []),
    ("benchmark plate, 2-D micropolar + damage", "workflows/benchmarks/scenes/plate.yaml", 2,
     ["effects=[micropolar,damage]", "time.end=25us"]),
    ("benchmark plate, 2-D micropolar + viscoplasticity", "workflows/benchmarks/scenes/plate.yaml", 1,
     ["effects=[micropolar,viscoplasticity]", "time.end=15us"]),
    ("shear band, 2-D micropolar + viscoplasticity, 1/4 of the travel", "workflows/shear-band/scene.yaml", 1,
     ["time.end=0.05s"]),
    ("3-D notched bar, non-polar + damage", "tests/stability/scenes/notched_impact_3d.yaml", 2,
     ["time.end=20us"]),
]


def main(argv):
    if len(argv) != 3:
        raise InputError("usage: check_estimates.py BIN WORK OUT.md")
    bin_dir, work, out = argv
    os.makedirs(work, exist_ok=True)
    cores = os.cpu_count() or 1
    load_before = load_average()
    rows = []
    for k, (name, scene, threads, sets) in enumerate(CASES):
        scene = os.path.join(ROOT, scene)
        set_args = [a for s in sets for a in ("--set", s)]
        points = os.path.join(work, f"case{k}.vtp")
        run([os.path.join(bin_dir, "mppm-preprocess"), scene, "-o", points, "--quiet"] + set_args)
        estimate = run([os.path.join(bin_dir, "mppm-solve"), scene, "--points", points, "--estimate",
                        "--threads", str(threads)] + set_args).stdout
        predicted_seconds, predicted_mib = estimate_numbers(estimate)
        run_dir = os.path.join(work, f"case{k}-run")
        timed = run(["/usr/bin/time", "-f", "peak_rss_kib %M", os.path.join(bin_dir, "mppm-solve"), scene,
                     "--points", points, "-o", run_dir, "--force", "--quiet", "--threads", str(threads)] + set_args)
        peak = re.search(r"peak_rss_kib (\d+)", timed.stderr)
        with open(os.path.join(run_dir, "run_info.json")) as f:
            info = json.load(f)
        measured_mib = int(peak.group(1)) / 1024 if peak else float("nan")
        rows.append((name, threads, info["points"], info["bonds"], info["steps"], predicted_seconds,
                     info["wall_seconds"], predicted_mib, measured_mib))
    load_after = load_average()
    busy = max(load_before, load_after) > 0.5 * cores
    lines = ["| case | threads | points | bonds | steps | predicted s | measured s | ratio | predicted MiB | "
             "measured MiB | ratio |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    worst_time = worst_memory = 0.0
    for name, threads, points, bonds, steps, ps, ms, pm, mm in rows:
        worst_time = max(worst_time, abs(ps / ms - 1))
        worst_memory = max(worst_memory, abs(pm / mm - 1))
        lines.append(f"| {name} | {threads} | {points} | {bonds} | {steps} | {ps:.3g} | {ms:.3g} | {ps / ms:.2f} | "
                     f"{pm:.0f} | {mm:.0f} | {pm / mm:.2f} |")
    lines += ["", f"Largest deviation: wall time {100 * worst_time:.0f} % (target 30 %), peak memory "
              f"{100 * worst_memory:.0f} % (target 20 %). Load average {load_before:.2f} before, "
              f"{load_after:.2f} after ({cores} cores)" + (": BUSY, not to be published" if busy else ".")]
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    run_main(main)
