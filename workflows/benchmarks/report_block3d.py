#!/usr/bin/python3
"""The 3-D side-by-side table (results_3d.md) from run_block3d.py's and run_lammps.py --benchmark
block's CSVs: bond updates per second of mppm's 3-D block at each effect set against LAMMPS
peri/lps and peri/pmb on the same lattice, at equal thread / rank counts, with the targets marked
(non-polar >= 5x peri/lps, micro-polar + damage >= 1.5x peri/pmb, the full model >= 1x peri/pmb),
and the start-up against the loop (the start-up in time steps: target <= 10); then the
crack-branching plate's 500-step runs (case plate-500): the whole run's two-thread efficiency,
start-up included (target >= 90 %).

With INSTRUCTIONS.csv (count_instructions.py --block-scene), also the instructions per bond update
of each effect set on a 20^3 block of the same lattice.

usage: report_block3d.py MPPM.csv LAMMPS.csv OUT.md [INSTRUCTIONS.csv]
"""
import csv
import datetime
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import atomic_open  # noqa: E402
from script_exit import InputError, run_main  # noqa: E402

TARGETS = [("none", "block-lammps-lps", 5.0), ("micropolar+damage", "block-lammps-pmb", 1.5),
           ("micropolar+damage+viscoplasticity", "block-lammps-pmb", 1.0)]
START_UP_STEPS = 10.0
WHOLE_RUN_EFFICIENCY = 0.9


def read(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}")


def phase_seconds(r):
    """The start-up's two estimates, from runs that recorded them (empty for older CSV files)."""
    if not r.get("step_estimate_seconds"):
        return ""
    return f"{r['step_estimate_seconds']}, {r['mode_naming_seconds']}"


def start_up_steps(r):
    return float(r["start_up_seconds"]) / (float(r["wall_seconds"]) / float(r["steps"]))


def plate_lines(plate):
    """The crack-branching plate's whole runs at each thread count and the two-thread efficiency."""
    if not plate:
        return []
    first = next(iter(plate.values()))
    lines = ["", f"The crack-branching plate ({first['points']} points, {first['bonds']} bonds, {first['effects']}), "
             f"{first['steps']} steps; each row is the fastest whole run of its repeats.", "",
             "| threads | whole run [s] | start-up [s] | of it: the step's estimate, the mode's naming [s] | loop [s] "
             "| start-up in steps |", "|---|---|---|---|---|---|"]
    for t, r in sorted(plate.items()):
        lines.append(f"| {t} | {r['run_seconds']} | {r['start_up_seconds']} | {phase_seconds(r)} | {r['wall_seconds']} | "
                     f"{start_up_steps(r):.0f} |")
    if 1 in plate and 2 in plate:
        efficiency = float(plate[1]["run_seconds"]) / (2.0 * float(plate[2]["run_seconds"]))
        loop = float(plate[1]["wall_seconds"]) / (2.0 * float(plate[2]["wall_seconds"]))
        lines += ["", "| target | measured | met |", "|---|---|---|",
                  f"| whole-run two-thread efficiency >= {100 * WHOLE_RUN_EFFICIENCY:.0f} % | {100 * efficiency:.1f} % "
                  f"(the loop alone {100 * loop:.1f} %) | {'yes' if efficiency >= WHOLE_RUN_EFFICIENCY else 'no'} |",
                  f"| start-up <= {START_UP_STEPS:g} steps | "
                  + ", ".join(f"{start_up_steps(r):.0f} steps at {t} thread{'s' if t > 1 else ''}"
                              for t, r in sorted(plate.items()))
                  + f" | {'yes' if all(start_up_steps(r) <= START_UP_STEPS for r in plate.values()) else 'no'} |"]
    return lines


