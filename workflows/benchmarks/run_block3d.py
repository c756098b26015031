#!/usr/bin/python3
"""Runs mppm's 3-D block side by side with LAMMPS's (lammps/make_block_input.py): the same 60^3
simple-cubic lattice (dx = 1 mm, horizon 2.05 dx, 216 000 points, 6 676 552 bonds), 100 steps, at
each effect set (none, micropolar, micropolar+damage, micropolar+damage+viscoplasticity) and
thread count, and writes the CSV rows of run_mppm.py plus the start-up (run_info.json's
start_up_total_seconds). No boundary condition (the families are LAMMPS's exactly; the kernels do
the same arithmetic at rest). Energy rows at the first and the last step only, as LAMMPS computes
its energies only on thermo steps (every 1000: its first and last). With --lammps-inputs (the
directory of make_block_input.py) LAMMPS's peri/lps and peri/pmb run in the same sweeps, their
rows (lammps/run_lammps.py's) going to --lammps-csv. Each repeat is one sweep over every case, the
two codes taking turns (peri/lps beside the non-polar block, peri/pmb between the micro-polar
damage models it is compared with) and the thread counts of a case one after the other: the
fastest run of each case then comes from the same minutes for both codes, and from as many tries,
on a machine whose speed drifts by 10-40 % over minutes. Each row keeps the fastest loop with the
slowest beside it. Then the crack-branching plate for 500 steps at each thread count (case
plate-500), whose rows keep the fastest whole run (run_seconds: start-up, loop and the end), for the
whole run's two-thread efficiency.

usage: run_block3d.py --bin BIN --scenes SCENES --work WORK --csv OUT.csv [--threads 1,2] [--repeats N]
                      [--lammps-inputs DIR --lammps-csv LAMMPS.csv]
"""
import argparse
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lammps"))
import run_lammps  # noqa: E402
from run_mppm import CSV_COLUMNS, fastest_row, preprocess, solve, write_csv  # noqa: E402
from script_exit import InputError, run_main  # noqa: E402

EFFECT_SETS = {
    "none": [],
    "micropolar": ["micropolar"],
    "micropolar+damage": ["micropolar", "damage"],
    "micropolar+damage+viscoplasticity": ["micropolar", "damage", "viscoplasticity"],
}
# One sweep's order: (code, model); LAMMPS's models sit beside the mppm effect sets they are the
# yardstick of.
SWEEP = [("lammps", "lps"), ("mppm", "none"), ("mppm", "micropolar+damage"), ("lammps", "pmb"),
         ("mppm", "micropolar+damage+viscoplasticity"), ("mppm", "micropolar")]
BLOCK_SETS = ["geometry.file=block60.geo", "boundary_conditions=[]", "time.end=5us", "output.interval=5us",
              "output.load_interval=5us"]
# The crack-branching plate (plate.yaml: micro-polar and damage, dx = 0.5 mm, horizon 4.05 dx),
# 500 steps of 0.025 us: the whole run's two-thread efficiency, start-up included.
PLATE_EFFECTS = ["micropolar", "damage"]
PLATE_SETS = ["time.end=12.5us", "output.interval=12.5us"]
PLATE_REPEATS = 5


def fastest_rows(case, name, runs, key):
    """One row per thread count: the run fastest by `key`, with the slowest loop beside it."""
    rows = []
    for t, done in runs.items():
        r = fastest_row(case, name, t, done, key)
        fastest = min(done, key=lambda run: run[0][key])[0]
        r["start_up_seconds"] = f"{fastest['start_up_total_seconds']:.4g}"
        phases = fastest["start_up_seconds"]
        r["step_estimate_seconds"] = f"{phases.get('critical_time_step', 0.0):.4g}"
        r["mode_naming_seconds"] = f"{phases.get('mode_naming', 0.0):.4g}"
        rows.append(r)
    return rows


