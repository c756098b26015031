#!/usr/bin/python3
"""Runs mppm-solve on the benchmark scenes and appends benchmark rows to a CSV.

Owns: the effect sets of the plate (none, micropolar, micropolar+damage,
micropolar+viscoplasticity, all) at each thread count, the inactive-effect runs (damage with an
enormous G_cr, viscoplasticity with an unreachable cohesion) and their bitwise comparison with
the run without the effect, damage limited to a region around the crack path, the 3-D block, per-run peak memory (GNU time), and the CSV rows
  case,effects,threads,points,bonds,steps,wall_seconds,bond_updates_per_second,peak_memory_bytes
(the columns of run_lammps.py) plus run_seconds (the whole mppm-solve run: reading the points,
families, critical step, time loop, files). wall_seconds is the time loop only
(run_info.json's loop_wall_seconds, the counterpart of LAMMPS's "Loop time") and
bond_updates_per_second = bonds * steps / wall_seconds. Standard library only.

Exit codes: 0 success; 2 bad input; 1 a run failed or an inactive effect changed the results.
"""

import argparse
import csv
import filecmp
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import atomic_open, run_info  # noqa: E402
from script_exit import InputError, RunError, run_main  # noqa: E402

CSV_COLUMNS = ["case", "effects", "threads", "points", "bonds", "steps", "wall_seconds",
               "bond_updates_per_second", "peak_memory_bytes", "run_seconds", "wall_seconds_max", "repeats"]

# The plate's effect sets and the two inactive variants.
PLATE_SETS = {
    "none": [],
    "micropolar": ["micropolar"],
    "micropolar+damage": ["micropolar", "damage"],
    "micropolar+viscoplasticity": ["micropolar", "viscoplasticity"],
    "all": ["micropolar", "damage", "viscoplasticity", "gravity"],
    "micropolar+pore_fluid": ["micropolar", "pore_fluid"],
}
# Effect on but inactive: the same run as "micropolar", bit for bit.
INACTIVE_SETS = {
    "micropolar+damage(inactive)": (["micropolar", "damage"],
                                    ["material.damage.critical_energy_release_rate=1e12 N/m"]),
    "micropolar+viscoplasticity(inactive)": (["micropolar", "viscoplasticity"],
                                             ["material.viscoplasticity.cohesion=1e15 Pa"]),
}


# Damage limited to a band around the crack path (the notch tip at x = 50 mm, y = 20 mm; the
# branches of the crack-branching case stay within 10 mm of the mid-line): the cost saving of a
# region, measured against "micropolar+damage".
REGION_SETS = {
    "micropolar+damage(region)": (["micropolar", "damage"],
                                  ["material.damage.region={box: [[45 mm, 8 mm], [101 mm, 32 mm]]}"]),
}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description="Run the mppm benchmark cases and append CSV rows.")
    parser.add_argument("csv", help="CSV file to write (replaced)")
    parser.add_argument("--bin", required=True, help="directory of mppm-preprocess and mppm-solve")
    parser.add_argument("--work", required=True, help="directory for points files and run directories")
    parser.add_argument("--scenes", required=True, help="directory of plate.yaml and block.yaml")
    parser.add_argument("--threads", default="1,2", help="thread counts of the plate runs (default 1,2)")
    parser.add_argument("--block-threads", default="2", help="thread counts of the 3-D block (default 2)")
    parser.add_argument("--plate-set", action="append", default=[],
                        help="extra --set of every plate run (e.g. time.end=1us for a smoke test)")
    parser.add_argument("--block-set", action="append", default=[],
                        help="extra --set of the block run (e.g. geometry.spacing=5mm)")
    parser.add_argument("--skip-block", action="store_true", help="no 3-D block")
    parser.add_argument("--plate-cases", help="only these plate cases (comma-separated names of PLATE_SETS); "
                        "then no inactive, region, crack-branching or block runs")
    parser.add_argument("--repeats", type=int, default=3,
                        help="runs of each plate case, its thread counts taking turns; a row keeps the "
                             "fastest time loop and the slowest beside it (default 3)")
    parser.add_argument("--crack-scene", help="the crack-branching case's scene.yaml: its base run, "
                        "shortened to --crack-end, with its own output, at the largest thread count")
    parser.add_argument("--crack-end", default="60 us", help="time.end of that run (default 60 us: 2400 steps)")
    args = parser.parse_args(argv)
    try:
        args.threads = [int(t) for t in args.threads.split(",") if t.strip()]
        args.block_threads = [int(t) for t in args.block_threads.split(",") if t.strip()]
    except ValueError:
        raise InputError("--threads / --block-threads: expected comma-separated positive integers")
    if args.repeats < 1:
        raise InputError("--repeats: expected a positive integer")
    if min(args.threads + args.block_threads, default=0) < 1:
        raise InputError("--threads / --block-threads: expected positive integers")
    for tool in ("mppm-preprocess", "mppm-solve"):
        if not os.access(os.path.join(args.bin, tool), os.X_OK):
            raise InputError(f"{os.path.join(args.bin, tool)}: not found (build mppm first: make -C workflows build)")
    if not shutil.which("/usr/bin/time"):
        raise InputError("/usr/bin/time: not found (Debian package 'time'; make installs it)")
    return args


