#!/usr/bin/python3
"""Runs the sweeps of the accuracy-cost study with mppm-accuracy, one process per run, and
writes every row to one CSV (atomically: a temporary file renamed at the end).

usage: sweeps.py MPPM_ACCURACY OUTPUT.csv [--quick] [--problems NAME[,NAME...]]

--problems keeps only the runs of the named problems (e.g. terzaghi): their rows can be made
without rerunning the whole study.

Defaults of every run: 2-D, horizon factor 3.05, time-step safety 0.8, stabilization G_s 0.1,
1 thread; each sweep changes one of them (the spacing sweeps also run at 2 threads).
OMP_WAIT_POLICY defaults to passive: on a machine shared with other jobs a spinning idle
OpenMP thread steals the working one's core (README.md, Performance).
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import atomic_open  # noqa: E402

DEFAULT = {"dimension": 2, "horizon-factor": 3.05, "safety": 0.8, "stabilization": 0.1, "threads": 1}
WAVES = ["p_wave", "shear_rotation_wave", "cutoff_frequency"]


def run(problem, sweep, resolution, **changes):
    options = dict(DEFAULT)
    options.update({key.replace("_", "-"): value for key, value in changes.items()})
    return (problem, sweep, resolution, options)


def full_study():
    runs = []
    # Spacing at a fixed horizon factor: wavelength 0.1 m resolved by 20..160 points (2-D), the
    # 30 mm layer by 10..640 rows (its error is first order); 3-D P wave (horizon factor 2.05)
    # by 12..32 points.
    for threads in (1, 2):
        for problem in WAVES:
            runs += [run(problem, "spacing", n, threads=threads) for n in (20, 40, 80, 160)]
        runs += [run("layer_shear", "spacing", n, threads=threads) for n in (10, 20, 40, 80, 160, 320, 640)]
        runs += [run("p_wave", "spacing", n, dimension=3, horizon_factor=2.05, threads=threads) for n in (12, 16, 24, 32)]
    # The other parameters at 80 points per wavelength (40 layer rows).
    for m in (2.05, 2.55, 3.05, 4.05, 5.0):
        runs += [run(p, "horizon_factor", 80, horizon_factor=m) for p in ("p_wave", "shear_rotation_wave")]
        runs.append(run("layer_shear", "horizon_factor", 40, horizon_factor=m))
    for s in (0.2, 0.4, 0.6, 0.8, 0.95):
        runs += [run(p, "safety", 80, safety=s) for p in WAVES]
    for g in (0.0, 0.05, 0.1, 0.2, 0.5, 1.0):
        runs += [run(p, "stabilization", 80, stabilization=g) for p in ("p_wave", "shear_rotation_wave")]
        runs.append(run("layer_shear", "stabilization", 40, stabilization=g))
    # The crack (rows across a 10 mm strip): its error is the breaking step's work, set by the
    # safety factor; the other sweeps at 20 rows and safety 0.2.
    runs += [run("crack_energy", "spacing", n, safety=0.2) for n in (16, 20, 24, 32)]
    runs += [run("crack_energy", "safety", 20, safety=s) for s in (0.1, 0.2, 0.4, 0.8)]
    runs += [run("crack_energy", "horizon_factor", 20, safety=0.2, horizon_factor=m) for m in (2.55, 3.05, 4.05)]
    runs += [run("crack_energy", "stabilization", 20, safety=0.2, stabilization=g) for g in (0.1, 0.2, 0.3)]
    # Terzaghi's consolidation: the 80 mm column of the pore-fluid test (80 rows there) by 10..160
    # rows; its steps grow like its rows (a fixed consolidation time); 1 thread (a column of at
    # most 1300 points). 160 rows, a level finer than the test's, shows the floor of its error.
    runs += [run("terzaghi", "spacing", n) for n in (10, 20, 40, 80, 160)]
    return runs


def quick_study():
    """Small enough for the test suite (well under a minute on 2 loaded cores)."""
    runs = []
    for threads in (1, 2):
        runs += [run("p_wave", "spacing", n, threads=threads) for n in (20, 40, 80)]
    runs += [run(p, "spacing", n) for p in ("shear_rotation_wave", "cutoff_frequency") for n in (20, 40, 80)]
    runs += [run("layer_shear", "spacing", n) for n in (10, 20, 40, 80)]
    runs += [run("p_wave", "spacing", n, dimension=3, horizon_factor=2.05) for n in (12, 16, 24)]
    runs += [run("p_wave", "horizon_factor", 40, horizon_factor=m) for m in (2.05, 5.0)]
    runs += [run("p_wave", "safety", 40, safety=s) for s in (0.4, 0.95)]
    runs += [run("p_wave", "stabilization", 40, stabilization=g) for g in (0.0, 0.5)]
    runs += [run("crack_energy", "safety", 20, safety=s) for s in (0.2, 0.4, 0.8)]
    runs += [run("terzaghi", "spacing", n) for n in (10, 20, 40)]
    return runs


def parse(arguments):
    """(program, output, quick, problems or None); exit 2 with the usage on anything else."""
    if len(arguments) < 2:
        sys.exit(__doc__)
    program, output, rest = arguments[0], arguments[1], arguments[2:]
    quick, problems = False, None
    while rest:
        if rest[0] == "--quick":
            quick, rest = True, rest[1:]
        elif rest[0] == "--problems" and len(rest) >= 2 and rest[1]:
            problems, rest = [p for p in rest[1].split(",") if p], rest[2:]
        else:
            print(__doc__, file=sys.stderr)
            sys.exit(2)
    return program, output, quick, problems


def main():
    program, output, quick, problems = parse(sys.argv[1:])
    runs = quick_study() if quick else full_study()
    if problems is not None:
        known = sorted({r[0] for r in runs})
        unknown = [p for p in problems if p not in known]
        if unknown:
            print(f"sweeps.py: --problems: unknown {', '.join(unknown)} (the study runs {', '.join(known)})",
                  file=sys.stderr)
            sys.exit(2)
        runs = [r for r in runs if r[0] in problems]
    header = subprocess.run([program, "--header"], check=True, capture_output=True, text=True).stdout
    environment = dict(os.environ)
    environment.setdefault("OMP_WAIT_POLICY", "passive")
    with atomic_open(output) as csv:
        csv.write(header)
        for index, (problem, sweep, resolution, options) in enumerate(runs, 1):
            command = [program, "--problem", problem, "--sweep", sweep, "--resolution", str(resolution)]
            for key, value in options.items():
                command += ["--" + key, str(value)]
            done = subprocess.run(command, capture_output=True, text=True, env=environment)
            if done.returncode != 0:  # sys.exit leaves the block: the temporary is removed
                sys.exit(f"sweeps.py: run {index} failed (exit {done.returncode}): {' '.join(command)}\n{done.stderr}")
            row = done.stdout.strip()
            csv.write(row + "\n")
            csv.flush()
            cells = row.split(",")
            print(f"[{index}/{len(runs)}] {problem} {sweep} resolution {resolution} "
                  f"{' '.join(f'{k}={v}' for k, v in options.items())}: error {cells[10] or '-'}, "
                  f"{cells[19] or '-'} s", flush=True)


if __name__ == "__main__":
    main()