class LammpsBlock:
    """LAMMPS's block runs (lammps/run_lammps.py) one at a time, for the sweeps."""

    def __init__(self, inputs, threads, csv):
        ranks = ",".join(str(t) for t in threads)
        self.args = run_lammps.parse_arguments([csv, "--inputs", inputs, "--benchmark", "block", "--ranks", ranks])
        self.plate = run_lammps.load_plate(self.args.inputs, self.args.models, "block")
        run_lammps.require_tools(self.args)
        self.open_mpi = run_lammps.is_open_mpi(self.args.mpirun)
        self.log_dir = os.path.abspath(self.args.inputs)

    def run(self, model, ranks):
        return run_lammps.run_one(self.args, self.plate, model, ranks, self.open_mpi, self.log_dir)

    def write(self, runs):
        """The fastest run of each model and rank count with the slowest loop beside it, written whole."""
        if os.path.exists(self.args.csv):
            os.unlink(self.args.csv)
        run_lammps.append_rows(self.args.csv, [run_lammps.fastest_row(done) for done in runs.values()])


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", required=True)
    parser.add_argument("--scenes", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--csv", required=True)
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--lammps-inputs", help="make_block_input.py's directory: LAMMPS in the same sweeps")
    parser.add_argument("--lammps-csv", help="where LAMMPS's rows go (with --lammps-inputs)")
    args = parser.parse_args(argv)
    if bool(args.lammps_inputs) != bool(args.lammps_csv):
        raise InputError("--lammps-inputs and --lammps-csv go together")
    try:
        threads = [int(t) for t in args.threads.split(",") if t.strip()]
    except ValueError:
        raise InputError(f"--threads: expected comma-separated positive integers (got {args.threads!r})")
    if not threads or min(threads) < 1 or args.repeats < 1:
        raise InputError("--threads and --repeats: expected positive integers")
    scene = os.path.join(args.scenes, "block.yaml")
    points = os.path.join(args.work, "block60", "points.vtp")
    preprocess(args, scene, points, BLOCK_SETS)
    lammps = LammpsBlock(args.lammps_inputs, threads, args.lammps_csv) if args.lammps_inputs else None
    runs = {name: {t: [] for t in threads} for name in EFFECT_SETS}
    lammps_runs = {}
    load = os.getloadavg()
    print(f"[block-3d] load average before the sweeps: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}", flush=True)
    for _ in range(args.repeats):
        for code, name in SWEEP:
            for t in threads:
                if code == "lammps":
                    if lammps:
                        lammps_runs.setdefault((name, t), []).append(lammps.run(name, t))
                    continue
                run_dir = os.path.join(args.work, "block60", f"{name.replace('+', '-')}-{t}t")
                runs[name][t].append(solve(args, scene, points, run_dir, EFFECT_SETS[name], t, BLOCK_SETS))
                shutil.rmtree(os.path.join(run_dir, "snapshots"), ignore_errors=True)
    rows = []
    for name in EFFECT_SETS:
        rows += fastest_rows("block60-3d", name, runs[name], "loop_wall_seconds")
    if lammps:
        lammps.write(lammps_runs)
    plate_scene = os.path.join(args.scenes, "plate.yaml")
    plate_points = os.path.join(args.work, "plate", "points.vtp")
    preprocess(args, plate_scene, plate_points, [])
    runs = {t: [] for t in threads}
    # Short runs (2-4 s): 5 repeats at least, the thread counts taking turns, against the VM's
    # drift of 10-40 % over minutes, which moves a ratio of two single runs by as much.
    for _ in range(max(args.repeats, PLATE_REPEATS)):
        for t in threads:
            run_dir = os.path.join(args.work, "plate", f"whole-run-{t}t")
            runs[t].append(solve(args, plate_scene, plate_points, run_dir, PLATE_EFFECTS, t, PLATE_SETS))
    rows += fastest_rows("plate-500", "+".join(PLATE_EFFECTS), runs, "wall_seconds")
    write_csv(args.csv, CSV_COLUMNS + ["start_up_seconds", "step_estimate_seconds", "mode_naming_seconds"], rows)
    return 0


if __name__ == "__main__":
    run_main(main)