def run(command, what):
    print("+ " + " ".join(command), flush=True)
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        raise RunError(f"{what} failed with exit code {result.returncode}:\n{result.stderr.strip()}")
    return result


def preprocess(args, scene, points, extra_sets):
    """The points file of the scene, made again when the preprocessor or a file of the scene's folder
    (the scene, its geometry) is newer than it: a points file of an earlier preprocessor may number
    its points otherwise (a slower run) or lack what the solver now reads."""
    binary = os.path.join(args.bin, "mppm-preprocess")
    folder = os.path.dirname(os.path.abspath(scene))
    inputs = [binary] + [os.path.join(folder, name) for name in os.listdir(folder)]
    if os.path.exists(points) and os.path.getmtime(points) >= max(os.path.getmtime(path) for path in inputs):
        return
    os.makedirs(os.path.dirname(points), exist_ok=True)
    # mppm-preprocess writes its file atomically: a points file is there only when complete.
    command = [os.path.join(args.bin, "mppm-preprocess"), scene, "-o", points]
    for s in extra_sets:
        command += ["--set", s]
    run(command, f"mppm-preprocess {scene}")


def write_csv(path, columns, rows):
    """The rows as a CSV file, written atomically (never half-written)."""
    with atomic_open(path, newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=columns)
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {path} ({len(rows)} rows)")


def solve(args, scene, points, run_dir, effects, threads, extra_sets):
    """One mppm-solve run under GNU time; returns run_info.json and the peak RSS in bytes."""
    sets = ["effects=[" + ", ".join(effects) + "]"] + extra_sets
    command = ["/usr/bin/time", "-f", "peak_rss_kib %M", os.path.join(args.bin, "mppm-solve"), scene,
               "--points", points, "-o", run_dir, "--force", "--quiet", "--threads", str(threads)]
    for s in sets:
        command += ["--set", s]
    result = run(command, f"mppm-solve {run_dir}")
    peak = [line for line in result.stderr.splitlines() if line.startswith("peak_rss_kib ")]
    if not peak:
        raise RunError(f"{run_dir}: GNU time printed no peak memory")
    info = run_info(run_dir)
    if info.get("status") != "completed":
        raise RunError(f"{run_dir}: status {info.get('status')}: {info.get('message')}")
    return info, int(peak[-1].split()[1]) * 1024


def fastest_row(case, effects_name, threads, done, key="loop_wall_seconds"):
    """The row of the run in `done` ((run_info, peak) pairs of one case and thread count) fastest by
    `key`, with the slowest loop beside it."""
    info, peak = min(done, key=lambda run: run[0][key])
    slowest = max(run[0]["loop_wall_seconds"] for run in done)
    return row(case, effects_name, threads, info, peak, slowest, len(done))


def row(case, effects_name, threads, info, peak_bytes, slowest_loop=None, repeats=1):
    loop = info["loop_wall_seconds"]
    return {"case": case, "effects": effects_name, "threads": threads, "points": info["points"],
            "bonds": info["bonds"], "steps": info["steps"], "wall_seconds": f"{loop:.4g}",
            "bond_updates_per_second": f"{info['bonds'] * info['steps'] / loop:.4g}",
            "peak_memory_bytes": peak_bytes, "run_seconds": f"{info['wall_seconds']:.4g}",
            "wall_seconds_max": f"{(slowest_loop if slowest_loop is not None else loop):.4g}", "repeats": repeats}


def same_results(a, b):
    """load.csv and the last snapshot of two run directories, byte for byte."""
    if not filecmp.cmp(os.path.join(a, "load.csv"), os.path.join(b, "load.csv"), shallow=False):
        return False, "load.csv differs"
    snaps = sorted(os.listdir(os.path.join(a, "snapshots")))
    if snaps != sorted(os.listdir(os.path.join(b, "snapshots"))) or not snaps:
        return False, "different snapshot lists"
    if not filecmp.cmp(os.path.join(a, "snapshots", snaps[-1]), os.path.join(b, "snapshots", snaps[-1]), shallow=False):
        return False, f"snapshots/{snaps[-1]} differs"
    return True, ""


