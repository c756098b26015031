#!/usr/bin/python3
"""Instructions per bond update of each plate effect set, counted by callgrind.

usage: count_instructions.py OUT.csv --bin BIN [--solve-bin BIN] --work DIR --scene plate.yaml [--steps 40]
       count_instructions.py OUT.csv --bin BIN [--solve-bin BIN] --work DIR --block-scene block.yaml [--steps 40]

Wall times on a shared 2-core machine move by 10-40 % from run to run; an instruction count
does not (it is the same for every run of the same binary, to a few parts in 1e4 from the
allocator and the file system). So the cost of an effect, and whether an effect that is on but
inactive costs more than the effect off, are also stated as instructions: valgrind
--tool=callgrind, 1 thread, collecting inside the time step only (the time loop: no
reading, no families, no critical step, no final files), over --steps steps of the plate
(40 by default, which is before any bond breaks: the count is that of the force kernels,
the bond-work bookkeeping and the integrator, not of breakage events). The energy rows come
every 0.5 us (20 steps) as in the timed runs, so steps with and without energies are mixed in
the same proportion.

With --block-scene, the same for the 3-D block's effect sets (run_block3d.py: none, micropolar,
micropolar+damage, the full model) on a 20^3 block of its lattice (scenes/block20.geo: 8000
points; the per-bond count of the 60^3 block's kernels, with more of its points at faces), no
boundary condition and energy rows at the first and last step only, as in the side by side.

Writes OUT.csv with case,effects,steps,bonds,instructions,instructions_per_bond_update.
Exit codes: 0 written; 2 bad input; 1 a run failed.
"""

import argparse
import os
import re
import shutil
import subprocess

import run_block3d
import run_mppm
from mppm_outputs import run_info  # tools/, on the path run_mppm sets
from script_exit import InputError, RunError, run_main

COLUMNS = ["case", "effects", "steps", "bonds", "instructions", "instructions_per_bond_update"]
# The functions whose calls are counted (demangled names, callgrind wildcards): the two halves of a
# time step (ExplicitDynamics::step is inline and calls them, with only the run's test hooks, which
# do nothing in these runs, between them).
TIME_STEP = ["mppm::solver::ExplicitDynamics::advance_to_forces*", "mppm::solver::ExplicitDynamics::complete_step*"]


def count(args, scene, points, effects, sets, run_dir):
    """Instructions callgrind collected inside the time step of one run, and its run_info."""
    shutil.rmtree(run_dir, ignore_errors=True)
    os.makedirs(os.path.dirname(run_dir), exist_ok=True)
    log = run_dir + ".callgrind.log"
    dt = 0.025e-6  # set below, so that the step count is exact
    end = args.steps * dt
    command = ["valgrind", "--tool=callgrind"] + [f"--toggle-collect={f}" for f in TIME_STEP] + [
               "--callgrind-out-file=/dev/null",
               f"--log-file={log}", os.path.join(args.solve_bin or args.bin, "mppm-solve"), scene, "--points", points,
               "-o", run_dir, "--force", "--quiet", "--threads", "1",
               "--set", "effects=[" + ", ".join(effects) + "]", "--set", f"time.step={dt!r}", "--set", f"time.end={end!r}",
               "--set", f"output.interval={end!r}"]
    for s in sets:
        command += ["--set", s]
    print("+ " + " ".join(command), flush=True)
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        raise RunError(f"{run_dir}: callgrind run failed with exit code {result.returncode}:\n"
                                f"{result.stderr.strip()}")
    with open(log) as stream:
        text = stream.read()
    collected = re.search(r"Collected\s*:\s*(\d+)", text)
    if not collected:
        raise RunError(f"{log}: callgrind reported no 'Collected' count")
    info = run_info(run_dir)
    if info["steps"] != args.steps:
        raise RunError(f"{run_dir}: ran {info['steps']} steps, expected {args.steps}")
    return int(collected.group(1)), info


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("--bin", required=True, help="where mppm-preprocess (and mppm-solve) are")
    parser.add_argument("--solve-bin", help="where the mppm-solve to count is, if not in --bin (the Makefile's "
                        "x86-64-v3 build: valgrind 3.19 cannot run AVX-512)")
    parser.add_argument("--work", required=True)
    parser.add_argument("--scene", help="the plate scene (workflows/benchmarks/scenes/plate.yaml)")
    parser.add_argument("--block-scene", help="the 3-D block scene (workflows/benchmarks/scenes/block.yaml)")
    parser.add_argument("--steps", type=int, default=40)
    args = parser.parse_args(argv)
    if args.steps < 1:
        raise InputError("--steps: expected a positive integer")
    if (args.scene is None) == (args.block_scene is None):
        raise InputError("expected one of --scene (the plate) and --block-scene (the 3-D block)")
    if not shutil.which("valgrind"):
        raise InputError("valgrind: not found (Debian package 'valgrind'; make installs it)")
    rows = block_rows(args) if args.block_scene else plate_rows(args)
    run_mppm.write_csv(args.csv, COLUMNS, rows)
    return 0


def row(case, name, instructions, info):
    return {"case": case, "effects": name, "steps": info["steps"], "bonds": info["bonds"],
            "instructions": instructions,
            "instructions_per_bond_update": f"{instructions / (info['bonds'] * info['steps']):.2f}"}


def plate_rows(args):
    points = os.path.join(args.work, "points.vtp")
    run_mppm.preprocess(args, args.scene, points, [])
    cases = dict((name, (effects, [])) for name, effects in run_mppm.PLATE_SETS.items())
    cases.update(run_mppm.INACTIVE_SETS)
    cases.update(run_mppm.REGION_SETS)
    rows = []
    for name, (effects, sets) in cases.items():
        run_dir = os.path.join(args.work, name.replace("(", "-").replace(")", ""))
        instructions, info = count(args, args.scene, points, effects, sets, run_dir)
        rows.append(row("plate", name, instructions, info))
    return rows


def block_rows(args):
    # Energy rows at the first and last step only, as in the side by side (run_block3d.py).
    sets = ["geometry.file=block20.geo", "boundary_conditions=[]", "output.load_interval=5us"]
    points = os.path.join(args.work, "block20", "points.vtp")
    run_mppm.preprocess(args, args.block_scene, points, sets)
    rows = []
    for name, effects in run_block3d.EFFECT_SETS.items():
        run_dir = os.path.join(args.work, "block20", name.replace("+", "-"))
        instructions, info = count(args, args.block_scene, points, effects, sets, run_dir)
        rows.append(row("block20-3d", name, instructions, info))
    return rows


if __name__ == "__main__":
    run_main(main)