def instruction_lines(rows):
    """Instructions per bond update of each effect set (callgrind, 1 thread, inside the time step)."""
    if not rows:
        return []
    first = rows[0]
    none = next((float(r["instructions_per_bond_update"]) for r in rows if r["effects"] == "none"), None)
    lines = ["", f"Instructions per bond update inside the time step (callgrind, 1 thread, {first['steps']} steps of a "
             f"20^3 block of the same lattice, {first['bonds']} bonds; count_instructions.py --block-scene): the same "
             "for every run of the same binary. Counted on a build for x86-64-v3 (valgrind 3.19 cannot run the "
             "AVX-512 of the timed build).", "",
             "| effects | instructions per bond update | relative to none |", "|---|---|---|"]
    for r in rows:
        per = float(r["instructions_per_bond_update"])
        lines.append(f"| {r['effects']} | {per:.1f} | {per / none:.2f} |" if none else f"| {r['effects']} | {per:.1f} | |")
    return lines


def main(argv):
    if len(argv) not in (3, 4):
        raise InputError(__doc__.strip().splitlines()[-1])
    rows, lammps = read(argv[0]), read(argv[1])
    mppm = [r for r in rows if r["case"] != "plate-500"]
    plate = {int(r["threads"]): r for r in rows if r["case"] == "plate-500"}
    stamp = datetime.datetime.fromtimestamp(os.path.getmtime(argv[0]), datetime.timezone.utc)
    lines = ["# 3-D block: mppm side by side with LAMMPS PERI", "",
             f"Written by `make block-3d` (report_block3d.py); mppm measured up to {stamp:%Y-%m-%d %H:%M} UTC. "
             "The same 60^3 simple-cubic lattice in both codes (dx = 1 mm, horizon 2.05 dx, 216 000 points, "
             f"{mppm[0]['bonds']} bonds from both ends), 100 steps, energies at the first and the last step in both "
             "(LAMMPS's thermo output, mppm's energy rows); threads are MPI ranks for LAMMPS. The loop "
             "time is the time integration only (LAMMPS's Loop time). The two codes ran in the same sweeps, taking "
             "turns (run_block3d.py); each row is the fastest of its sweeps.", "",
             "| code, model | threads | loop [s] | bond updates/s | start-up [s] | of it: the step's estimate, "
             "the mode's naming [s] | start-up in steps |",
             "|---|---|---|---|---|---|---|"]
    for r in mppm:
        per_step = float(r["wall_seconds"]) / float(r["steps"])
        lines.append(f"| mppm, {r['effects']} | {r['threads']} | {r['wall_seconds']} | "
                     f"{float(r['bond_updates_per_second']):.3g} | {r['start_up_seconds']} | {phase_seconds(r)} | "
                     f"{float(r['start_up_seconds']) / per_step:.0f} |")
    for r in lammps:
        lines.append(f"| LAMMPS, {r['effects']} | {r['threads']} | {r['wall_seconds']} | "
                     f"{float(r['bond_updates_per_second']):.3g} | | | |")
    lines += ["", "| target | threads | ratio | met |", "|---|---|---|---|"]
    for effects, case, target in TARGETS:
        for r in (x for x in mppm if x["effects"] == effects):
            other = next((x for x in lammps if x["case"] == case and x["threads"] == r["threads"]), None)
            if other is None:
                continue
            ratio = float(r["bond_updates_per_second"]) / float(other["bond_updates_per_second"])
            lines.append(f"| {effects} >= {target:g}x {other['effects']} | {r['threads']} | {ratio:.2f} | "
                         f"{'yes' if ratio >= target else 'no'} |")
    for r in mppm:
        steps = start_up_steps(r)
        lines.append(f"| start-up <= {START_UP_STEPS:g} steps, {r['effects']} | {r['threads']} | {steps:.0f} steps | "
                     f"{'yes' if steps <= START_UP_STEPS else 'no'} |")
    lines += plate_lines(plate)
    if len(argv) == 4:
        lines += instruction_lines(read(argv[3]))
    with atomic_open(argv[2]) as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {argv[2]}")
    return 0


if __name__ == "__main__":
    run_main(main)