def main(argv):
    args = parse_arguments(argv)
    rows = []
    plate_scene = os.path.join(args.scenes, "plate.yaml")
    plate_points = os.path.join(args.work, "plate", "points.vtp")
    preprocess(args, plate_scene, plate_points, [])
    # This VM's speed drifts by 10-30 % over minutes, so the thread counts of a case run back to
    # back and take turns over the repeats, and each row keeps the fastest repeat (the one least
    # slowed by the machine) with the slowest beside it: the ratios (2-thread efficiency, effect
    # costs) then compare runs made minutes apart at most.
    def timed(name, effects, sets, check_against=None):
        runs = {threads: [] for threads in args.threads}
        for _ in range(args.repeats):
            for threads in args.threads:
                run_dir = os.path.join(args.work, "plate", name.replace("(", "-").replace(")", "") + f"-{threads}t")
                info, peak = solve(args, plate_scene, plate_points, run_dir, effects, threads, args.plate_set + sets)
                if check_against:
                    reference = os.path.join(args.work, "plate", f"{check_against}-{threads}t")
                    same, why = same_results(run_dir, reference)
                    if not same:
                        raise RunError(f"{name}: an inactive effect changed the results ({why}: {run_dir} vs {reference})")
                runs[threads].append((info, peak))
        for threads in args.threads:
            rows.append(fastest_row("plate", name, threads, runs[threads]))

    # The crack-branching base case is held to an absolute time (10 s), not to a ratio of runs
    # made side by side, so its repeats are spread over the plate runs, one after each plate case:
    # back to back they took a minute, and one slow phase of the VM could hold all of them (12.1-12.6 s
    # in five runs in a row, 9.1-9.4 s before and after).
    plate_cases = ([(name, effects, [], None) for name, effects in PLATE_SETS.items()] +
                   [(name, effects, sets, "micropolar") for name, (effects, sets) in INACTIVE_SETS.items()] +
                   [(name, effects, sets, None) for name, (effects, sets) in REGION_SETS.items()])
    if args.plate_cases:
        chosen = [c.strip() for c in args.plate_cases.split(",") if c.strip()]
        unknown = [c for c in chosen if c not in PLATE_SETS]
        if unknown:
            raise InputError(f"--plate-cases: unknown case(s) {', '.join(unknown)} (expected some of {', '.join(PLATE_SETS)})")
        plate_cases = [(name, PLATE_SETS[name], [], None) for name in chosen]
        args.crack_scene, args.skip_block = None, True
    crack_repeats = args.repeats if args.crack_scene else 0
    if crack_repeats:
        crack_points = os.path.join(args.work, "crack-branching", "points.vtp")
        preprocess(args, args.crack_scene, crack_points, [])
        crack_threads = max(args.threads)
        crack_dir = os.path.join(args.work, "crack-branching", f"base-{crack_threads}t")
    crack_runs = []
    for k in range(max(len(plate_cases), crack_repeats)):
        if k < len(plate_cases):
            timed(*plate_cases[k])
        if k < crack_repeats:
            crack_runs.append(solve(args, args.crack_scene, crack_points, crack_dir, ["micropolar", "damage"],
                                    crack_threads, [f"time.end={args.crack_end}"]))
    if crack_runs:
        info, peak = min(crack_runs, key=lambda run: run[0]["wall_seconds"])  # the target is the whole run's
        rows.append(row("crack-branching-base", "micropolar+damage", crack_threads, info, peak,
                        max(run[0]["loop_wall_seconds"] for run in crack_runs), args.repeats))
    if not args.skip_block:
        block_scene = os.path.join(args.scenes, "block.yaml")
        block_points = os.path.join(args.work, "block", "points.vtp")
        preprocess(args, block_scene, block_points, args.block_set)
        for threads in args.block_threads:
            run_dir = os.path.join(args.work, "block", f"all-{threads}t")
            info, peak = solve(args, block_scene, block_points, run_dir,
                               ["micropolar", "damage", "viscoplasticity"], threads, args.block_set)
            rows.append(row("block-3d", "micropolar+damage+viscoplasticity", threads, info, peak))
            shutil.rmtree(os.path.join(run_dir, "snapshots"), ignore_errors=True)  # 1e6-point snapshots
    write_csv(args.csv, CSV_COLUMNS, rows)
    if args.plate_cases:  # each chosen case against the first, thread count by thread count
        first = plate_cases[0][0]
        for r in rows:
            base = next(b for b in rows if b["effects"] == first and b["threads"] == r["threads"])
            if r is not base:
                print(f"{r['effects']}: {float(r['wall_seconds']) / float(base['wall_seconds']):.3f}x the time loop of {first}"
                      f" on {r['threads']} thread(s)")
    return 0


if __name__ == "__main__":
    run_main(main)
